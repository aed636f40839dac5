/* MUSCL reconstruction on the primitive variables (ρ, u): ghost cells from the boundary types and
 * limited slopes (minmod, monotonised central). docs/theory.md §2. */
#include <math.h>

#include "internal.h"

const char *const fv1d_recon_names[] = {"none", "minmod", "mc", NULL};

static double minmod2(double a, double b) {
  if (a * b <= 0.0) return 0.0;
  return fabs(a) < fabs(b) ? a : b;
}

double fv1d_recon_slope(enum fv1d_recon kind, double d_minus, double d_plus) {
  switch (kind) {
    case FV1D_RECON_NONE:
      return 0.0;
    case FV1D_RECON_MINMOD:
      return minmod2(d_minus, d_plus);
    case FV1D_RECON_MC: {
      /* van Leer's monotonised central slope: minmod(2 d−, ½(d− + d+), 2 d+). */
      if (d_minus * d_plus <= 0.0) return 0.0;
      double m = fmin(fmin(2.0 * fabs(d_minus), 2.0 * fabs(d_plus)), 0.5 * fabs(d_minus + d_plus));
      return d_minus > 0.0 ? m : -m;
    }
  }
  return 0.0;
}

void fv1d_recon_ghosts(struct fv1d_solver *s) {
  const long n = s->n, g = FV1D_GHOST;
  double *rho = s->rho + g, *u = s->u + g; /* rho[i] is cell i; ghosts at −g..−1 and n..n+g−1 */
  for (long k = 0; k < g; ++k) {
    long gl = -1 - k, gr = n + k; /* ghost cells, k-th away from each end */
    long il = (k < n) ? k : n - 1, ir = (k < n) ? n - 1 - k : 0;
    switch (s->par.bc[0].type) {
      case FV1D_BC_PERIODIC:
        rho[gl] = rho[n - 1 - (k % n)], u[gl] = u[n - 1 - (k % n)];
        break;
      case FV1D_BC_WALL:
        rho[gl] = rho[il], u[gl] = -u[il];
        break;
      case FV1D_BC_TRANSMISSIVE:
      case FV1D_BC_OPEN: /* zero gradient: the open face flux uses the cell average anyway */
        rho[gl] = rho[0], u[gl] = u[0];
        break;
    }
    switch (s->par.bc[1].type) {
      case FV1D_BC_PERIODIC:
        rho[gr] = rho[k % n], u[gr] = u[k % n];
        break;
      case FV1D_BC_WALL:
        rho[gr] = rho[ir], u[gr] = -u[ir];
        break;
      case FV1D_BC_TRANSMISSIVE:
      case FV1D_BC_OPEN:
        rho[gr] = rho[n - 1], u[gr] = u[n - 1];
        break;
    }
  }
}

void fv1d_recon_slopes(struct fv1d_solver *s) {
  const long n = s->n, g = FV1D_GHOST;
  const double *rho = s->rho + g, *u = s->u + g;
  double *srho = s->srho + g, *su = s->su + g;
  const enum fv1d_recon kind = s->par.recon;
  if (kind == FV1D_RECON_NONE) {
    for (long i = -1; i <= n; ++i) srho[i] = 0.0, su[i] = 0.0;
    return;
  }
  for (long i = -1; i <= n; ++i) {
    srho[i] = fv1d_recon_slope(kind, rho[i] - rho[i - 1], rho[i + 1] - rho[i]);
    su[i] = fv1d_recon_slope(kind, u[i] - u[i - 1], u[i + 1] - u[i]);
  }
}
