/*
 * γ and ∇γ_as in 1D (docs/sph-gamma.md §3): a wall "segment" is a point x_s with normal n_s = ±1.
 *   ∇γ_as = w(|δ|) n_s,                         J(3)
 *   gamma_term = sign(δ) (1/2 − W(|δ|)),        G1 with G_1(r) = W(r) − 1/2, ω_1 = 2
 * where δ = (a − x_s) n_s and W(x) = ∫_0^x w = α_1 (q − 5/6 q³ + 5/8 q⁴ − 3/16 q⁵ + 1/48 q⁶).
 */
#include <math.h>

#include "kernel.h"
#include "walls/gamma_impl.h"

/* ∫_0^x w dr for x = q h ≥ 0 (reaches 1/2 at q = 2). */
static double cumulative_w1(double q) {
  if (q >= 2.0) return 0.5;
  const double q2 = q * q, q3 = q2 * q;
  return SPH_WENDLAND_ALPHA1 *
         (q - 5.0 / 6.0 * q3 + q3 * q * (5.0 / 8.0 - 3.0 / 16.0 * q + 1.0 / 48.0 * q2));
}

void sph_gamma1d_element(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, const double *m, double *term,
                         double grad[3]) {
  const double n = e->normal[0] > 0.0 ? 1.0 : -1.0;
  const double delta = (a[0] - e->x[0][0]) * n;
  const double r = fabs(delta);
  grad[0] = sph_kernel_w_inline(k, r) * e->normal[0];
  grad[1] = grad[2] = 0.0;
  if (r <= SPH_GAMMA_PLANE_TOL * k->h) {
    /* Solid-angle limit: half of the "sphere" {−1, +1} lies behind the wall. */
    const double side = m == NULL ? 1.0 : (m[0] * n > 0.0 ? 1.0 : -1.0);
    *term = 0.5 * side;
  } else {
    *term = (delta > 0.0 ? 1.0 : -1.0) * (0.5 - cumulative_w1(r * k->inv_h));
  }
}

int sph_gamma1d_incident(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, double tol, double m[3]) {
  (void)tol; /* a point has no extent: on the wall means within the plane tolerance */
  if (fabs(a[0] - e->x[0][0]) > SPH_GAMMA_PLANE_TOL * k->h) return 0;
  if (m != NULL) m[0] += e->normal[0] > 0.0 ? 1.0 : -1.0;
  return 1;
}

int sph_gamma1d_check(const struct sph_wall_element *e) {
  if (!isfinite(e->x[0][0]) || !isfinite(e->normal[0])) return -1;
  return fabs(fabs(e->normal[0]) - 1.0) <= 1e-6 ? 0 : -1;
}
