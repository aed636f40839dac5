/* Solver lifecycle, mesh and the initial condition (cell averages). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

struct fv1d_solver *fv1d_solver_create(const struct fv1d_params *params) {
  struct fv1d_solver *s = cmn_calloc(1, sizeof *s);
  s->par = *params;
  s->n = params->cells;
  s->dx = (params->x_max - params->x_min) / (double)params->cells;
  s->t = 0.0;
  const long nw = s->n + 2 * FV1D_GHOST;
  s->y = cmn_calloc((size_t)(2 * s->n + FV1D_NFLUXINT), sizeof(double));
  s->rho = cmn_calloc((size_t)nw, sizeof(double));
  s->u = cmn_calloc((size_t)nw, sizeof(double));
  s->srho = cmn_calloc((size_t)nw, sizeof(double));
  s->su = cmn_calloc((size_t)nw, sizeof(double));
  s->face = cmn_calloc((size_t)(2 * (s->n + 1)), sizeof(double));
  s->ws = rmn_workspace_alloc();
  if (!s->ws) cmn_error("cannot allocate the riemann/ workspace");
  fv1d_initial_apply(s);
  return s;
}

void fv1d_solver_destroy(struct fv1d_solver *s) {
  if (!s) return;
  rmn_workspace_free(s->ws);
  free(s->y);
  free(s->rho);
  free(s->u);
  free(s->srho);
  free(s->su);
  free(s->face);
  free(s);
}

long fv1d_solver_cells(const struct fv1d_solver *s) { return s->n; }
double fv1d_solver_dx(const struct fv1d_solver *s) { return s->dx; }
double fv1d_solver_x(const struct fv1d_solver *s, long i) {
  return s->par.x_min + ((double)i + 0.5) * s->dx;
}
double fv1d_solver_time(const struct fv1d_solver *s) { return s->t; }
double *fv1d_solver_state(struct fv1d_solver *s) { return s->y; }
long fv1d_solver_state_length(const struct fv1d_solver *s) { return 2 * s->n + FV1D_NFLUXINT; }
const char *fv1d_solver_error(const struct fv1d_solver *s) { return s->err; }
const struct fv1d_boundary_state *fv1d_solver_boundary(const struct fv1d_solver *s, int side) {
  return &s->bnd[side != 0];
}

void fv1d_initial_point(const struct fv1d_params *p, double x, double *rho, double *u) {
  const struct fv1d_initial *ini = &p->initial;
  *rho = ini->rho;
  *u = ini->u;
  if (ini->ntable > 0) {
    *rho = cmn_interp_linear(ini->ntable, ini->table_x, ini->table_rho, 1, x);
    *u = cmn_interp_linear(ini->ntable, ini->table_x, ini->table_u, 1, x);
  }
  if (ini->rho_expr) *rho = cmn_expr_eval(ini->rho_expr, &x);
  if (ini->p_expr) *rho = rmn_eos_density(&p->eos, cmn_expr_eval(ini->p_expr, &x));
  if (ini->u_expr) *u = cmn_expr_eval(ini->u_expr, &x);
}

void fv1d_initial_apply(struct fv1d_solver *s) {
  const struct fv1d_params *p = &s->par;
  /* 3-point Gauss–Legendre on each cell: exact cell averages of mass and momentum for profiles
   * up to degree 5, so smooth initial data do not limit the observed order. */
  static const double gx[3] = {-0.7745966692414833770358531, 0.0, 0.7745966692414833770358531};
  static const double gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  for (long i = 0; i < s->n; ++i) {
    double xc = fv1d_solver_x(s, i);
    double mass = 0.0, mom = 0.0;
    for (int q = 0; q < 3; ++q) {
      double rho, u;
      fv1d_initial_point(p, xc + 0.5 * s->dx * gx[q], &rho, &u);
      mass += gw[q] * rho;
      mom += gw[q] * rho * u;
    }
    for (size_t r = 0; r < p->initial.nregions; ++r) { /* later regions win */
      const struct fv1d_region *reg = &p->initial.regions[r];
      if (xc >= reg->from && xc < reg->to) {
        mass = reg->rho;
        mom = reg->rho * reg->u;
      }
    }
    s->y[2 * i] = mass;
    s->y[2 * i + 1] = mom;
  }
  for (int k = 0; k < FV1D_NFLUXINT; ++k) s->y[2 * s->n + k] = 0.0;
  s->t = 0.0;
}
