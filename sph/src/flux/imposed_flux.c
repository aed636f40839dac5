/*
 * Imposed volume flux in periodic flows, M(56–63): slice measurement and driving-force updates.
 * Derivation and verification: docs/sph-robin.md §4.
 */
#include <math.h>
#include <stddef.h>

#include "sabre/sph.h"
#include "sabre/sph_flux.h"

static int slice_ok(int dim, const struct sph_flux_slice *s) {
  if (s == NULL || dim < 1 || dim > 3) return 0;
  if (!isfinite(s->width) || !(s->width > 0.0) || !isfinite(s->area) || !(s->area > 0.0)) return 0;
  double nn = 0.0;
  for (int k = 0; k < dim; k++) {
    if (!isfinite(s->normal[k]) || !isfinite(s->point[k])) return 0;
    nn += s->normal[k] * s->normal[k];
  }
  return fabs(nn - 1.0) <= 2e-9;
}

/* Σ_{b ∈ P_A} V_b v_b·n_A, M(56), with V_b = vol[b], or m_b/ρ_b when vol is NULL. */
static double slice_sum(int dim, const struct sph_flux_slice *slice, const struct sph_domain *dom,
                        size_t n, const double *const x[3], const double *const v[3],
                        const double *vol, const double *mass, const double *rho) {
  const double half = 0.5 * slice->width;
  double sum = 0.0;
  for (size_t b = 0; b < n; b++) {
    double r[3] = {0.0, 0.0, 0.0}, d[3];
    for (int k = 0; k < dim; k++) r[k] = x[k][b];
    if (dom != NULL) {
      sph_domain_delta(dom, slice->point, r, d);
    } else {
      for (int k = 0; k < 3; k++) d[k] = r[k] - slice->point[k];
    }
    double s = 0.0, vn = 0.0;
    for (int k = 0; k < dim; k++) {
      s += d[k] * slice->normal[k];
      vn += v[k][b] * slice->normal[k];
    }
    if (s >= -half && s < half) sum += (vol != NULL ? vol[b] : mass[b] / rho[b]) * vn;
  }
  return sum;
}

static int arrays_ok(int dim, size_t n, const double *const x[3], const double *const v[3]) {
  if (n == 0) return 1;
  if (x == NULL || v == NULL) return 0;
  for (int k = 0; k < dim; k++)
    if (x[k] == NULL || v[k] == NULL) return 0;
  return 1;
}

int sph_flux_measure(int dim, const struct sph_flux_slice *slice, const struct sph_domain *dom,
                     size_t n, const double *const x[3], const double *const v[3],
                     const double *vol, double *q, double *v_mean) {
  if (q != NULL) *q = NAN;
  if (v_mean != NULL) *v_mean = NAN;
  if (q == NULL || !slice_ok(dim, slice) || !arrays_ok(dim, n, x, v) || (n > 0 && vol == NULL))
    return -1;
  *q = slice_sum(dim, slice, dom, n, x, v, vol, NULL, NULL) / slice->width; /* M(56) */
  if (v_mean != NULL) *v_mean = *q / slice->area;                           /* M(57) */
  return 0;
}

int sph_flux_measure_parts(int dim, const struct sph_flux_slice *slice,
                           const struct sph_domain *dom, const struct sph_parts *p, double *q,
                           double *v_mean) {
  if (q != NULL) *q = NAN;
  if (v_mean != NULL) *v_mean = NAN;
  if (p == NULL || q == NULL || !slice_ok(dim, slice)) return -1;
  const double *const *x = (const double *const *)p->x, *const *v = (const double *const *)p->v;
  if (!arrays_ok(dim, p->n, x, v) || (p->n > 0 && (p->mass == NULL || p->rho == NULL))) return -1;
  *q = slice_sum(dim, slice, dom, p->n, x, v, NULL, p->mass, p->rho) / slice->width;
  if (v_mean != NULL) *v_mean = *q / slice->area;
  return 0;
}

double sph_flux_force_m58(double v_target, double vt_nm1, double vt_nm2, double dt) {
  return (v_target - 2.0 * vt_nm1 + vt_nm2) / (2.0 * dt);
}

double sph_flux_force_m63(double v_target, double vt_nm1, double vt_nm2, double dt_n, double dt_nm1,
                          double f_nm1) {
  /* (v − ṽ^{n−1})/Δt^n reaches the target in one step; −(ṽ^{n−1} − ṽ^{n−2})/Δt^{n−1} + F^{n−1}
   * is −F^{int,n−1} from M(60), standing in for the unknown −F^{int,n}, M(61–62). */
  return (v_target - vt_nm1) / dt_n - (vt_nm1 - vt_nm2) / dt_nm1 + f_nm1;
}

void sph_flux_ctrl_init(struct sph_flux_ctrl *c, enum sph_flux_method method, double v_target,
                        double force0) {
  c->method = method;
  c->v_target = v_target;
  c->vt1 = c->vt2 = 0.0;
  c->dt1 = 0.0;
  c->force = force0;
  c->steps = 0;
}

double sph_flux_ctrl_update(struct sph_flux_ctrl *c, double vt_measured, double dt) {
  const double vt2 = c->steps == 0 ? vt_measured : c->vt1;
  const double dt1 = c->steps == 0 ? dt : c->dt1;
  const double f = c->method == SPH_FLUX_M58
                       ? sph_flux_force_m58(c->v_target, vt_measured, vt2, dt)
                       : sph_flux_force_m63(c->v_target, vt_measured, vt2, dt, dt1, c->force);
  c->vt2 = vt2;
  c->vt1 = vt_measured;
  c->dt1 = dt;
  c->force = f;
  c->steps++;
  return f;
}
