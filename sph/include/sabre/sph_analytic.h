/*
 * SABRE sph/ — analytical reference solutions used to verify the SPH solver.
 *
 * Robin wave, M §6.2 (derivation, convergence and measured truncation error: docs/sph-robin.md):
 *
 *   u_tt = u_xx on [0, 1],   ∂u/∂n = u at x = 0 and x = 1 (n into the domain),   M(75–76)
 *   u(x, 0) = 0,   u_t(x, 0) = sin(2πx),                                          M(77)
 *   u(x, t) = Σ_{i≥1} α_i sin(κ_i t) [sin(κ_i x) + κ_i cos(κ_i x)],                M(78)
 *
 * κ_i the i-th positive root of tan κ = 2κ/(κ² − 1), M(79). Dimensionless x and t.
 * The eigenfunctions φ_i = sin κ_i x + κ_i cos κ_i x are orthogonal in the plain L²(0, 1) product
 * (regular Sturm–Liouville problem, weight 1), ‖φ_i‖² = (κ_i² + 3)/2, and the projection of
 * sin(2πx) is closed form: α_i = −8π/((κ_i² − 4π²)(κ_i² + 3)) for even i, 0 for odd i.
 *
 * Status codes are those of sabre/sph_robin.h (SPH_ROBIN_SUCCESS == 0, ...).
 */
#ifndef SABRE_SPH_ANALYTIC_H
#define SABRE_SPH_ANALYTIC_H

#include <stddef.h>

#include "sabre/sph_robin.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * i-th root κ_i (i ≥ 1) of M(79). Written as κ − 2 arctan(1/κ) = (i − 1)π (no poles), whose
 * left side increases strictly, so the root is bracketed in [(i − 1)π, iπ] and found by GSL Brent
 * to |Δκ| ≤ 4 ε κ. Returns SPH_ROBIN_SUCCESS, SPH_ROBIN_EINVAL (i = 0, NULL) or
 * SPH_ROBIN_ENOCONV.
 */
int sph_robin_wave_root(size_t i, double *kappa);

/** Truncated series M(78): modes i = 1..n_terms. */
struct sph_robin_wave {
  size_t n_terms;
  double *kappa; /**< κ_i, i = 1..n_terms at [i − 1], increasing */
  double *alpha; /**< α_i of M(78) (0 for odd i) */
  /**
   * 1 (default): u_t and u_x include the closed-form sum of the leading asymptotic terms of the
   * modes beyond n_terms (Kummer's transformation), which brings their truncation error from
   * O(1/n_terms) to O(1/n_terms²). It adds functions of x ± t only, so the wave equation still
   * holds exactly, and it vanishes at x = 0, 1 in u_x, so the Robin condition is untouched.
   * 0: plain truncated sums (to measure the truncation error). u is always the plain sum.
   */
  int tail;
};

/** Compute κ_i and α_i for i = 1..n_terms (n_terms ≥ 1). Returns SPH_ROBIN_SUCCESS,
 *  SPH_ROBIN_EINVAL, SPH_ROBIN_ENOMEM or SPH_ROBIN_ENOCONV (w is then empty, safe to free). */
int sph_robin_wave_init(struct sph_robin_wave *w, size_t n_terms);
void sph_robin_wave_free(struct sph_robin_wave *w);

/**
 * u(x, t), u_t(x, t) and u_x(x, t) of the truncated series (any pointer may be NULL).
 * x ∈ [0, 1], t ≥ 0 (not checked). Cost: n_terms sines and cosines.
 */
void sph_robin_wave_eval(const struct sph_robin_wave *w, double x, double t, double *u, double *u_t,
                         double *u_x);

#ifdef __cplusplus
}
#endif

#endif
