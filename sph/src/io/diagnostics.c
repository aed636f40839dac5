/*
 * Global diagnostics (diagnostics.csv), pressure probes by Shepard interpolation, free-surface
 * gauges, forces on the wall groups, and the skew-adjoint defect M(27).
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdlib.h>

#include "operators/pair.h"
#include "operators/pressure.h"
#include "sabre/common.h"
#include "sabre/sph_solver.h"
#include "sabre/sph_walls.h"

double sph_internal_energy(const struct rmn_eos *e, double rho) {
  const double r = rho / e->rho0, c2 = e->c0 * e->c0;
  if (e->isothermal) return c2 * (log(r) + 1.0 / r - 1.0);
  /* ∫ b ((ρ/ρ0)^ξ − 1)/ρ² dρ = b/ρ0 [ (r^(ξ−1) − 1)/(ξ − 1) + 1/r − 1 ] */
  return e->b / e->rho0 * (expm1((e->xi - 1.0) * log(r)) / (e->xi - 1.0) + 1.0 / r - 1.0);
}

void sph_solver_diagnostics(const struct sph_solver *sv, struct sph_diagnostics *d) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID], *v = &sv->sys.part[SPH_KIND_VERTEX];
  const double *g = sv->cfg.gravity;
  double mass = 0.0, kin = 0.0, pot = 0.0, inte = 0.0, vmax = 0.0, dmax = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    double v2 = 0.0, gx = 0.0;
    for (int c = 0; c < 3; c++) {
      v2 += f->v[c][a] * f->v[c][a];
      gx += g[c] * f->x[c][a];
    }
    mass += f->mass[a];
    kin += 0.5 * f->mass[a] * v2;
    pot -= f->mass[a] * gx;
    inte += f->mass[a] * sph_internal_energy(&sv->eos, f->rho[a]);
    vmax = fmax(vmax, sqrt(v2));
    dmax = fmax(dmax, fabs(f->rho[a] / sv->cfg.rho0 - 1.0));
  }
  /* the wall vertices at their set-up masses: with numerics.wall_vertex_mass: density their mass
   * follows the wall layer's density, which moves no mass between particles (docs/sph-solver.md
   * §4); open vertices at the masses they carry (§10) */
  for (size_t i = 0; i < v->n; i++)
    mass += (v->flags[i] & SPH_FLAG_OPEN) ? v->mass[i] : v->wall_mass[i];
  d->time = sv->time;
  d->dt = sv->dt;
  d->count = (double)f->n;
  d->mass = mass;
  d->kinetic = kin;
  d->potential = pot;
  d->internal = inte;
  d->max_speed = vmax;
  d->max_drho = dmax;
}

/* Naive loops: probes and gauges are few and evaluated at output rows only. */
double sph_solver_probe_pressure(const struct sph_solver *sv, const double *x) {
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const double support = sph_kernel_support(&sv->kernel);
  double alpha = 0.0, sum = 0.0;
  for (size_t b = 0; b < f->n; b++) {
    const double xb[3] = {f->x[0][b], f->x[1][b], f->x[2][b]};
    double d[3];
    sph_domain_delta(&s->domain, xb, x, d);
    double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (r >= support) continue;
    double vw = f->mass[b] / f->rho[b] * sph_kernel_w_inline(&sv->kernel, r);
    alpha += vw;
    sum += vw * rmn_eos_pressure(&sv->eos, f->rho[b]);
  }
  return alpha > 0.0 ? sum / alpha : NAN;
}

void sph_gauge_up(const double gravity[3], double up[3]) {
  const double *g = gravity;
  const double gn = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  up[0] = gn > 0 ? -g[0] / gn : 0;
  up[1] = gn > 0 ? -g[1] / gn : 1;
  up[2] = gn > 0 ? -g[2] / gn : 0;
}

double sph_solver_gauge(const struct sph_solver *sv, const double *x) {
  /* Highest fluid particle (along −g) within h of the gauge's vertical line, plus Δr/2 (h: at
   * least one particle of the top layer is always that close, even when the layer shifts). */
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  double up[3];
  sph_gauge_up(sv->cfg.gravity, up);
  double top = -INFINITY;
  for (size_t b = 0; b < f->n; b++) {
    const double xb[3] = {f->x[0][b], f->x[1][b], f->x[2][b]};
    double d[3];
    sph_domain_delta(&s->domain, x, xb, d);
    double dz = d[0] * up[0] + d[1] * up[1] + d[2] * up[2];
    double lat2 = 0.0;
    for (int c = 0; c < 3; c++) lat2 += (d[c] - dz * up[c]) * (d[c] - dz * up[c]);
    if (lat2 > s->h * s->h) continue;
    top = fmax(top, xb[0] * up[0] + xb[1] * up[1] + xb[2] * up[2]);
  }
  return isfinite(top) ? top + 0.5 * s->dr : NAN;
}

/*
 * Kernel-sum level (probes.gauges' levelI columns; docs/sph-solver.md §6): along the gauge's
 * vertical line, the fill fraction
 *   c(s) = Σ_F V_b w(x(s) − x_b) / (γ(x(s)) − Σ_V V_v w(x(s) − x_v)),
 * the fluid's share of the part of the kernel that fluid can occupy (γ takes out the walls, the
 * vertex sum the wall layer the first row does not cover). On a lattice whose top row is Δr/2
 * below H, the particles below and the lattice sites above are mirror images about H, so c = 1/2
 * there. The level is the highest s with c(s) = 1/2: scanned down from Δr above the highest fluid
 * particle within the support of the line, in steps of Δr/4, then bracketed by GSL's Brent solver.
 */
struct level_line {
  const struct sph_kernel *k;
  double base[3], up[3];   /* the line: base + s up */
  size_t nf, nv, ne;       /* fluid, vertices and elements within the support of the line */
  double *fz, *fr2, *fvol; /* fluid: height along up, squared lateral distance, volume */
  double *vz, *vr2, *vvol; /* vertices: the same */
  struct sph_wall_element *e;
};

static double level_fill(double s, void *data) {
  const struct level_line *L = data;
  double fluid = 0.0, layer = 0.0, gamma = 1.0, grad[3];
  for (size_t i = 0; i < L->nf; i++)
    fluid +=
        L->fvol[i] * sph_kernel_w_inline(L->k, sqrt(L->fr2[i] + (L->fz[i] - s) * (L->fz[i] - s)));
  if (fluid == 0.0) return 0.0;
  for (size_t i = 0; i < L->nv; i++)
    layer +=
        L->vvol[i] * sph_kernel_w_inline(L->k, sqrt(L->vr2[i] + (L->vz[i] - s) * (L->vz[i] - s)));
  const double x[3] = {L->base[0] + s * L->up[0], L->base[1] + s * L->up[1],
                       L->base[2] + s * L->up[2]};
  if (L->ne > 0 && sph_gamma_eval(L->k, x, L->ne, L->e, &gamma, grad) != 0) return NAN;
  const double room = gamma - layer;
  return room > 0.0 ? fluid / room : 1.0; /* no room left: the fluid fills it */
}

static double level_minus_half(double s, void *data) { return level_fill(s, data) - 0.5; }

/* The root of c − 1/2 in [lo, hi] (c(lo) ≥ 1/2 > c(hi)) to 1e-9 Δr; NaN if GSL fails. */
static double level_root(struct level_line *L, double lo, double hi, double dr) {
  gsl_function fn = {level_minus_half, L};
  if (level_minus_half(lo, L) == 0.0) return lo;
  gsl_error_handler_t *handler = gsl_set_error_handler_off();
  gsl_root_fsolver *rs = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  double root = NAN;
  if (rs && gsl_root_fsolver_set(rs, &fn, lo, hi) == GSL_SUCCESS)
    for (int it = 0; it < 100; it++) {
      if (gsl_root_fsolver_iterate(rs) != GSL_SUCCESS) break;
      const double a = gsl_root_fsolver_x_lower(rs), b = gsl_root_fsolver_x_upper(rs);
      if (gsl_root_test_interval(a, b, 1e-9 * dr, 0.0) == GSL_SUCCESS) {
        root = gsl_root_fsolver_root(rs);
        break;
      }
    }
  gsl_root_fsolver_free(rs);
  gsl_set_error_handler(handler);
  return root;
}

/* The squared distance of d from the line along up, and d's component along up. */
static double lateral2(const double d[3], const double up[3], double *along) {
  *along = d[0] * up[0] + d[1] * up[1] + d[2] * up[2];
  double r2 = 0.0;
  for (int c = 0; c < 3; c++) r2 += (d[c] - *along * up[c]) * (d[c] - *along * up[c]);
  return r2;
}

/* The particles of kind `kind` within the support of the line: heights, squared lateral
 * distances and volumes m/ρ; returns how many. */
static size_t level_parts(const struct sph_solver *sv, enum sph_kind kind, const double base[3],
                          const double up[3], double **z, double **r2, double **vol) {
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *p = &s->part[kind];
  const double support = sph_kernel_support(&sv->kernel);
  *z = cmn_malloc((p->n + 1) * sizeof **z);
  *r2 = cmn_malloc((p->n + 1) * sizeof **r2);
  *vol = cmn_malloc((p->n + 1) * sizeof **vol);
  size_t n = 0;
  for (size_t b = 0; b < p->n; b++) {
    const double xb[3] = {p->x[0][b], p->x[1][b], p->x[2][b]};
    double d[3], along;
    sph_domain_delta(&s->domain, base, xb, d);
    const double lat2 = lateral2(d, up, &along);
    if (lat2 >= support * support || !(p->rho[b] > 0.0)) continue;
    (*z)[n] = along;
    (*r2)[n] = lat2;
    (*vol)[n++] = p->mass[b] / p->rho[b];
  }
  return n;
}

double sph_solver_level(const struct sph_solver *sv, const double *x) {
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT];
  const double support = sph_kernel_support(&sv->kernel), dr = s->dr;
  struct level_line L = {.k = &sv->kernel};
  sph_gauge_up(sv->cfg.gravity, L.up);
  const double x0 = x[0] * L.up[0] + x[1] * L.up[1] + x[2] * L.up[2];
  for (int c = 0; c < 3; c++) L.base[c] = x[c] - x0 * L.up[c];
  L.nf = level_parts(sv, SPH_KIND_FLUID, L.base, L.up, &L.fz, &L.fr2, &L.fvol);
  L.nv = level_parts(sv, SPH_KIND_VERTEX, L.base, L.up, &L.vz, &L.vr2, &L.vvol);
  /* the elements that may come within the support of the line (bounding circle about the
   * centroid, lateral distance) */
  L.e = cmn_malloc((sg->n + 1) * sizeof *L.e);
  L.ne = 0;
  for (size_t j = 0; j < sg->n; j++) {
    struct sph_wall_element *e = &L.e[L.ne];
    sph_segment_vertices(s, j, L.base, e->x);
    double mid[3] = {0.0, 0.0, 0.0}, reach = 0.0, along;
    for (int k = 0; k < s->dim; k++)
      for (int c = 0; c < 3; c++) mid[c] += e->x[k][c] / s->dim;
    for (int k = 0; k < s->dim; k++) {
      double r2 = 0.0;
      for (int c = 0; c < 3; c++) r2 += (e->x[k][c] - mid[c]) * (e->x[k][c] - mid[c]);
      reach = fmax(reach, sqrt(r2));
    }
    const double d[3] = {mid[0] - L.base[0], mid[1] - L.base[1], mid[2] - L.base[2]};
    if (sqrt(lateral2(d, L.up, &along)) - reach >= support) continue;
    for (int c = 0; c < 3; c++) e->normal[c] = sg->normal[c][j];
    L.ne++;
  }
  double level = NAN;
  if (L.nf > 0) {
    double top = -INFINITY, bottom = INFINITY;
    for (size_t i = 0; i < L.nf; i++) {
      top = fmax(top, L.fz[i]);
      bottom = fmin(bottom, L.fz[i]);
    }
    /* a start above the surface (c < 1/2; c = 0 from a support above the highest particle) */
    double hi = top + dr, chi = level_fill(hi, &L);
    while (chi >= 0.5 && hi < top + support) chi = level_fill(hi += 0.5 * dr, &L);
    /* down to the first s with c ≥ 1/2 (none below the lowest particle minus the support) */
    double lo = hi, clo = chi;
    while (isfinite(clo) && clo < 0.5 && lo > bottom - support)
      clo = level_fill(lo -= 0.25 * dr, &L);
    if (isfinite(chi) && isfinite(clo) && clo >= 0.5 && chi < 0.5)
      level = level_root(&L, lo, hi, dr);
  }
  free(L.fz), free(L.fr2), free(L.fvol), free(L.vz), free(L.vr2), free(L.vvol), free(L.e);
  return level;
}

void sph_solver_wall_forces(const struct sph_solver *sv, double (*out)[3]) {
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID], *v = &s->part[SPH_KIND_VERTEX];
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT];
  const struct sph_nlist *nlv = &sv->nb.list[SPH_KIND_VERTEX],
                         *nls = &sv->nb.list[SPH_KIND_SEGMENT];
  for (int g = 0; g < sv->cfg.nforces; g++) out[g][0] = out[g][1] = out[g][2] = 0.0;
  /* Pressure: the integral of the segment pressure over the group, −Σ_s p_s |s| n_s (M §8). The
   * momentum equation's pressure terms are not used: with γ_a ≠ 1 the fluid–fluid pair terms do
   * not cancel near walls, so their wall parts alone would not be the force on the wall. */
  for (size_t j = 0; j < sg->n; j++) {
    int g = sv->seg_group[j];
    if (g < 0) continue;
    const double ps = sv->sys.part[SPH_KIND_SEGMENT].p[j] * sg->measure[j];
    for (int c = 0; c < 3; c++) out[g][c] -= ps * sg->normal[c][j];
  }
  if (!(sv->cfg.nu > 0.0)) return;
  /* Shear: minus the wall contributions of Lap^γ to Σ m_a dv_a/dt (the wall shear stress of
   * M 19–20 on the segments, and the vertices' volume terms). */
  const struct sph_wall_shear shear = {sv->mu[SPH_KIND_FLUID], sv->mu[SPH_KIND_SEGMENT],
                                       0.5 * s->dr};
  for (size_t a = 0; a < f->n; a++) {
    const double fac = f->mass[a] / (f->rho[a] * f->gamma[a]);
    const double mua = sv->mu[SPH_KIND_FLUID][a];
    for (size_t q = nlv->offset[a]; q < nlv->offset[a + 1]; q++) {
      size_t b = nlv->index[q];
      int g = sv->vert_group[b];
      struct sph_pair pr;
      if (g < 0 || !sph_pair_eval(&sv->kernel, s, f, a, v, b, &pr) || pr.dist == 0.0) continue;
      const double mub = sv->mu[SPH_KIND_VERTEX][b];
      const double bbar = mua + mub > 0 ? 2.0 * mua * mub / (mua + mub) : 0.0;
      const double tv = v->mass[b] / v->rho[b] * 2.0 * bbar * pr.dwdr_over_r;
      for (int c = 0; c < 3; c++) out[g][c] -= fac * tv * (f->v[c][a] - v->v[c][b]);
    }
    for (size_t q = nls->offset[a]; q < nls->offset[a + 1]; q++) {
      int g = sv->seg_group[nls->index[q]];
      if (g < 0) continue;
      double mag = 0.0;
      for (int c = 0; c < 3; c++) mag += sv->nb.grad_gamma_as[c][q] * sv->nb.grad_gamma_as[c][q];
      if (mag == 0.0) continue; /* beyond the support: the pair is in the list only by its skin */
      mag = sqrt(mag);
      double fl[3];
      sph_wall_shear_flux(s, &sv->nb, &shear, a, q, fl);
      for (int c = 0; c < 3; c++) out[g][c] += fac * fl[c] * mag;
    }
  }
}

double sph_skew_adjoint_defect(const struct sph_solver *sv, const double *const fk[SPH_NKINDS],
                               const double *const B[SPH_NKINDS][3]) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const struct sph_op op = {&sv->sys, &sv->kernel, &sv->nb, 0};
  double sum = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    double g[3];
    sph_op_grad(&op, sv->cfg.grad_k, fk, a, g);
    double div = sph_op_div(&op, sv->cfg.grad_k, B, a);
    double gb = 0.0;
    for (int c = 0; c < 3; c++) gb += g[c] * (B[SPH_KIND_FLUID][c] ? B[SPH_KIND_FLUID][c][a] : 0.0);
    sum += f->mass[a] / f->rho[a] * (gb + fk[SPH_KIND_FLUID][a] * div);
  }
  return sum;
}
