/*
 * Arbitrary-order Robin/Neumann vertex values, M(64–74), with the hydrostatic correction M(83).
 * Derivation and verification: docs/sph-robin.md.
 *
 * Distances along the normal are scaled by L (ξ = x/L): the columns ξ^j then stay O(1) and the
 * normal matrix is well scaled. Scaling the columns j ≥ 2 only rescales β_j; the β1 column
 * 1 − (μ1/μ2) x = 1 − κ ξ is unchanged, so β1 = f_v is the same as in the paper's unscaled M(74).
 */
#include <gsl/gsl_blas.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <string.h>

#include "sabre/sph_robin.h"

const char *sph_robin_strerror(int status) {
  switch (status) {
#define SPH_ROBIN_X_TEXT(name, value, text) \
  case name:                                \
    return text;
    SPH_ROBIN_STATUS_LIST(SPH_ROBIN_X_TEXT)
#undef SPH_ROBIN_X_TEXT
    default:
      return "unknown status";
  }
}

const char *sph_robin_status_name(int status) {
  switch (status) {
#define SPH_ROBIN_X_NAME(name, value, text) \
  case name:                                \
    return #name;
    SPH_ROBIN_STATUS_LIST(SPH_ROBIN_X_NAME)
#undef SPH_ROBIN_X_NAME
    default:
      return "SPH_ROBIN_UNKNOWN";
  }
}

void sph_robin_params_init(struct sph_robin_params *p, double length) {
  memset(p, 0, sizeof *p);
  p->mu1 = 0.0;
  p->mu2 = 1.0;
  p->mu3 = 0.0;
  p->m = 1;
  p->length = length;
  p->dist_tol = 1e-6;
  p->rcond_min = 1e-13;
  p->hydro = 0;
}

static int fail(struct sph_robin_ws *ws, int status) {
  if (ws->status == SPH_ROBIN_SUCCESS) ws->status = status;
  return ws->status;
}

/* num/den·len is finite, decided without computing it (tests run with overflow traps on). */
static int scaled_ratio_ok(double num, double den, double len) {
  if (num == 0.0) return 1;
  return log(fabs(num)) - log(fabs(den)) + log(len) < 700.0;
}

int sph_robin_begin(struct sph_robin_ws *ws, const struct sph_robin_params *p, int dim,
                    const double *n_v) {
  if (ws == NULL) return SPH_ROBIN_EINVAL;
  memset(ws, 0, sizeof *ws);
  if (p == NULL || n_v == NULL || dim < 1 || dim > 3) return fail(ws, SPH_ROBIN_EINVAL);
  if (p->m < 1 || p->m > SPH_ROBIN_M_MAX) return fail(ws, SPH_ROBIN_EINVAL);
  if (!isfinite(p->mu1) || !isfinite(p->mu2) || !isfinite(p->mu3) || p->mu2 == 0.0)
    return fail(ws, SPH_ROBIN_EINVAL);
  if (!isfinite(p->length) || !(p->length > 0.0)) return fail(ws, SPH_ROBIN_EINVAL);
  if (!isfinite(p->dist_tol) || !(p->dist_tol >= 0.0)) return fail(ws, SPH_ROBIN_EINVAL);
  if (!isfinite(p->rcond_min) || !(p->rcond_min >= 0.0) || !(p->rcond_min < 1.0))
    return fail(ws, SPH_ROBIN_EINVAL);
  double nn = 0.0;
  for (int k = 0; k < dim; k++) {
    if (!isfinite(n_v[k])) return fail(ws, SPH_ROBIN_EINVAL);
    nn += n_v[k] * n_v[k];
  }
  if (!(fabs(sqrt(nn) - 1.0) <= 1e-6)) return fail(ws, SPH_ROBIN_EINVAL);
  const double inv_n = 1.0 / sqrt(nn);
  for (int k = 0; k < dim; k++) ws->normal[k] = n_v[k] * inv_n;
  if (p->hydro) {
    for (int k = 0; k < dim; k++) {
      if (!isfinite(p->gravity[k])) return fail(ws, SPH_ROBIN_EINVAL);
      ws->gravity[k] = p->gravity[k];
    }
  }
  if (!scaled_ratio_ok(p->mu1, p->mu2, p->length) || !scaled_ratio_ok(p->mu3, p->mu2, p->length))
    return fail(ws, SPH_ROBIN_EINVAL);
  const double kappa = p->mu1 / p->mu2 * p->length;
  const double sigma = p->mu3 / p->mu2 * p->length;
  ws->dim = dim;
  ws->m = p->m;
  ws->hydro = p->hydro != 0;
  ws->kappa = kappa;
  ws->sigma = sigma;
  ws->inv_len = 1.0 / p->length;
  ws->dist_tol = p->dist_tol;
  ws->rcond_min = p->rcond_min;
  ws->status = SPH_ROBIN_SUCCESS;
  return SPH_ROBIN_SUCCESS;
}

void sph_robin_add(struct sph_robin_ws *ws, const double *r_av, double f_a, double weight,
                   double rho_a) {
  if (ws->status != SPH_ROBIN_SUCCESS) return;
  if (weight == 0.0) return;
  if (!(weight > 0.0) || !isfinite(weight) || !isfinite(f_a)) {
    fail(ws, SPH_ROBIN_EINVAL);
    return;
  }
  const int dim = ws->dim, m = ws->m;
  double x = 0.0;
  for (int k = 0; k < dim; k++) x += r_av[k] * ws->normal[k];
  const double xi = x * ws->inv_len;
  /* M(69), with the tangential hydrostatic part removed for M(83). */
  double y = f_a - ws->sigma * xi;
  if (ws->hydro) {
    double tg = 0.0;
    for (int k = 0; k < dim; k++) tg += (r_av[k] - x * ws->normal[k]) * ws->gravity[k];
    y -= rho_a * tg;
  }
  if (!isfinite(xi) || !isfinite(y)) {
    fail(ws, SPH_ROBIN_EINVAL);
    return;
  }
  /* Row of X, M(68), in scaled distance. */
  double row[SPH_ROBIN_M_MAX];
  row[0] = 1.0 - ws->kappa * xi;
  double pw = xi;
  for (int j = 1; j < m; j++) {
    pw *= xi;
    row[j] = pw;
  }
  for (int j = 0; j < m; j++) {
    const double lr = weight * row[j];
    for (int k = j; k < m; k++) ws->a[j * m + k] += lr * row[k];
    ws->b[j] += lr * y;
  }
  ws->n_used++;
  if (ws->n_distinct < m) {
    int is_new = 1;
    for (int k = 0; k < ws->n_distinct; k++)
      if (fabs(xi - ws->distinct[k]) <= ws->dist_tol) is_new = 0;
    if (is_new) ws->distinct[ws->n_distinct++] = xi;
  }
}

int sph_robin_finish(struct sph_robin_ws *ws, double *f_v) {
  if (f_v != NULL) *f_v = NAN;
  if (ws == NULL || f_v == NULL) return SPH_ROBIN_EINVAL;
  if (ws->status != SPH_ROBIN_SUCCESS) return ws->status;
  const int m = ws->m;
  if (ws->n_distinct < m) return fail(ws, SPH_ROBIN_ETOOFEW);
  for (int j = 0; j < m; j++)
    for (int k = 0; k < j; k++) ws->a[j * m + k] = ws->a[k * m + j];
  for (int j = 0; j < m * m; j++)
    if (!isfinite(ws->a[j])) return fail(ws, SPH_ROBIN_EINVAL);

  /* SVD by one-sided Jacobi (GSL) on views of the workspace arrays: it allocates nothing (GSL's
   * Golub–Reinsch SV_decomp/SV_solve allocate scratch vectors), gives σ_min/σ_max for the
   * conditioning test, and, unlike Cholesky, does not report a (near-)singular matrix through the
   * GSL error handler. β = V Σ⁻¹ Uᵀ b by two GSL BLAS products. */
  gsl_matrix_view a = gsl_matrix_view_array(ws->a, (size_t)m, (size_t)m);
  gsl_matrix_view v = gsl_matrix_view_array(ws->v, (size_t)m, (size_t)m);
  gsl_vector_view s = gsl_vector_view_array(ws->s, (size_t)m);
  gsl_vector_view work = gsl_vector_view_array(ws->work, (size_t)m);
  gsl_vector_view b = gsl_vector_view_array(ws->b, (size_t)m);
  gsl_vector_view beta = gsl_vector_view_array(ws->beta, (size_t)m);
  if (gsl_linalg_SV_decomp_jacobi(&a.matrix, &v.matrix, &s.vector) != GSL_SUCCESS)
    return fail(ws, SPH_ROBIN_ESINGULAR);
  double smax = 0.0, smin = INFINITY;
  for (int j = 0; j < m; j++) {
    smax = fmax(smax, ws->s[j]);
    smin = fmin(smin, ws->s[j]);
  }
  ws->rcond = smax > 0.0 ? smin / smax : 0.0;
  if (!(smax > 0.0) || !(smin > 0.0) || !(ws->rcond >= ws->rcond_min))
    return fail(ws, SPH_ROBIN_ESINGULAR);
  gsl_blas_dgemv(CblasTrans, 1.0, &a.matrix, &b.vector, 0.0, &work.vector); /* Uᵀ b */
  for (int j = 0; j < m; j++) ws->work[j] /= ws->s[j];
  gsl_blas_dgemv(CblasNoTrans, 1.0, &v.matrix, &work.vector, 0.0, &beta.vector);
  if (!isfinite(ws->beta[0])) return fail(ws, SPH_ROBIN_ESINGULAR);
  *f_v = ws->beta[0];
  return SPH_ROBIN_SUCCESS;
}

int sph_robin_vertex_value(const struct sph_robin_params *p, int dim, const double *x_v,
                           const double *n_v, size_t n, const double (*x)[3], const double *f,
                           const double *vol, const double *w, const double *rho,
                           struct sph_robin_ws *ws, double *f_v) {
  if (f_v != NULL) *f_v = NAN;
  if (ws == NULL || f_v == NULL) return SPH_ROBIN_EINVAL;
  int status = sph_robin_begin(ws, p, dim, n_v);
  if (status != SPH_ROBIN_SUCCESS) return status;
  if (x_v == NULL || (n > 0 && (x == NULL || f == NULL || vol == NULL || w == NULL)) ||
      (n > 0 && p->hydro && rho == NULL))
    return fail(ws, SPH_ROBIN_EINVAL);
  for (int k = 0; k < dim; k++)
    if (!isfinite(x_v[k])) return fail(ws, SPH_ROBIN_EINVAL);
  for (size_t a = 0; a < n; a++) {
    double r_av[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < dim; k++) r_av[k] = x[a][k] - x_v[k];
    if (!(vol[a] >= 0.0) || !(w[a] >= 0.0)) return fail(ws, SPH_ROBIN_EINVAL);
    sph_robin_add(ws, r_av, f[a], vol[a] * w[a], rho != NULL ? rho[a] : 0.0);
  }
  return sph_robin_finish(ws, f_v);
}
