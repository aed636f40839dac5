/* The semi-discrete right-hand side of docs/theory.md §2: primitives, ghosts, limited slopes, face
 * fluxes (interior: numerical flux; ends: wall, periodic, transmissive or open), flux differences.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include "internal.h"

void fv1d_set_error(struct fv1d_solver *s, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(s->err, sizeof s->err, fmt, ap);
  va_end(ap);
}

/* Face state of cell i on its right (+½) or left (−½) face. */
static inline void face_state(const struct fv1d_solver *s, long i, double half, double *rho,
                              double *u) {
  const long g = FV1D_GHOST;
  *rho = s->rho[g + i] + half * s->srho[g + i];
  *u = s->u[g + i] + half * s->su[g + i];
}

static int interior_flux(struct fv1d_solver *s, long j, double f[2]) {
  double rl, ul, rr, ur;
  face_state(s, j - 1, 0.5, &rl, &ul);
  face_state(s, j, -0.5, &rr, &ur);
  return fv1d_flux_numerical(s->par.flux, &s->par.eos, &s->par.rmn, s->ws, rl, ul, rr, ur, f);
}

/* End face `side` (0: face 0 at x_min, 1: face n at x_max); fills f and s->bnd[side]. */
static int end_flux(struct fv1d_solver *s, int side, double t, double f[2]) {
  const struct rmn_eos *eos = &s->par.eos;
  const long n = s->n, g = FV1D_GHOST;
  struct fv1d_boundary_state *b = &s->bnd[side];
  int status = RMN_SUCCESS;
  switch (s->par.bc[side].type) {
    case FV1D_BC_PERIODIC:
      /* one flux for faces 0 and n, so that what leaves one end enters the other bit for bit */
      status = interior_flux(s, n, f);
      b->rho = 0.5 * (s->rho[g + n - 1] + s->rho[g]);
      b->u = 0.5 * (s->u[g + n - 1] + s->u[g]);
      b->p = rmn_eos_pressure(eos, b->rho);
      break;
    case FV1D_BC_WALL: {
      double rho, u;
      face_state(s, side == 0 ? 0 : n - 1, side == 0 ? -0.5 : 0.5, &rho, &u);
      status = side == 0
                   ? fv1d_flux_numerical(s->par.flux, eos, &s->par.rmn, s->ws, rho, -u, rho, u, f)
                   : fv1d_flux_numerical(s->par.flux, eos, &s->par.rmn, s->ws, rho, u, rho, -u, f);
      f[0] = 0.0; /* no mass crosses a wall, exactly */
      b->u = 0.0;
      b->p = f[1];
      b->rho = rmn_eos_density(eos, f[1]);
      break;
    }
    case FV1D_BC_TRANSMISSIVE: {
      long i = side == 0 ? 0 : n - 1;
      b->rho = s->rho[g + i];
      b->u = s->u[g + i];
      b->p = rmn_eos_pressure(eos, b->rho);
      fv1d_flux_physical(eos, b->rho, b->u, f);
      break;
    }
    case FV1D_BC_OPEN:
      status = fv1d_boundary_open_flux(s, side, t, f);
      break;
  }
  b->flux[0] = f[0];
  b->flux[1] = f[1];
  return status;
}

int fv1d_rhs_eval(struct fv1d_solver *s, double t, const double *y, double *ydot) {
  const long n = s->n, g = FV1D_GHOST;
  const struct rmn_eos *eos = &s->par.eos;
  for (long i = 0; i < n; ++i) {
    double rho = y[2 * i], m = y[2 * i + 1];
    if (!(rho > 0.0) || !isfinite(rho) || !isfinite(m)) {
      fv1d_set_error(s, "t = %.9g s: cell %ld (x = %.9g m) has density %g and momentum %g", t, i,
                     fv1d_solver_x(s, i), rho, m);
      return 1;
    }
    s->rho[g + i] = rho;
    s->u[g + i] = m / rho;
  }
  fv1d_recon_ghosts(s);
  fv1d_recon_slopes(s);

  double *face = s->face; /* face j (between cells j−1 and j) holds face[2j], face[2j+1] */
  for (long j = 1; j < n; ++j) {
    int status = interior_flux(s, j, face + 2 * j);
    if (status != RMN_SUCCESS) {
      fv1d_set_error(s, "t = %.9g s: Riemann problem at face %ld (x = %.9g m): %s", t, j,
                     s->par.x_min + j * s->dx, rmn_strerror(status));
      return 1;
    }
  }
  for (int side = 0; side < 2; ++side) {
    int status = end_flux(s, side, t, face + 2 * (side == 0 ? 0 : n));
    if (status != RMN_SUCCESS) {
      fv1d_set_error(s, "t = %.9g s: %s end (%s): %s (%s)", t, side == 0 ? "left" : "right",
                     fv1d_bc_names[s->par.bc[side].type], rmn_strerror(status),
                     rmn_status_name(status));
      return 1;
    }
  }

#ifdef SABRE_DEBUG_CHECKS
  /* every face flux finite; periodic ends share one flux bit for bit */
  for (long j = 0; j <= n; ++j) {
    if (!isfinite(face[2 * j]) || !isfinite(face[2 * j + 1]))
      cmn_error("t = %.9g s: face %ld has a non-finite flux (%g, %g)", t, j, face[2 * j],
                face[2 * j + 1]);
  }
  if (s->par.bc[0].type == FV1D_BC_PERIODIC &&
      (face[0] != face[2 * n] || face[1] != face[2 * n + 1]))
    cmn_error("periodic end fluxes differ");
#endif
  const double inv_dx = 1.0 / s->dx;
  for (long i = 0; i < n; ++i) {
    ydot[2 * i] = (face[2 * i] - face[2 * i + 2]) * inv_dx;
    ydot[2 * i + 1] = (face[2 * i + 1] - face[2 * i + 3]) * inv_dx;
  }
  /* time integrals of the end fluxes, integrated by the same RK weights as the cells, so that
   * mass(t) − mass(0) = ∫F_left − ∫F_right holds to round-off */
  double *q = ydot + 2 * n;
  for (int side = 0; side < 2; ++side) {
    const struct fv1d_boundary_state *b = &s->bnd[side];
    q[3 * side + 0] = b->flux[0];
    q[3 * side + 1] = b->flux[1];
    q[3 * side + 2] =
        s->par.bc[side].type == FV1D_BC_WALL ? 0.0 : fv1d_energy_flux(eos, b->rho, b->u);
  }
  if (s->par.bc[0].type == FV1D_BC_PERIODIC) q[2] = q[5];
  return 0;
}

double fv1d_max_wave_speed(const struct fv1d_solver *s, const double *y) {
  double amax = 0.0;
  for (long i = 0; i < s->n; ++i) {
    double rho = y[2 * i], u = y[2 * i + 1] / rho;
    double a = fabs(u) + rmn_eos_sound_speed(&s->par.eos, rho);
    if (a > amax || isnan(a)) amax = a;
  }
  return amax;
}

void fv1d_totals(const struct fv1d_solver *s, const double *y, double totals[3]) {
  double mass = 0.0, mom = 0.0, energy = 0.0;
  for (long i = 0; i < s->n; ++i) {
    double rho = y[2 * i], m = y[2 * i + 1];
    mass += rho;
    mom += m;
    energy += 0.5 * m * m / rho + fv1d_internal_energy(&s->par.eos, rho);
  }
  totals[0] = mass * s->dx;
  totals[1] = mom * s->dx;
  totals[2] = energy * s->dx;
}
