/* Internal: the solver workspace (GSL solvers preallocated so that solving does not allocate). */
#ifndef SABRE_RIEMANN_WORKSPACE_H
#define SABRE_RIEMANN_WORKSPACE_H

#include <gsl/gsl_multiroots.h>
#include <gsl/gsl_roots.h>

#include "sabre/riemann.h"

/* Data of the moving-shock Rankine–Hugoniot system (docs/theory.md §1.1). */
struct rmn_rh_data {
  const struct rmn_eos *eos;
  double rho_i; /* density ahead of the shock (interior) */
  double drho;  /* ρ2 − ρ_i (imposed pressure) */
  double dp;    /* p2 − p_i (imposed pressure) */
  double du;    /* u2 − u_i (imposed velocity) */
};

/* Data of the exact solver's star function. */
struct rmn_star_data {
  const struct rmn_eos *eos;
  double rho_l, u_l, p_l, psi_l, rho_r, u_r, p_r, psi_r;
  double lo, hi; /* bracket of the root; outside it the functions return NaN (no evaluation) */
};

struct rmn_workspace {
  gsl_multiroot_fdfsolver *newton;
  gsl_vector *x;
  gsl_multiroot_function_fdf rh_pressure, rh_velocity;
  struct rmn_rh_data rh;
  gsl_root_fsolver *brent;
  gsl_root_fdfsolver *secant_newton;
  gsl_function star;
  gsl_function_fdf star_fdf;
  struct rmn_star_data star_data;
};

/* Star function pieces, shared by exact.c and its tests through the public wrapper. */
double rmn_star_f_side_(const struct rmn_eos *eos, double rho, double rho_k, double p_k,
                        double psi_k);

#endif
