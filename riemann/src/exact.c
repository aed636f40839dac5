/* Exact two-wave Riemann solver of the barotropic Euler equations (docs/theory.md §1.2), with dry
 * states and vacuum generation. The star density solves f_L(ρ*) + f_R(ρ*) + u_R − u_L = 0 with f_K
 * = ψ(ρ) − ψ(ρ_K) (rarefaction, ρ ≤ ρ_K) or sqrt((p − p_K)(ρ − ρ_K)/(ρ ρ_K)) (shock); f is
 * increasing, so the root is bracketed from the data and found by GSL's Newton solver inside the
 * bracket, with GSL's Brent solver as fallback. */
#include <math.h>

#include "sabre/riemann.h"
#include "workspace.h"

double rmn_exact_star_function(const struct rmn_eos *eos, double rho, double rho_l, double u_l,
                               double rho_r, double u_r) {
  double p_l = rmn_eos_pressure(eos, rho_l), p_r = rmn_eos_pressure(eos, rho_r);
  return rmn_star_f_side_(eos, rho, rho_l, p_l, rmn_eos_psi(eos, rho_l)) +
         rmn_star_f_side_(eos, rho, rho_r, p_r, rmn_eos_psi(eos, rho_r)) + u_r - u_l;
}

/* Fan of the left (λ−1) family at s: u − c = s and u + ψ = R (the R−1 invariant of J 21). */
static void left_fan(const struct rmn_eos *e, double r_minus, double s, double *rho, double *u) {
  if (e->isothermal) {
    *u = s + e->c0;
    *rho = rmn_eos_density_from_psi(e, r_minus - *u);
    return;
  }
  double psi = 2.0 * (r_minus - s) / (e->xi + 1.0);
  *u = s + rmn_eos_sound_speed_from_psi(e, psi);
  *rho = rmn_eos_density_from_psi(e, psi);
}

/* Fan of the right (λ+1) family at s: u + c = s and u − ψ = R (the R+1 invariant of J 23). */
static void right_fan(const struct rmn_eos *e, double r_plus, double s, double *rho, double *u) {
  if (e->isothermal) {
    *u = s - e->c0;
    *rho = rmn_eos_density_from_psi(e, *u - r_plus);
    return;
  }
  double psi = 2.0 * (s - r_plus) / (e->xi + 1.0);
  *u = s - rmn_eos_sound_speed_from_psi(e, psi);
  *rho = rmn_eos_density_from_psi(e, psi);
}

static int valid_state(double rho, double u) { return isfinite(rho) && isfinite(u) && rho >= 0.0; }

int rmn_exact_solve(const struct rmn_eos *eos, const struct rmn_params *params,
                    struct rmn_workspace *ws, double rho_l, double u_l, double rho_r, double u_r,
                    struct rmn_exact *sol) {
  if (!eos || !params || !sol) return RMN_EINVAL;
  int st = rmn_params_check(params);
  if (st != RMN_SUCCESS) return st;
  if (!valid_state(rho_l, u_l) || !valid_state(rho_r, u_r)) return RMN_EINVAL;
  if (rho_l == 0.0 && rho_r == 0.0) return RMN_EINVAL;

  struct rmn_exact s = {.eos = *eos,
                        .rho_l = rho_l,
                        .u_l = u_l,
                        .rho_r = rho_r,
                        .u_r = u_r,
                        .left = RMN_EXACT_RAREFACTION,
                        .right = RMN_EXACT_RAREFACTION};
  const struct rmn_eos *e = &s.eos;
  const double vacuum_p = rmn_eos_min_pressure(e);

  if (rho_l == 0.0 || rho_r == 0.0) {
    /* One dry side: a single fan into vacuum; its tail (c = 0) is the dry front. For ξ = 1 the
     * fan never reaches zero density and extends to infinity. */
    s.vacuum = 1;
    s.rho_star = 0.0;
    s.u_star = NAN;
    s.p_star = vacuum_p;
    if (rho_l == 0.0) {
      s.right_head = u_r + rmn_eos_sound_speed(e, rho_r);
      s.right_tail = e->isothermal ? -HUGE_VAL : u_r - rmn_eos_psi(e, rho_r);
      s.left_head = s.left_tail = s.right_tail;
    } else {
      s.left_head = u_l - rmn_eos_sound_speed(e, rho_l);
      s.left_tail = e->isothermal ? HUGE_VAL : u_l + rmn_eos_psi(e, rho_l);
      s.right_head = s.right_tail = s.left_tail;
    }
    *sol = s;
    return RMN_SUCCESS;
  }

  const double psi_l = rmn_eos_psi(e, rho_l), psi_r = rmn_eos_psi(e, rho_r);
  const double p_l = rmn_eos_pressure(e, rho_l), p_r = rmn_eos_pressure(e, rho_r);
  const double c_l = rmn_eos_sound_speed(e, rho_l), c_r = rmn_eos_sound_speed(e, rho_r);

  /* Two rarefactions: both f_K on their ψ branch, closed form. Vacuum when ψ* ≤ 0 (ξ > 1). */
  const double psi_two_rarefactions = 0.5 * (psi_l + psi_r) - 0.5 * (u_r - u_l);
  if (!e->isothermal && psi_two_rarefactions <= 0.0) {
    s.vacuum = 1;
    s.rho_star = 0.0;
    s.u_star = NAN;
    s.p_star = vacuum_p;
    s.left_head = u_l - c_l;
    s.left_tail = u_l + psi_l;
    s.right_tail = u_r - psi_r;
    s.right_head = u_r + c_r;
    *sol = s;
    return RMN_SUCCESS;
  }

  const double rho_min = fmin(rho_l, rho_r), rho_max = fmax(rho_l, rho_r);
  double rho_star;
  if (rmn_exact_star_function(e, rho_min, rho_l, u_l, rho_r, u_r) >= 0.0) {
    rho_star = rmn_eos_density_from_psi(e, psi_two_rarefactions);
  } else {
    if (!ws) return RMN_EINVAL;
    ws->star_data = (struct rmn_star_data){.eos = e,
                                           .rho_l = rho_l,
                                           .u_l = u_l,
                                           .p_l = p_l,
                                           .psi_l = psi_l,
                                           .rho_r = rho_r,
                                           .u_r = u_r,
                                           .p_r = p_r,
                                           .psi_r = psi_r,
                                           .lo = 0.0,
                                           .hi = HUGE_VAL};
    double lo = rho_min, hi = rho_max;
    if (GSL_FN_EVAL(&ws->star, hi) < 0.0) {
      /* Two shocks: grow the bracket until the function changes sign. */
      lo = rho_max;
      int k = 0;
      do {
        hi *= 2.0;
        if (++k > 2000 || !isfinite(hi)) return RMN_ENOCONV;
      } while (GSL_FN_EVAL(&ws->star, hi) < 0.0);
      lo = 0.5 * hi > lo ? 0.5 * hi : lo;
    }
    ws->star_data.lo = lo;
    ws->star_data.hi = hi;
    /* Newton (GSL) from the acoustic estimate, kept inside the bracket; converges in two or
     * three steps for the nearly equal states of a finite-volume flux. Should an iterate leave
     * the bracket or the budget run out, Brent on the bracket takes over. */
    const double rho_bar = 0.5 * (rho_l + rho_r);
    double guess = rho_bar * (1.0 - 0.5 * (u_r - u_l) / rmn_eos_sound_speed(e, rho_bar));
    if (!(guess > lo && guess < hi)) guess = 0.5 * (lo + hi);
    int it = 0, converged = 0;
    const int newton_budget = params->max_iter < 8 ? params->max_iter : 8;
    if (gsl_root_fdfsolver_set(ws->secant_newton, &ws->star_fdf, guess) == GSL_SUCCESS) {
      double x = guess;
      while (!converged && it < newton_budget) {
        ++it;
        if (gsl_root_fdfsolver_iterate(ws->secant_newton) != GSL_SUCCESS) break;
        double x_new = gsl_root_fdfsolver_root(ws->secant_newton);
        if (!(x_new >= lo && x_new <= hi)) break;
        converged = fabs(x_new - x) <= params->tol_rel * x_new;
        x = x_new;
      }
      if (converged) rho_star = x;
    }
    if (!converged) {
      if (gsl_root_fsolver_set(ws->brent, &ws->star, lo, hi) != GSL_SUCCESS) return RMN_ENOCONV;
      int status = GSL_CONTINUE;
      while (status == GSL_CONTINUE && it < params->max_iter) {
        ++it;
        if (gsl_root_fsolver_iterate(ws->brent) != GSL_SUCCESS) return RMN_ENOCONV;
        status = gsl_root_test_interval(gsl_root_fsolver_x_lower(ws->brent),
                                        gsl_root_fsolver_x_upper(ws->brent), 0.0, params->tol_rel);
      }
      if (status != GSL_SUCCESS) return RMN_ENOCONV;
      rho_star = gsl_root_fsolver_root(ws->brent);
    }
    s.iterations = it;
  }

  const double f_l = rmn_star_f_side_(e, rho_star, rho_l, p_l, psi_l);
  const double f_r = rmn_star_f_side_(e, rho_star, rho_r, p_r, psi_r);
  s.rho_star = rho_star;
  s.u_star = 0.5 * (u_l + u_r) + 0.5 * (f_r - f_l);
  s.p_star = rmn_eos_pressure(e, rho_star);
  const double c_star = rmn_eos_sound_speed(e, rho_star);
  if (rho_star > rho_l) {
    s.left = RMN_EXACT_SHOCK;
    s.left_head = s.left_tail = (rho_star * s.u_star - rho_l * u_l) / (rho_star - rho_l);
  } else {
    s.left_head = u_l - c_l;
    s.left_tail = s.u_star - c_star;
  }
  if (rho_star > rho_r) {
    s.right = RMN_EXACT_SHOCK;
    s.right_head = s.right_tail = (rho_star * s.u_star - rho_r * u_r) / (rho_star - rho_r);
  } else {
    s.right_head = u_r + c_r;
    s.right_tail = s.u_star + c_star;
  }
  *sol = s;
  return RMN_SUCCESS;
}

void rmn_exact_sample(const struct rmn_exact *sol, double s, double *rho, double *u) {
  const struct rmn_eos *e = &sol->eos;
  /* In a vacuum region ρ = 0; the velocity is undefined there and 0 is returned so that fluxes
   * computed from samples stay finite. */
  if (sol->rho_l == 0.0) {
    if (s >= sol->right_head) {
      *rho = sol->rho_r, *u = sol->u_r;
    } else if (s > sol->right_tail) {
      right_fan(e, sol->u_r - rmn_eos_psi(e, sol->rho_r), s, rho, u);
    } else {
      *rho = 0.0, *u = 0.0;
    }
    return;
  }
  if (sol->rho_r == 0.0) {
    if (s <= sol->left_head) {
      *rho = sol->rho_l, *u = sol->u_l;
    } else if (s < sol->left_tail) {
      left_fan(e, sol->u_l + rmn_eos_psi(e, sol->rho_l), s, rho, u);
    } else {
      *rho = 0.0, *u = 0.0;
    }
    return;
  }
  if (sol->vacuum) {
    if (s <= sol->left_head) {
      *rho = sol->rho_l, *u = sol->u_l;
    } else if (s < sol->left_tail) {
      left_fan(e, sol->u_l + rmn_eos_psi(e, sol->rho_l), s, rho, u);
    } else if (s <= sol->right_tail) {
      *rho = 0.0, *u = 0.0;
    } else if (s < sol->right_head) {
      right_fan(e, sol->u_r - rmn_eos_psi(e, sol->rho_r), s, rho, u);
    } else {
      *rho = sol->rho_r, *u = sol->u_r;
    }
    return;
  }
  if (s <= sol->u_star) {
    if (sol->left == RMN_EXACT_SHOCK ? s < sol->left_head : s <= sol->left_head) {
      *rho = sol->rho_l, *u = sol->u_l;
    } else if (sol->left == RMN_EXACT_SHOCK || s >= sol->left_tail) {
      *rho = sol->rho_star, *u = sol->u_star;
    } else {
      left_fan(e, sol->u_l + rmn_eos_psi(e, sol->rho_l), s, rho, u);
    }
  } else {
    if (sol->right == RMN_EXACT_SHOCK ? s > sol->right_head : s >= sol->right_head) {
      *rho = sol->rho_r, *u = sol->u_r;
    } else if (sol->right == RMN_EXACT_SHOCK || s <= sol->right_tail) {
      *rho = sol->rho_star, *u = sol->u_star;
    } else {
      right_fan(e, sol->u_r - rmn_eos_psi(e, sol->rho_r), s, rho, u);
    }
  }
}
