/* The boundary (partial) Riemann problem, J §III and docs/theory.md §1.1: the segment state ("state
 * 2") is linked to the interior across the λ+1 wave only; one quantity is imposed. */
#include <float.h>
#include <math.h>

#include "sabre/riemann.h"
#include "workspace.h"

int rmn_shock_solve_pressure_(const struct rmn_eos *eos, const struct rmn_params *params,
                              struct rmn_workspace *ws, double rho_i, double u_i, double c_i,
                              double drho, double dp, double *u2, double *s, int *iterations);
int rmn_shock_solve_velocity_(const struct rmn_eos *eos, const struct rmn_params *params,
                              struct rmn_workspace *ws, double rho_i, double u_i, double c_i,
                              double u2, double *rho2, double *s, int *iterations);

void rmn_params_default(struct rmn_params *params) {
  *params = (struct rmn_params){
      .shock = RMN_SHOCK_EXACT, .tol_rel = 1e-14, .max_iter = 100, .contact_tol = 1e-12};
}

int rmn_params_check(const struct rmn_params *params) {
  if (!params) return RMN_EINVAL;
  if (params->shock != RMN_SHOCK_EXACT && params->shock != RMN_SHOCK_LINEARISED) return RMN_EINVAL;
  if (!(params->tol_rel > 0.0 && params->tol_rel <= 1e-2)) return RMN_EINVAL;
  if (params->max_iter < 1) return RMN_EINVAL;
  if (!(params->contact_tol >= 0.0 && params->contact_tol < 1.0)) return RMN_EINVAL;
  return RMN_SUCCESS;
}

/* Lax condition λ+1(int) < S < λ+1(2) for a shock of speed S, i.e. c_i < S − u_i < u2 − u_i + c2,
 * to within a few ulps of the speeds involved. */
static int lax_holds(double u_i, double c_i, double u2, double c2, double s) {
  double w = s - u_i, slack = 16.0 * DBL_EPSILON * (c_i + c2 + fabs(w));
  return c_i < w + slack && w < (u2 - u_i) + c2 + slack;
}

int rmn_boundary_solve_normal(const struct rmn_eos *eos, const struct rmn_params *params,
                              struct rmn_workspace *ws, double rho_int, double un_int,
                              enum rmn_imposed imposed, double value,
                              struct rmn_normal_state *out) {
  if (!eos || !params || !out) return RMN_EINVAL;
  int st = rmn_params_check(params);
  if (st != RMN_SUCCESS) return st;
  if (!isfinite(rho_int) || !isfinite(un_int) || !isfinite(value)) return RMN_EINVAL;
  if (imposed != RMN_IMPOSE_PRESSURE && imposed != RMN_IMPOSE_VELOCITY) return RMN_EINVAL;
  if (rho_int <= 0.0) return RMN_EDENSITY;

  /* Interior state, with one power at most: b (ρ/ρ0)^ξ = p + b, c = c0 sqrt((ρ/ρ0)^(ξ−1)),
   * ψ = 2c/(ξ−1). All increments below are taken relative to it (log1p/expm1), so that weak
   * waves keep full relative precision and (δρ, δp, δψ) stay consistent through the EOS. */
  const int iso = eos->isothermal;
  const double half = eos->half_xim1;
  const double ratio = rho_int / eos->rho0;
  const double pref = iso ? 0.0 : eos->b * rmn_eos_ratio_xi_(eos, ratio);
  const double c_i = iso ? eos->c0 : eos->c0 * sqrt(pref / (eos->b * ratio));
  if (!(fabs(un_int) < c_i)) return RMN_ESUPERSONIC;
  const double psi_i = iso ? eos->c0 * log(ratio) : eos->psi_scale * c_i / eos->c0;
  const double p_i = iso ? eos->c0 * eos->c0 * (rho_int - eos->rho0) : pref - eos->b;

  struct rmn_normal_state r = {.shock_speed = NAN};
  double c2;
  if (imposed == RMN_IMPOSE_PRESSURE) {
    const double dp = value - p_i;
    double drho, log_ratio; /* log_ratio = log(ρ2/ρ_int) */
    if (iso) {
      drho = dp / (eos->c0 * eos->c0);
      if (!(rho_int + drho > 0.0)) return RMN_ECAVITATION;
      log_ratio = log1p(drho / rho_int);
    } else {
      if (!(dp / pref > -1.0)) return RMN_ECAVITATION; /* p2 ≤ p(0) */
      log_ratio = log1p(dp / pref) / eos->xi;
      drho = rho_int * expm1(log_ratio);
    }
    r.p = value;
    r.rho = rho_int + drho;
    if (!(r.rho > 0.0)) return RMN_ECAVITATION;
    c2 = iso ? eos->c0 : c_i * exp(half * log_ratio);
    if (drho <= params->contact_tol * rho_int) {
      /* Contact (J 26–27) or expansion (J 28–29): R+1 = u_n − ψ is conserved. */
      r.wave = fabs(drho) <= params->contact_tol * rho_int ? RMN_WAVE_CONTACT : RMN_WAVE_EXPANSION;
      r.un = un_int + (iso ? eos->c0 * log_ratio : psi_i * expm1(half * log_ratio));
    } else {
      r.wave = RMN_WAVE_SHOCK;
      if (params->shock == RMN_SHOCK_LINEARISED) {
        if (un_int == 0.0) return RMN_EUNDEFINED;
        r.un = un_int - dp / (rho_int * un_int);
        r.shock_speed = 0.0;
      } else {
        if (!ws) return RMN_EINVAL;
        st = rmn_shock_solve_pressure_(eos, params, ws, rho_int, un_int, c_i, drho, dp, &r.un,
                                       &r.shock_speed, &r.iterations);
        if (st != RMN_SUCCESS) return st;
      }
    }
  } else {
    r.un = value;
    const double du = value - un_int;
    if (du <= params->contact_tol * c_i) {
      r.wave = fabs(du) <= params->contact_tol * c_i ? RMN_WAVE_CONTACT : RMN_WAVE_EXPANSION;
      /* ψ2 = ψ_int + δu (R+1 conserved); ψ2 ≤ 0 is vacuum for ξ > 1 */
      if (iso) {
        double drho = rho_int * expm1(du / eos->c0);
        r.rho = rho_int + drho;
        r.p = p_i + eos->c0 * eos->c0 * drho;
        c2 = eos->c0;
      } else {
        if (!(psi_i + du > 0.0)) return RMN_ECAVITATION;
        double log_ratio = log1p(du / psi_i) / half;
        r.rho = rho_int * (1.0 + expm1(log_ratio));
        r.p = p_i + pref * expm1(eos->xi * log_ratio);
        c2 = half * (psi_i + du);
      }
      if (!(r.rho > 0.0)) return RMN_ECAVITATION;
    } else {
      r.wave = RMN_WAVE_SHOCK;
      if (params->shock == RMN_SHOCK_LINEARISED) {
        double p2 = p_i + rho_int * un_int * (un_int - value);
        if (!iso && !(p2 > -eos->b)) return RMN_ECAVITATION;
        r.rho = rmn_eos_density(eos, p2);
        if (!(r.rho > 0.0)) return RMN_ECAVITATION;
        r.shock_speed = 0.0;
      } else {
        if (!ws) return RMN_EINVAL;
        st = rmn_shock_solve_velocity_(eos, params, ws, rho_int, un_int, c_i, value, &r.rho,
                                       &r.shock_speed, &r.iterations);
        if (st != RMN_SUCCESS) return st;
        if (!(r.rho > rho_int)) return RMN_ENOCONV; /* converged to the wrong branch */
      }
      r.p = p_i + rmn_eos_pressure_increment(eos, rho_int, r.rho - rho_int);
      c2 = rmn_eos_sound_speed(eos, r.rho);
    }
  }

  if (!isfinite(r.un) || !isfinite(r.rho) || !isfinite(c2)) return RMN_ENOCONV;
  if (!(fabs(r.un) < c2)) return RMN_ESUPERSONIC;
  if (r.wave == RMN_WAVE_SHOCK && params->shock == RMN_SHOCK_EXACT &&
      !lax_holds(un_int, c_i, r.un, c2, r.shock_speed))
    return RMN_ELAX;
  r.flow = r.un >= 0.0 ? RMN_FLOW_INFLOW : RMN_FLOW_OUTFLOW;
  *out = r;
  return RMN_SUCCESS;
}

static void result_fail(struct rmn_boundary_result *out, int status) {
  *out = (struct rmn_boundary_result){.rho = NAN,
                                      .p = NAN,
                                      .u = {NAN, NAN, NAN},
                                      .un = NAN,
                                      .ut = {NAN, NAN},
                                      .shock_speed = NAN,
                                      .status = status};
}

int rmn_boundary_solve(const struct rmn_eos *eos, const struct rmn_params *params,
                       struct rmn_workspace *ws, int dim, const struct rmn_boundary_input *in,
                       struct rmn_boundary_result *out) {
  if (!out) return RMN_EINVAL;
  struct rmn_frame frame;
  int st = in ? rmn_frame_from_normal(dim, in->normal, &frame) : RMN_EINVAL;
  if (st != RMN_SUCCESS) {
    result_fail(out, st);
    return st;
  }
  double local[3];
  rmn_frame_to_local(&frame, in->u, local);
  struct rmn_normal_state ns;
  st = rmn_boundary_solve_normal(eos, params, ws, in->rho, local[0], in->imposed, in->value, &ns);
  if (st != RMN_SUCCESS) {
    result_fail(out, st);
    return st;
  }
  /* Tangential velocity, J §III: continuous across λ+1; across λ0 it is imposed on inflow and
   * taken from the interior on outflow (λ0 is then a "ghost" wave). */
  double seg[3] = {ns.un, 0.0, 0.0};
  for (int k = 1; k < dim; ++k) {
    double ut = ns.flow == RMN_FLOW_INFLOW ? in->ut[k - 1] : local[k];
    if (!isfinite(ut)) {
      result_fail(out, RMN_EINVAL);
      return RMN_EINVAL;
    }
    seg[k] = ut;
  }
  struct rmn_boundary_result r = {.rho = ns.rho,
                                  .p = ns.p,
                                  .un = ns.un,
                                  .ut = {seg[1], seg[2]},
                                  .wave = ns.wave,
                                  .flow = ns.flow,
                                  .shock_speed = ns.shock_speed,
                                  .status = RMN_SUCCESS};
  rmn_frame_to_global(&frame, seg, r.u);
  *out = r;
  return RMN_SUCCESS;
}

int rmn_boundary_solve_batch(const struct rmn_eos *eos, const struct rmn_params *params,
                             struct rmn_workspace *ws, int dim, size_t count,
                             const struct rmn_boundary_input *in, struct rmn_boundary_result *out,
                             size_t *first_failed) {
  if (count > 0 && (!in || !out)) return RMN_EINVAL;
  int first = RMN_SUCCESS;
  for (size_t i = 0; i < count; ++i) {
    int st = rmn_boundary_solve(eos, params, ws, dim, &in[i], &out[i]);
    if (st != RMN_SUCCESS && first == RMN_SUCCESS) {
      first = st;
      if (first_failed) *first_failed = i;
    }
  }
  return first;
}
