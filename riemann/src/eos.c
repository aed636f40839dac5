/* Tait equation of state: parameter checks and derived constants (the pointwise maps are inline
 * in riemann.h). */
#include <math.h>

#include "sabre/riemann.h"

int rmn_eos_init(struct rmn_eos *eos, double rho0, double c0, double xi) {
  if (!eos || !isfinite(rho0) || !isfinite(c0) || !isfinite(xi)) return RMN_EINVAL;
  if (rho0 <= 0.0 || c0 <= 0.0 || xi < 1.0) return RMN_EINVAL;
  struct rmn_eos e = {.rho0 = rho0, .c0 = c0, .xi = xi};
  e.b = rho0 * c0 * c0 / xi;
  e.half_xim1 = 0.5 * (xi - 1.0);
  e.isothermal = (xi == 1.0);
  e.psi_scale = e.isothermal ? c0 : 2.0 * c0 / (xi - 1.0);
  e.integer_xi = 0;
  for (int k = 2; k <= 7; ++k)
    if (xi == (double)k) e.integer_xi = k;
  *eos = e;
  return RMN_SUCCESS;
}

int rmn_eos_check_density(double rho) {
  if (!isfinite(rho)) return RMN_EINVAL;
  return rho > 0.0 ? RMN_SUCCESS : RMN_EDENSITY;
}

double rmn_eos_min_pressure(const struct rmn_eos *eos) {
  return eos->isothermal ? -HUGE_VAL : -eos->b;
}
