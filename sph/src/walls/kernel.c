/*
 * Out-of-line entry points of the Wendland C2 kernel (sph/src/kernel.h holds the inline forms used
 * by the hot loops). Normalisation derived in docs/sph-gamma.md §1.
 */
#include "kernel.h"

#include <math.h>

#include "sabre/sph_walls.h"

int sph_kernel_init(struct sph_kernel *k, int dim, double h) {
  static const double alpha[4] = {0.0, SPH_WENDLAND_ALPHA1, SPH_WENDLAND_ALPHA2,
                                  SPH_WENDLAND_ALPHA3};
  /* The range keeps 1/h^(d+1) finite and normal. */
  if (k == NULL || dim < 1 || dim > 3 || !isfinite(h) || h < 1e-100 || h > 1e100) return -1;
  const double inv_h = 1.0 / h;
  k->dim = dim;
  k->h = h;
  k->inv_h = inv_h;
  k->alpha = alpha[dim];
  k->w_norm = alpha[dim] * pow(inv_h, dim);
  k->dw_norm = k->w_norm * inv_h;
  return 0;
}

double sph_kernel_w(const struct sph_kernel *k, double r) {
  return sph_kernel_w_inline(k, fabs(r));
}

double sph_kernel_dwdr(const struct sph_kernel *k, double r) {
  return sph_kernel_dwdr_inline(k, fabs(r));
}
