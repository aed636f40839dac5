/*
 * SABRE sph/ — imposed volume flux in periodic flows, M §5 (docs/sph-robin.md §4):
 *
 *   Q_SPH = (1/Δr_A) Σ_{b ∈ P_A} V_b v_b·n_A = A ṽ                               M(56–57)
 *   F^n   = (v − 2ṽ^{n−1} + ṽ^{n−2}) / (2Δt)                   (baseline)          M(58)
 *   F^n   = (v − ṽ^{n−1})/Δt^n − (ṽ^{n−1} − ṽ^{n−2})/Δt^{n−1} + F^{n−1}          M(62)
 *         = (v − 2ṽ^{n−1} + ṽ^{n−2}) / Δt + F^{n−1}            (constant Δt)       M(63)
 *
 * v = Q/A is the target cross-averaged velocity, ṽ^n the measured one after step n, F^n the
 * driving acceleration [m/s²] applied along n_A during step n (from t^{n−1} to t^n). M(63) keeps
 * the internal (pressure + viscous) force of the previous step, from M(60); M(58) ignores it and
 * settles below the target (kept only to reproduce the paper's comparison, Fig. 4).
 *
 * Pure functions: no allocation, no static state. sph_flux_measure() returns 0 or −1 (bad input).
 */
#ifndef SABRE_SPH_FLUX_H
#define SABRE_SPH_FLUX_H

#include <stddef.h>

#include "sabre/sph.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A measuring slice: particles b with −width/2 ≤ (r_b − point)·normal < width/2 (minimum image
 *  in periodic directions), so that adjacent slices of one width tile space without overlap. */
struct sph_flux_slice {
  double point[3];  /**< a point of the slice's mid-plane [m] */
  double normal[3]; /**< unit normal n_A, the flow direction */
  double width;     /**< Δr_A > 0 [m] (the paper uses 2Δr) */
  double area;      /**< cross-section A > 0 [m^(d−1)] (2D: channel height; 1D: 1) */
};

/**
 * Volume flux Q_SPH, M(56) [m^d/s], and the cross-averaged velocity ṽ = Q_SPH/A, M(57) [m/s]
 * (v_mean may be NULL), over n particles with positions x[k][b], velocities v[k][b] (k < dim;
 * the structure-of-arrays layout of struct sph_parts) and volumes vol[b] [m^d]. dom may be NULL
 * (no periodic wrap). Returns 0, or −1 (outputs NaN) for NULL arrays with n > 0, dim ∉ {1, 2, 3},
 * a normal not of unit length within 1e-9, or width/area not positive and finite.
 */
int sph_flux_measure(int dim, const struct sph_flux_slice *slice, const struct sph_domain *dom,
                     size_t n, const double *const x[3], const double *const v[3],
                     const double *vol, double *q, double *v_mean);

/** The same over a particle store (fluid), with V_b = m_b/ρ_b. */
int sph_flux_measure_parts(int dim, const struct sph_flux_slice *slice,
                           const struct sph_domain *dom, const struct sph_parts *p, double *q,
                           double *v_mean);

/** Driving acceleration of M(58) (baseline, Violeau 2012): (v − 2ṽ^{n−1} + ṽ^{n−2})/(2Δt). */
double sph_flux_force_m58(double v_target, double vt_nm1, double vt_nm2, double dt);

/**
 * Driving acceleration of M(62), the variable-step form of M(63) (equal to it when
 * dt_n = dt_nm1): F^n = (v − ṽ^{n−1})/Δt^n − (ṽ^{n−1} − ṽ^{n−2})/Δt^{n−1} + F^{n−1}.
 */
double sph_flux_force_m63(double v_target, double vt_nm1, double vt_nm2, double dt_n, double dt_nm1,
                          double f_nm1);

enum sph_flux_method { SPH_FLUX_M63 = 0, SPH_FLUX_M58 = 1 };

/** History of one controller (the solver keeps one per imposed flux). */
struct sph_flux_ctrl {
  enum sph_flux_method method;
  double v_target; /**< v = Q/A [m/s] */
  double vt1, vt2; /**< ṽ^{n−1}, ṽ^{n−2} [m/s] */
  double dt1;      /**< Δt^{n−1} [s] */
  double force;    /**< F^{n−1} [m/s²] (the last force returned) */
  long steps;      /**< updates so far */
};

/** Start a controller with the initial driving acceleration force0 (e.g. 0 or a guess). */
void sph_flux_ctrl_init(struct sph_flux_ctrl *c, enum sph_flux_method method, double v_target,
                        double force0);

/**
 * Step n: given ṽ^{n−1} measured at the start of the step (M(56–57)) and the step Δt^n, return
 * F^n. At the first update there is no ṽ^{n−2} and no Δt^{n−1}: the flow is taken as steady before
 * (ṽ^{n−2} = ṽ^{n−1}, Δt^{n−1} = Δt^n), so M(63) gives F^1 = (v − ṽ^0)/Δt + F^0, the force that
 * would reach the target in one step if the internal force were F^0's opposite.
 */
double sph_flux_ctrl_update(struct sph_flux_ctrl *c, double vt_measured, double dt);

#ifdef __cplusplus
}
#endif

#endif
