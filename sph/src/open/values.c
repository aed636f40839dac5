/* The value imposed by an open-boundary group at a point and time (sabre/sph_open.h): expressions
 * of t, x, y (, z), a table of time, the Poiseuille profiles of plates, circular and rectangular
 * ducts, the Stokes and solitary waves of sabre/sph_waves.h and the hydrostatic profile.
 * Conventions: docs/sph-case-file.md (`open_boundaries`) and docs/sph-solver.md §10. */
#include <gsl/gsl_math.h> /* M_PI */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "open/open_internal.h"
#include "sabre/common.h"
#include "sabre/sph_open.h"

static double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double sph_hydrostatic_pressure(const struct rmn_eos *e, double g, double d) {
  const double c2 = e->c0 * e->c0;
  if (e->isothermal) return e->b * expm1(g * d / c2);
  return e->b * expm1(e->xi / (e->xi - 1.0) * log1p((e->xi - 1.0) * g * d / c2));
}

/* ---------------------------------------------------------------------------------------------
 * Rectangular duct −a < y < a, −b < z < b: the Poisson problem Δf = −1, f = 0 on the walls, has
 *   f(y, z) = (a² − y²)/2 − (16 a²/π³) Σ_{n odd} (−1)^((n−1)/2) cos(nπy/2a) cosh(nπz/2a)
 *                                                  / (n³ cosh(nπb/2a)),
 * (the first term is the plates' profile: the series corrects it for the side walls z = ±b; it
 * converges like e^{−nπ(b−|z|)/2a}/n³), with the flux
 *   ∫∫ f = (4 a³ b/3) [1 − (192 a/(π⁵ b)) Σ_{n odd} tanh(nπb/2a)/n⁵]
 * (e.g. F. M. White, Viscous Fluid Flow, §3.3). The velocity is U_max f/f(0, 0). */
static double duct_series(double a, double b, double y, double z) {
  const double c = 16.0 * a * a / (M_PI * M_PI * M_PI);
  double sum = 0.0;
  for (long k = 0; k < 1000000L; k++) {
    const double n = 2.0 * (double)k + 1.0, q = n * M_PI / (2.0 * a);
    /* cosh(qz)/cosh(qb) without overflow */
    const double ratio = exp(q * (z - b)) * (1.0 + exp(-2.0 * q * z)) / (1.0 + exp(-2.0 * q * b));
    const double term = c * ratio / (n * n * n);
    sum += (k % 2 ? -1.0 : 1.0) * term * cos(q * y);
    if (term < 1e-16 * a * a) break;
  }
  return 0.5 * (a * a - y * y) - sum;
}

/* f by the representation whose series converges faster at (y, z): the one above, or the same
 * with the roles of the sides exchanged (they are equal; each is slow only next to the walls its
 * cosh runs towards). */
static double duct_f(double a, double b, double y, double z) {
  y = fabs(y);
  z = fabs(z);
  if (y >= a || z >= b) return 0.0;
  return (b - z) / a >= (a - y) / b ? duct_series(a, b, y, z) : duct_series(b, a, z, y);
}

static double duct_flux(double a, double b) {
  double sum = 0.0;
  for (long k = 0; k < 100000L; k++) {
    const double n = 2.0 * (double)k + 1.0, term = tanh(n * M_PI * b / (2.0 * a)) / pow(n, 5.0);
    sum += term;
    if (term < 1e-18) break;
  }
  return 4.0 * a * a * a * b / 3.0 * (1.0 - 192.0 * a / (pow(M_PI, 5.0) * b) * sum);
}

double sph_open_duct_umax(const struct sph_open_poiseuille *d) {
  if (d->shape != SPH_DUCT_RECTANGLE || !isnan(d->u_max)) return d->u_max;
  const double a = d->half[0], b = d->half[1];
  return d->flux * duct_f(a, b, 0.0, 0.0) / duct_flux(a, b);
}

int sph_open_source_init(struct sph_open_source *src, const struct sph_open_group *g, int dim,
                         const double gravity[3], const struct rmn_eos *eos, char *msg,
                         size_t msglen) {
  static const char *const vars[] = {"t", "x", "y", "z"};
  memset(src, 0, sizeof *src);
  src->group = g;
  src->dim = dim;
  src->eos = *eos;
  src->g = sqrt(dot3(gravity, gravity));
  if (src->g > 0.0)
    for (int k = 0; k < 3; k++) src->up[k] = -gravity[k] / src->g;
  /* side = up × direction */
  src->side[0] = src->up[1] * g->direction[2] - src->up[2] * g->direction[1];
  src->side[1] = src->up[2] * g->direction[0] - src->up[0] * g->direction[2];
  src->side[2] = src->up[0] * g->direction[1] - src->up[1] * g->direction[0];
  char err[1536];
  switch (g->source) {
    case SPH_OPEN_VALUE:
      for (int k = 0; k < g->ncomp; k++) {
        src->expr[k] = cmn_expr_compile(g->expr[k], 1 + dim, vars, err, sizeof err);
        if (!src->expr[k]) {
          snprintf(msg, msglen, "open boundary '%s': %s", g->name, err);
          sph_open_source_free(src);
          return -1;
        }
      }
      break;
    case SPH_OPEN_TABLE: {
      struct cmn_table t;
      if (cmn_table_read(g->table, &t, err, sizeof err) != 0 ||
          cmn_table_check_increasing(&t, 0, err, sizeof err) != 0) {
        snprintf(msg, msglen, "open boundary '%s': %s", g->name, err);
        cmn_table_free(&t);
        return -1;
      }
      src->nrows = t.nrows;
      src->ncols = t.ncols;
      src->table = cmn_malloc(t.nrows * (size_t)t.ncols * sizeof *src->table);
      memcpy(src->table, t.data, t.nrows * (size_t)t.ncols * sizeof *src->table);
      cmn_table_free(&t);
      break;
    }
    case SPH_OPEN_POISEUILLE:
      if (g->poiseuille.shape == SPH_DUCT_RECTANGLE) {
        src->duct_scale = sph_open_duct_umax(&g->poiseuille) /
                          duct_f(g->poiseuille.half[0], g->poiseuille.half[1], 0.0, 0.0);
      }
      break;
    case SPH_OPEN_STOKES5:
      if (sph_stokes5_init(&src->stokes5, &g->stokes5, err, sizeof err) != SPH_WAVE_SUCCESS) {
        snprintf(msg, msglen, "open boundary '%s': stokes5: %s", g->name, err);
        return -1;
      }
      break;
    case SPH_OPEN_SOLITARY:
      if (sph_solitary_init(&src->solitary, &g->solitary, err, sizeof err) != SPH_WAVE_SUCCESS) {
        snprintf(msg, msglen, "open boundary '%s': solitary: %s", g->name, err);
        return -1;
      }
      break;
    default:
      break;
  }
  return 0;
}

void sph_open_source_free(struct sph_open_source *src) {
  if (!src) return;
  for (int k = 0; k < 3; k++) cmn_expr_free(src->expr[k]);
  free(src->table);
  memset(src, 0, sizeof *src);
}

/* The start-up factor s²(3 − 2s), s = t/T clamped to [0, 1] (1 without a ramp). */
static double ramp_factor(double ramp, double t) {
  if (!(ramp > 0.0)) return 1.0;
  const double s = fmin(fmax(t / ramp, 0.0), 1.0);
  return s * s * (3.0 - 2.0 * s);
}

/* Centre-line speed times the profile at x (the duct's coordinates in the plane normal to n),
 * times the start-up ramp at t. */
static double poiseuille_speed(const struct sph_open_source *src, double t, const double x[3],
                               const double n[3]) {
  const struct sph_open_poiseuille *d = &src->group->poiseuille;
  const double f = ramp_factor(d->ramp, t);
  double r[3];
  for (int k = 0; k < 3; k++) r[k] = x[k] - d->center[k];
  const double rn = dot3(r, n);
  for (int k = 0; k < 3; k++) r[k] -= rn * n[k]; /* in the boundary's plane */
  if (d->shape != SPH_DUCT_RECTANGLE) {
    const double q = dot3(r, r) / (d->radius * d->radius);
    return q < 1.0 ? f * d->u_max * (1.0 - q) : 0.0;
  }
  /* axis: the side of half-width half[0], made normal to n; the other side along n × axis */
  double e1[3], e2[3];
  const double an = dot3(d->axis, n);
  for (int k = 0; k < 3; k++) e1[k] = d->axis[k] - an * n[k];
  const double len = sqrt(dot3(e1, e1));
  for (int k = 0; k < 3; k++) e1[k] /= len;
  e2[0] = n[1] * e1[2] - n[2] * e1[1];
  e2[1] = n[2] * e1[0] - n[0] * e1[2];
  e2[2] = n[0] * e1[1] - n[1] * e1[0];
  return f * src->duct_scale * duct_f(d->half[0], d->half[1], dot3(r, e1), dot3(r, e2));
}

/* A wave at x: velocity (global) and gauge pressure, at the point's height clamped to
 * [bed, surface]; returns the surface elevation (sph_open.h). */
double sph_open_source_wave(const struct sph_open_source *src, double t, const double x[3],
                            double *p, double u[3]) {
  const struct sph_open_group *g = src->group;
  const double X = dot3(x, g->direction), Y = dot3(x, src->side);
  double Z = dot3(x, src->up) - g->bed;
  struct sph_wave_point w;
  for (int pass = 0; pass < 2; pass++) {
    if (g->source == SPH_OPEN_STOKES5)
      sph_stokes5_eval(&src->stokes5, X - g->x0, Z, t, &w);
    else
      sph_solitary_eval(&src->solitary, X, Y, Z, t, &w);
    if (Z >= 0.0 && Z <= w.eta) break;
    Z = Z < 0.0 ? 0.0 : w.eta;
  }
  *p = fmax(w.p, 0.0) * (Z < w.eta); /* zero on the surface (the series' residual there) */
  for (int k = 0; k < 3; k++) u[k] = w.u * g->direction[k] + w.v * src->side[k] + w.w * src->up[k];
  return g->bed + w.eta;
}

void sph_open_source_eval(const struct sph_open_source *src, double t, const double x[3],
                          const double n[3], double level, struct sph_open_value *out) {
  const struct sph_open_group *g = src->group;
  const int dim = src->dim;
  double scalar = NAN, vec[3] = {0.0, 0.0, 0.0};
  int is_vector = 0;
  switch (g->source) {
    case SPH_OPEN_VALUE: {
      const double vals[4] = {t, x[0], x[1], x[2]};
      if (g->ncomp == 1) {
        scalar = cmn_expr_eval(src->expr[0], vals);
      } else {
        is_vector = 1;
        for (int k = 0; k < dim; k++) vec[k] = cmn_expr_eval(src->expr[k], vals);
      }
      break;
    }
    case SPH_OPEN_TABLE: {
      const size_t nc = (size_t)src->ncols;
      if (nc == 2) {
        scalar = cmn_interp_linear(src->nrows, src->table, src->table + 1, nc, t);
      } else {
        is_vector = 1;
        for (int k = 0; k < dim; k++)
          vec[k] = cmn_interp_linear(src->nrows, src->table, src->table + 1 + k, nc, t);
      }
      break;
    }
    case SPH_OPEN_POISEUILLE:
      scalar = poiseuille_speed(src, t, x, n);
      break;
    case SPH_OPEN_STOKES5:
    case SPH_OPEN_SOLITARY:
      is_vector = 1;
      sph_open_source_wave(src, t, x, &scalar, vec);
      break;
    case SPH_OPEN_HYDROSTATIC: {
      const double top = g->depth_measured || g->absorbing ? level : g->bed + g->depth;
      const double d = top - dot3(x, src->up);
      scalar = isfinite(top) && d > 0.0 ? sph_hydrostatic_pressure(&src->eos, src->g, d) : 0.0;
      break;
    }
  }
  /* The inflow's tangential velocity when the source gives none: the user's, without its normal
   * part. */
  if (!is_vector) {
    const double tn = dot3(g->tangential, n);
    for (int k = 0; k < 3; k++) vec[k] = g->tangential[k] - tn * n[k];
  }
  if (g->imposed == RMN_IMPOSE_PRESSURE) {
    out->p = scalar;
    out->un = NAN;
    for (int k = 0; k < 3; k++) out->u[k] = vec[k];
  } else if (is_vector) {
    out->p = NAN;
    out->un = dot3(vec, n);
    for (int k = 0; k < 3; k++) out->u[k] = vec[k];
  } else {
    out->p = NAN;
    out->un = scalar;
    for (int k = 0; k < 3; k++) out->u[k] = vec[k] + scalar * n[k];
  }
  for (int k = dim; k < 3; k++) out->u[k] = 0.0;
}
