/*
 * Pair geometry shared by the operators, the continuity equation and the diagnostics:
 * r_ab = r_a − r_b (minimum image), |r_ab|, w_ab and dw/dr / r (so that ∇_a w_ab = that · r_ab).
 */
#ifndef SPH_OPERATORS_PAIR_H
#define SPH_OPERATORS_PAIR_H

#include <math.h>

#include "kernel.h"
#include "sabre/sph.h"

struct sph_pair {
  double r[3];        /**< r_a − r_b [m] */
  double dist;        /**< |r_ab| [m] */
  double w;           /**< w(|r_ab|) [1/m^d] */
  double dwdr_over_r; /**< w'(r)/r [1/m^(d+2)], 0 at r = 0 */
};

/** Fill pr for particles a (of pa) and b (of pb). Returns 0 when b lies outside the support. */
static inline int sph_pair_eval(const struct sph_kernel *k, const struct sph_system *s,
                                const struct sph_parts *pa, size_t a, const struct sph_parts *pb,
                                size_t b, struct sph_pair *pr) {
  const double xa[3] = {pa->x[0][a], pa->x[1][a], pa->x[2][a]};
  const double xb[3] = {pb->x[0][b], pb->x[1][b], pb->x[2][b]};
  double d[3];
  sph_domain_delta(&s->domain, xb, xa, d); /* d = r_a − r_b */
  const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double support = 2.0 * k->h;
  if (r2 >= support * support) return 0;
  const double r = sqrt(r2);
  for (int c = 0; c < 3; c++) pr->r[c] = d[c];
  pr->dist = r;
  pr->w = sph_kernel_w_inline(k, r);
  pr->dwdr_over_r = r > 0.0 ? sph_kernel_dwdr_over_r_inline(k, r) : 0.0;
  return 1;
}

/* 1/ρ² of a particle, as the pair loops use it (one expression, so that the fused loop's
 * per-particle value and the operators' per-pair value have the same bits). */
static inline double sph_inv_rho2(double rho) { return 1.0 / (rho * rho); }

/* The pressure pair term of M(37) with k = 1 before w'/r: V_b (ρ_a/ρ_b f_b + ρ_b/ρ_a f_a) =
 * m_b (ρ_a f_b/ρ_b² + f_a/ρ_a), from m_b, ρ_a, 1/ρ_b², f_b and f_a/ρ_a: no division per pair.
 * (With the open difference form, f_b − fc and (f_a − fc)/ρ_a.) */
static inline double sph_pair_pressure_k1(double m_b, double rho_a, double inv_rho2_b, double f_b,
                                          double fa_over_rho_a) {
  return m_b * (rho_a * inv_rho2_b * f_b + fa_over_rho_a);
}

/** (ρ_a/ρ_b)^k with exact paths for k = 0 and 1 (M 37–38). */
static inline double sph_rho_ratio_k(double rho_a, double rho_b, double k) {
  if (k == 0.0) return 1.0;
  if (k == 1.0) return rho_a / rho_b;
  return pow(rho_a / rho_b, k);
}

#endif
