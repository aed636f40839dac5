/*
 * Wendland C2 kernel, M(1), for the hot loops: static inline, no branches on the dimension (the
 * dimension only enters through the normalisation stored in struct sph_kernel).
 *
 *   w(r) = α_d/h^d f(q),  f(q) = (1 − q/2)^4 (1 + 2q)  (q = r/h ≤ 2),
 *   f(q) = 1 − 5/2 q² + 5/2 q³ − 15/16 q⁴ + 1/8 q⁵,  f'(q) = −5q (1 − q/2)^3.
 *
 * The factored forms are used for point values (no cancellation near q = 2); the monomial form
 * is what the wall integrals integrate (sph/src/walls/, docs/sph-gamma.md).
 */
#ifndef SPH_KERNEL_H
#define SPH_KERNEL_H

#include <math.h>

#include "sabre/sph_walls.h"

/** π (M_PI is not ISO C). */
#define SPH_PI 3.14159265358979323846

/** Normalisation α_d so that ∫ w dV = 1 (derivation of α_1 = 3/4 in docs/sph-gamma.md §1). */
#define SPH_WENDLAND_ALPHA1 0.75
#define SPH_WENDLAND_ALPHA2 (7.0 / (4.0 * SPH_PI))
#define SPH_WENDLAND_ALPHA3 (21.0 / (16.0 * SPH_PI))

/** f(q) = (1 − q/2)^4 (1 + 2q) for 0 ≤ q < 2, else 0. */
static inline double sph_wendland_f(double q) {
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  const double t2 = t * t;
  return t2 * t2 * (1.0 + 2.0 * q);
}

/** f'(q) = −5q (1 − q/2)^3 for 0 ≤ q < 2, else 0. */
static inline double sph_wendland_dfdq(double q) {
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  return -5.0 * q * t * t * t;
}

/** w(r) for r ≥ 0 [1/m^d]. */
static inline double sph_kernel_w_inline(const struct sph_kernel *k, double r) {
  return k->w_norm * sph_wendland_f(r * k->inv_h);
}

/** dw/dr for r ≥ 0 [1/m^(d+1)]. */
static inline double sph_kernel_dwdr_inline(const struct sph_kernel *k, double r) {
  return k->dw_norm * sph_wendland_dfdq(r * k->inv_h);
}

/** dw/dr / r for r > 0 [1/m^(d+2)]: α_d f'(q)/(q h^(d+2)) = −5 α_d (1 − q/2)^3 / h^(d+2), without
 *  a division (dw_norm = α_d/h^(d+1)). */
static inline double sph_kernel_dwdr_over_r_inline(const struct sph_kernel *k, double r) {
  const double q = r * k->inv_h;
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  return k->dw_norm * k->inv_h * (-5.0 * t * t * t);
}

#endif
