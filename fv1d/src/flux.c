/* Numerical fluxes at cell faces (docs/theory.md §2): exact Godunov through riemann/, HLL, Rusanov;
 * and the energy bookkeeping of the barotropic system. */
#include <math.h>

#include "internal.h"

const char *const fv1d_flux_names[] = {"godunov", "hll", "rusanov", NULL};

double fv1d_internal_energy(const struct rmn_eos *eos, double rho) {
  /* W(ρ) = ρ ∫_{ρ0}^{ρ} p(s)/s² ds, so that dW/dρ = (W + p)/ρ: the energy equation of the
   * barotropic system is ∂E/∂t + ∂((E + p)u)/∂x ≤ 0 with E = ½ρu² + W. Closed forms:
   *   ξ > 1: W = B [(r^ξ − r)/(ξ − 1) + 1 − r],  ξ = 1: W = c0² (ρ ln r + ρ0 − ρ),  r = ρ/ρ0. */
  double r = rho / eos->rho0;
  if (eos->isothermal) {
    if (rho <= 0.0) return eos->c0 * eos->c0 * eos->rho0;
    return eos->c0 * eos->c0 * (rho * log(r) + eos->rho0 - rho);
  }
  double rxi = rmn_eos_pressure(eos, rho) / eos->b + 1.0; /* r^ξ */
  return eos->b * ((rxi - r) / (eos->xi - 1.0) + 1.0 - r);
}

double fv1d_energy_flux(const struct rmn_eos *eos, double rho, double u) {
  double e = 0.5 * rho * u * u + fv1d_internal_energy(eos, rho);
  return (e + rmn_eos_pressure(eos, rho)) * u;
}

static int flux_godunov(const struct rmn_eos *eos, const struct rmn_params *params,
                        struct rmn_workspace *ws, double rho_l, double u_l, double rho_r,
                        double u_r, double f[2]) {
  if (rho_l == rho_r && u_l == u_r) { /* uniform flow: no waves, skip the root finder */
    fv1d_flux_physical(eos, rho_l, u_l, f);
    return RMN_SUCCESS;
  }
  struct rmn_exact sol;
  int status = rmn_exact_solve(eos, params, ws, rho_l, u_l, rho_r, u_r, &sol);
  if (status != RMN_SUCCESS) return status;
  double rho, u;
  rmn_exact_sample(&sol, 0.0, &rho, &u);
  if (!(rho > 0.0)) { /* the face sits in a vacuum: no mass, the vacuum pressure p(0) */
    f[0] = 0.0;
    f[1] = rmn_eos_pressure(eos, 0.0);
    return RMN_SUCCESS;
  }
  fv1d_flux_physical(eos, rho, u, f);
  return RMN_SUCCESS;
}

static void flux_hll(const struct rmn_eos *eos, double rho_l, double u_l, double rho_r, double u_r,
                     double f[2]) {
  double c_l = rmn_eos_sound_speed(eos, rho_l), c_r = rmn_eos_sound_speed(eos, rho_r);
  double s_l = fmin(u_l - c_l, u_r - c_r); /* Davis' estimates */
  double s_r = fmax(u_l + c_l, u_r + c_r);
  double f_l[2], f_r[2];
  fv1d_flux_physical(eos, rho_l, u_l, f_l);
  fv1d_flux_physical(eos, rho_r, u_r, f_r);
  if (s_l >= 0.0) {
    f[0] = f_l[0], f[1] = f_l[1];
  } else if (s_r <= 0.0) {
    f[0] = f_r[0], f[1] = f_r[1];
  } else {
    double inv = 1.0 / (s_r - s_l);
    f[0] = (s_r * f_l[0] - s_l * f_r[0] + s_l * s_r * (rho_r - rho_l)) * inv;
    f[1] = (s_r * f_l[1] - s_l * f_r[1] + s_l * s_r * (rho_r * u_r - rho_l * u_l)) * inv;
  }
}

static void flux_rusanov(const struct rmn_eos *eos, double rho_l, double u_l, double rho_r,
                         double u_r, double f[2]) {
  double a = fmax(fabs(u_l) + rmn_eos_sound_speed(eos, rho_l),
                  fabs(u_r) + rmn_eos_sound_speed(eos, rho_r));
  double f_l[2], f_r[2];
  fv1d_flux_physical(eos, rho_l, u_l, f_l);
  fv1d_flux_physical(eos, rho_r, u_r, f_r);
  f[0] = 0.5 * (f_l[0] + f_r[0]) - 0.5 * a * (rho_r - rho_l);
  f[1] = 0.5 * (f_l[1] + f_r[1]) - 0.5 * a * (rho_r * u_r - rho_l * u_l);
}

int fv1d_flux_numerical(enum fv1d_flux kind, const struct rmn_eos *eos,
                        const struct rmn_params *params, struct rmn_workspace *ws, double rho_l,
                        double u_l, double rho_r, double u_r, double f[2]) {
  switch (kind) {
    case FV1D_FLUX_GODUNOV:
      return flux_godunov(eos, params, ws, rho_l, u_l, rho_r, u_r, f);
    case FV1D_FLUX_HLL:
      flux_hll(eos, rho_l, u_l, rho_r, u_r, f);
      return RMN_SUCCESS;
    case FV1D_FLUX_RUSANOV:
      flux_rusanov(eos, rho_l, u_l, rho_r, u_r, f);
      return RMN_SUCCESS;
  }
  return RMN_EINVAL;
}
