/* Moving-shock Rankine–Hugoniot relations across the λ+1 wave (docs/theory.md §1.1, beyond J
 * 31–32): ρ2 (u2 − S) = ρ_i (u_i − S),   ρ2 u2 (u2 − S) + p2 = ρ_i u_i (u_i − S) + p_i, solved by
 * Newton through GSL multiroot with the analytic Jacobian, plus the solver workspace. */
#include <math.h>
#include <stdlib.h>

#include "sabre/riemann.h"
#include "workspace.h"

/* The system is solved in the increments δu = u2 − u_i, w = S − u_i and, for an imposed velocity,
 * δρ = ρ2 − ρ_i. Subtracting u_i times the mass equation from the momentum equation gives the
 * equivalent, Galilean-invariant pair
 *     F0 = ρ2 δu − δρ w = 0,      F1 = ρ2 δu (δu − w) + δp = 0,
 * whose terms all vanish with the shock strength, so weak shocks keep full relative precision
 * (the literal form loses it to cancellation of O(ρ c) terms). */

/* Imposed pressure: unknowns x = (δu, w); δρ and δp known. */
static int rh_pressure_f(const gsl_vector *x, void *params, gsl_vector *f) {
  const struct rmn_rh_data *d = params;
  double du = gsl_vector_get(x, 0), w = gsl_vector_get(x, 1);
  double rho2 = d->rho_i + d->drho;
  gsl_vector_set(f, 0, rho2 * du - d->drho * w);
  gsl_vector_set(f, 1, rho2 * du * (du - w) + d->dp);
  return GSL_SUCCESS;
}

static int rh_pressure_df(const gsl_vector *x, void *params, gsl_matrix *jac) {
  const struct rmn_rh_data *d = params;
  double du = gsl_vector_get(x, 0), w = gsl_vector_get(x, 1);
  double rho2 = d->rho_i + d->drho;
  gsl_matrix_set(jac, 0, 0, rho2);
  gsl_matrix_set(jac, 0, 1, -d->drho);
  gsl_matrix_set(jac, 1, 0, rho2 * (2.0 * du - w));
  gsl_matrix_set(jac, 1, 1, -rho2 * du);
  return GSL_SUCCESS;
}

static int rh_pressure_fdf(const gsl_vector *x, void *params, gsl_vector *f, gsl_matrix *jac) {
  rh_pressure_f(x, params, f);
  return rh_pressure_df(x, params, jac);
}

/* Imposed velocity: unknowns x = (δρ, w); δu known, δp = p(ρ_i + δρ) − p(ρ_i). */
static int rh_velocity_f(const gsl_vector *x, void *params, gsl_vector *f) {
  const struct rmn_rh_data *d = params;
  double drho = gsl_vector_get(x, 0), w = gsl_vector_get(x, 1), du = d->du;
  double rho2 = d->rho_i + drho;
  gsl_vector_set(f, 0, rho2 * du - drho * w);
  gsl_vector_set(f, 1, rho2 * du * (du - w) + rmn_eos_pressure_increment(d->eos, d->rho_i, drho));
  return GSL_SUCCESS;
}

static int rh_velocity_df(const gsl_vector *x, void *params, gsl_matrix *jac) {
  const struct rmn_rh_data *d = params;
  double drho = gsl_vector_get(x, 0), w = gsl_vector_get(x, 1), du = d->du;
  double rho2 = d->rho_i + drho;
  double c2 = rmn_eos_sound_speed(d->eos, rho2);
  gsl_matrix_set(jac, 0, 0, du - w);
  gsl_matrix_set(jac, 0, 1, -drho);
  gsl_matrix_set(jac, 1, 0, du * (du - w) + c2 * c2);
  gsl_matrix_set(jac, 1, 1, -rho2 * du);
  return GSL_SUCCESS;
}

static int rh_velocity_fdf(const gsl_vector *x, void *params, gsl_vector *f, gsl_matrix *jac) {
  rh_velocity_f(x, params, f);
  return rh_velocity_df(x, params, jac);
}

static double star_function_gsl(double rho, void *params);
static double star_derivative_gsl(double rho, void *params);
static void star_fdf_gsl(double rho, void *params, double *f, double *df);

struct rmn_workspace *rmn_workspace_alloc(void) {
  struct rmn_workspace *ws = calloc(1, sizeof *ws);
  if (!ws) return NULL;
  ws->newton = gsl_multiroot_fdfsolver_alloc(gsl_multiroot_fdfsolver_newton, 2);
  ws->x = gsl_vector_alloc(2);
  ws->brent = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  ws->secant_newton = gsl_root_fdfsolver_alloc(gsl_root_fdfsolver_newton);
  if (!ws->newton || !ws->x || !ws->brent || !ws->secant_newton) {
    rmn_workspace_free(ws);
    return NULL;
  }
  ws->rh_pressure = (gsl_multiroot_function_fdf){
      .f = rh_pressure_f, .df = rh_pressure_df, .fdf = rh_pressure_fdf, .n = 2, .params = &ws->rh};
  ws->rh_velocity = (gsl_multiroot_function_fdf){
      .f = rh_velocity_f, .df = rh_velocity_df, .fdf = rh_velocity_fdf, .n = 2, .params = &ws->rh};
  ws->star = (gsl_function){.function = star_function_gsl, .params = &ws->star_data};
  ws->star_fdf = (gsl_function_fdf){.f = star_function_gsl,
                                    .df = star_derivative_gsl,
                                    .fdf = star_fdf_gsl,
                                    .params = &ws->star_data};
  return ws;
}

void rmn_workspace_free(struct rmn_workspace *ws) {
  if (!ws) return;
  if (ws->newton) gsl_multiroot_fdfsolver_free(ws->newton);
  if (ws->x) gsl_vector_free(ws->x);
  if (ws->brent) gsl_root_fsolver_free(ws->brent);
  if (ws->secant_newton) gsl_root_fdfsolver_free(ws->secant_newton);
  free(ws);
}

double rmn_star_f_side_(const struct rmn_eos *eos, double rho, double rho_k, double p_k,
                        double psi_k) {
  if (rho <= rho_k) return rmn_eos_psi(eos, rho) - psi_k;
  double p = rmn_eos_pressure(eos, rho);
  return sqrt((p - p_k) * (rho - rho_k) / (rho * rho_k));
}

static double star_function_gsl(double rho, void *params) {
  const struct rmn_star_data *d = params;
  if (!(rho >= d->lo && rho <= d->hi)) return NAN;
  return rmn_star_f_side_(d->eos, rho, d->rho_l, d->p_l, d->psi_l) +
         rmn_star_f_side_(d->eos, rho, d->rho_r, d->p_r, d->psi_r) + d->u_r - d->u_l;
}

/* d f_K/dρ: c/ρ on the rarefaction branch; on the shock branch, with A = (p − p_K)(ρ − ρ_K)/(ρ
 * ρ_K), f_K = sqrt(A) and dA/dρ = (c² (ρ − ρ_K) + p − p_K)/(ρ ρ_K) − A/ρ; both tend to c_K/ρ_K at
 * ρ_K. */
static double star_f_side_derivative(const struct rmn_eos *eos, double rho, double rho_k,
                                     double p_k) {
  double c = rmn_eos_sound_speed(eos, rho);
  if (rho <= rho_k) return c / rho;
  double dp = rmn_eos_pressure(eos, rho) - p_k, drho = rho - rho_k;
  double a = dp * drho / (rho * rho_k);
  if (!(a > 0.0)) return c / rho;
  double da = (c * c * drho + dp) / (rho * rho_k) - a / rho;
  return 0.5 * da / sqrt(a);
}

static double star_derivative_gsl(double rho, void *params) {
  const struct rmn_star_data *d = params;
  if (!(rho >= d->lo && rho <= d->hi)) return NAN;
  return star_f_side_derivative(d->eos, rho, d->rho_l, d->p_l) +
         star_f_side_derivative(d->eos, rho, d->rho_r, d->p_r);
}

static void star_fdf_gsl(double rho, void *params, double *f, double *df) {
  *f = star_function_gsl(rho, params);
  *df = star_derivative_gsl(rho, params);
}

double rmn_shock_velocity_closed_form(const struct rmn_eos *eos, double rho_int, double un_int,
                                      double rho2) {
  if (!(rho_int > 0.0) || !(rho2 >= rho_int)) return NAN;
  double dp = rmn_eos_pressure_increment(eos, rho_int, rho2 - rho_int);
  return un_int + sqrt(dp * (rho2 - rho_int) / (rho2 * rho_int));
}

void rmn_shock_residuals(const struct rmn_eos *eos, double rho_int, double un_int, double rho2,
                         double un2, double s, double residual[2]) {
  double p_i = rmn_eos_pressure(eos, rho_int), p2 = rmn_eos_pressure(eos, rho2);
  residual[0] = rho2 * (un2 - s) - rho_int * (un_int - s);
  residual[1] = rho2 * un2 * (un2 - s) + p2 - rho_int * un_int * (un_int - s) - p_i;
}

/* Newton iterations on the prepared system; x holds the initial guess on entry, the root on exit.
 * Converged when each step is below tol_rel relative to its component (w: or to c_i). */
static int newton_run(struct rmn_workspace *ws, gsl_multiroot_function_fdf *fdf,
                      const struct rmn_params *params, double scale1, double x[2],
                      int *iterations) {
  gsl_vector_set(ws->x, 0, x[0]);
  gsl_vector_set(ws->x, 1, x[1]);
  if (gsl_multiroot_fdfsolver_set(ws->newton, fdf, ws->x) != GSL_SUCCESS) return RMN_ENOCONV;
  int converged = 0, it = 0;
  while (!converged && it < params->max_iter) {
    ++it;
    if (gsl_multiroot_fdfsolver_iterate(ws->newton) != GSL_SUCCESS) return RMN_ENOCONV;
    const gsl_vector *root = gsl_multiroot_fdfsolver_root(ws->newton);
    const gsl_vector *dx = gsl_multiroot_fdfsolver_dx(ws->newton);
    double r0 = gsl_vector_get(root, 0), r1 = gsl_vector_get(root, 1);
    if (!isfinite(r0) || !isfinite(r1)) return RMN_ENOCONV;
    converged = fabs(gsl_vector_get(dx, 0)) <= params->tol_rel * fabs(r0) &&
                fabs(gsl_vector_get(dx, 1)) <= params->tol_rel * fmax(fabs(r1), scale1);
  }
  if (!converged) return RMN_ENOCONV;
  const gsl_vector *root = gsl_multiroot_fdfsolver_root(ws->newton);
  x[0] = gsl_vector_get(root, 0);
  x[1] = gsl_vector_get(root, 1);
  *iterations = it;
  return RMN_SUCCESS;
}

/* Internal entry points used by boundary.c: they return u2 (or ρ2) and S. */
int rmn_shock_solve_pressure_(const struct rmn_eos *eos, const struct rmn_params *params,
                              struct rmn_workspace *ws, double rho_i, double u_i, double c_i,
                              double drho, double dp, double *u2, double *s, int *iterations);
int rmn_shock_solve_velocity_(const struct rmn_eos *eos, const struct rmn_params *params,
                              struct rmn_workspace *ws, double rho_i, double u_i, double c_i,
                              double u2, double *rho2, double *s, int *iterations);

int rmn_shock_solve_pressure_(const struct rmn_eos *eos, const struct rmn_params *params,
                              struct rmn_workspace *ws, double rho_i, double u_i, double c_i,
                              double drho, double dp, double *u2, double *s, int *iterations) {
  const double rho2 = rho_i + drho;
  ws->rh = (struct rmn_rh_data){.eos = eos, .rho_i = rho_i, .drho = drho, .dp = dp};
  /* Acoustic guess: S halfway between the λ+1 of both states, δu from the mass balance. */
  double c2 = rmn_eos_sound_speed(eos, rho2);
  double w0 = 0.5 * (c_i + c2);
  double x[2] = {ws->rh.drho * w0 / rho2, w0};
  int st = newton_run(ws, &ws->rh_pressure, params, c_i, x, iterations);
  if (st != RMN_SUCCESS) return st;
  *u2 = u_i + x[0];
  *s = u_i + x[1];
  return RMN_SUCCESS;
}

int rmn_shock_solve_velocity_(const struct rmn_eos *eos, const struct rmn_params *params,
                              struct rmn_workspace *ws, double rho_i, double u_i, double c_i,
                              double u2, double *rho2, double *s, int *iterations) {
  ws->rh = (struct rmn_rh_data){.eos = eos, .rho_i = rho_i, .du = u2 - u_i};
  /* Acoustic guess: δρ = ρ δu / c, S halfway between the λ+1 of both states. */
  double drho0 = rho_i * ws->rh.du / c_i;
  double c2 = rmn_eos_sound_speed(eos, rho_i + drho0);
  double x[2] = {drho0, 0.5 * (c_i + ws->rh.du + c2)};
  int st = newton_run(ws, &ws->rh_velocity, params, c_i, x, iterations);
  if (st != RMN_SUCCESS) return st;
  *rho2 = rho_i + x[0];
  *s = u_i + x[1];
  return RMN_SUCCESS;
}
