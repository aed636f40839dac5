/*
 * The linearised dynamics of the fluid about a state at rest (docs/sph-solver.md §7.1, "The free
 * surface's static states are linearly unstable"): J = ∂a/∂x by central differences of the
 * solver's own accelerations, and the growth rates of ẍ = J x from J's eigenvalues (GSL).
 */
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_solver.h"
#include "solver/solver_internal.h"

/* The reference state: positions x0, γ⁰ρ⁰ and the kernel sums S⁰ at x0. */
struct reference {
  double *x0[3], *grho0, *s0;
};

/* Lists and the geometric γ at the current positions (what a step's evaluation forms, without
 * its forces). */
static void lists_and_gamma(struct sph_solver *sv) {
  sph_solver_sync(sv);
  sph_nbrs_build(&sv->nb, &sv->sys, sv->cfg.skin_over_h * sv->sys.h);
  sph_nbrs_gamma(&sv->nb, &sv->sys, &sv->kernel);
}

/* Accelerations at x0 + u (u NULL: x0) with ρ_a = (γ⁰_a ρ⁰_a + S_a(x) − S⁰_a)/γ_a(x), into out. */
static void accelerations(struct sph_solver *sv, const struct reference *ref, const double *u,
                          double *out) {
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const int dim = sv->sys.dim;
  for (size_t a = 0; a < f->n; a++)
    for (int c = 0; c < dim; c++) f->x[c][a] = ref->x0[c][a] + (u ? u[a * dim + c] : 0.0);
  lists_and_gamma(sv);
  for (size_t a = 0; a < f->n; a++)
    f->rho[a] = (ref->grho0[a] + sph_solver_kernel_sum(sv, a) - ref->s0[a]) / f->gamma[a];
  sph_solver_boundary_values(sv);
  sph_solver_forces(sv);
  for (size_t a = 0; a < f->n; a++)
    for (int c = 0; c < dim; c++) out[a * dim + c] = sv->acc[c][a];
}

void sph_solver_jacobian(struct sph_solver *sv, double eps, double *J) {
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const int dim = sv->sys.dim;
  const size_t n = f->n * (size_t)dim;
  struct reference ref = {{NULL, NULL, NULL},
                          cmn_malloc((f->n + 1) * sizeof(double)),
                          cmn_malloc((f->n + 1) * sizeof(double))};
  double *rho0 = cmn_malloc((f->n + 1) * sizeof(double)),
         *gamma0 = cmn_malloc((f->n + 1) * sizeof(double));
  memcpy(rho0, f->rho, f->n * sizeof(double));
  memcpy(gamma0, f->gamma, f->n * sizeof(double)); /* state with numerics.gamma dynamic */
  for (int c = 0; c < dim; c++) {
    ref.x0[c] = cmn_malloc((f->n + 1) * sizeof(double));
    memcpy(ref.x0[c], f->x[c], f->n * sizeof(double));
  }
  lists_and_gamma(sv);
  for (size_t a = 0; a < f->n; a++) {
    ref.grho0[a] = f->gamma[a] * f->rho[a];
    ref.s0[a] = sph_solver_kernel_sum(sv, a);
  }
  double *u = cmn_calloc(n + 1, sizeof(double)), *ap = cmn_malloc((n + 1) * sizeof(double)),
         *am = cmn_malloc((n + 1) * sizeof(double));
  for (size_t j = 0; j < n; j++) {
    u[j] = eps;
    accelerations(sv, &ref, u, ap);
    u[j] = -eps;
    accelerations(sv, &ref, u, am);
    u[j] = 0.0;
    for (size_t i = 0; i < n; i++) J[i * n + j] = (ap[i] - am[i]) / (2.0 * eps);
  }
  /* the state as it was, evaluated */
  for (int c = 0; c < dim; c++) memcpy(f->x[c], ref.x0[c], f->n * sizeof(double));
  memcpy(f->rho, rho0, f->n * sizeof(double));
  memcpy(f->gamma, gamma0, f->n * sizeof(double));
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
  free(u);
  free(ap);
  free(am);
  free(rho0);
  free(gamma0);
  free(ref.grho0);
  free(ref.s0);
  for (int c = 0; c < dim; c++) free(ref.x0[c]);
}

int sph_stability_modes(size_t n, double *J, double *lambda_re, double *lambda_im, double *rate,
                        double *amp) {
  if (n == 0) return 0;
  gsl_matrix_view m = gsl_matrix_view_array(J, n, n);
  gsl_vector_complex *ev = gsl_vector_complex_alloc(n);
  gsl_matrix_complex *vec = amp ? gsl_matrix_complex_alloc(n, n) : NULL;
  gsl_eigen_nonsymm_workspace *ws = amp ? NULL : gsl_eigen_nonsymm_alloc(n);
  gsl_eigen_nonsymmv_workspace *wv = amp ? gsl_eigen_nonsymmv_alloc(n) : NULL;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  const int status =
      amp ? gsl_eigen_nonsymmv(&m.matrix, ev, vec, wv) : gsl_eigen_nonsymm(&m.matrix, ev, ws);
  gsl_set_error_handler(old);
  if (status == GSL_SUCCESS) {
    for (size_t i = 0; i < n; i++) {
      const gsl_complex l = gsl_vector_complex_get(ev, i);
      lambda_re[i] = GSL_REAL(l);
      lambda_im[i] = GSL_IMAG(l);
      rate[i] = GSL_REAL(gsl_complex_sqrt(l));
    }
    if (amp)
      for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
          amp[i * n + j] = gsl_complex_abs(gsl_matrix_complex_get(vec, i, j));
  }
  if (ws) gsl_eigen_nonsymm_free(ws);
  if (wv) gsl_eigen_nonsymmv_free(wv);
  if (vec) gsl_matrix_complex_free(vec);
  gsl_vector_complex_free(ev);
  return status == GSL_SUCCESS ? 0 : -1;
}

int sph_stability_rates(size_t n, double *J, double *lambda_re, double *lambda_im, double *rate) {
  return sph_stability_modes(n, J, lambda_re, lambda_im, rate, NULL);
}
