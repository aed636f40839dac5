/*
 * SABRE sph/ — wave generators for open boundaries: surface elevation, velocity and pressure of
 * two analytical waves at given points and times. Formulas, sources, validity and verification:
 * docs/sph-waves.md.
 *
 *   - Stokes fifth order, J. D. Fenton, "A fifth-order Stokes theory for steady waves", J. Waterway
 *     Port Coastal Ocean Eng. 111(2) (1985) 216–234: the series in ε = kH/2 with the coefficients
 *     A_ij, B_ij, C_0..C_4, D_2, D_4, E_2, E_4, functions of kd only (S = sech 2kd). A periodic
 *     wave of permanent form travelling towards +x over a flat bed.
 *   - Solitary wave of J(42–47) (first-order Korteweg–de Vries), travelling along (cos θ, sin θ).
 *
 * Conventions (both waves): SI units; the bed is the plane z = 0 and z points up (against
 * gravity); η is the elevation of the free surface ABOVE THE BED (the water depth there, not the
 * elevation above the mean level); velocities are in the fixed (laboratory) frame; p is the gauge
 * pressure (zero on the free surface, positive in the water) for the density ρ0 the caller gives.
 *
 * Like sph_robin.h, this part of the library never prints and never exits: every fallible call
 * returns a status (SPH_WAVE_SUCCESS == 0) that sph_wave_strerror() names, and the _init
 * functions also write a one-line message naming the offending parameter by its field name
 * ("height: ...", "period: ..."), so that a command line can prefix "--" and a case file its key.
 * The structs hold no pointers and need no freeing. The only allocation is GSL's root solver inside
 * sph_stokes5_init() when a period is given (freed before it returns). GSL's default error handler
 * aborts on a GSL error: applications turn it off once at start-up (the SABRE programs and tests
 * do). Evaluation calls are pure functions of their arguments: no allocation, no state,
 * thread-safe.
 */
#ifndef SABRE_SPH_WAVES_H
#define SABRE_SPH_WAVES_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SPH_WAVE_STATUS_LIST(X)                                                                \
  X(SPH_WAVE_SUCCESS, 0, "success")                                                            \
  X(SPH_WAVE_EINVAL, 1,                                                                        \
    "invalid parameter (NULL pointer, NaN or infinite value, non-positive depth, height, "     \
    "length, period, amplitude, g or rho0, or neither or both of length and period)")          \
  X(SPH_WAVE_EBREAK, 2,                                                                        \
    "wave steeper or higher than the breaking limit (Stokes: H/L > 0.142 tanh kd; solitary: "  \
    "A/D > 0.78): no steady wave exists there and the series is not valid")                    \
  X(SPH_WAVE_ESHALLOW, 3,                                                                      \
    "wave too long for the depth: Ursell number H L^2/d^3 above the limit of the fifth-order " \
    "Stokes series (a cnoidal theory is needed there)")                                        \
  X(SPH_WAVE_ECURRENT, 4,                                                                      \
    "the mean current sweeps the wave back or stops it (phase speed c <= 0)")                  \
  X(SPH_WAVE_ENOWAVE, 5,                                                                       \
    "no wave of the given period within the validity range (too long for the depth, steeper "  \
    "than the breaking limit, or blocked by the current)")                                     \
  X(SPH_WAVE_ENOMEM, 6, "memory allocation failed")                                            \
  X(SPH_WAVE_ENOCONV, 7, "root finding did not converge")                                      \
  X(SPH_WAVE_EOUTSIDE, 8,                                                                      \
    "point outside the water (above the free surface or below the bed): the values are the "   \
    "formulas evaluated as written, with no physical meaning")

enum sph_wave_status {
#define SPH_WAVE_X_ENUM(name, value, text) name = value,
  SPH_WAVE_STATUS_LIST(SPH_WAVE_X_ENUM)
#undef SPH_WAVE_X_ENUM
};

/** Human-readable text of a status code (static storage, never NULL). */
const char *sph_wave_strerror(int status);
/** Symbolic name of a status code, e.g. "SPH_WAVE_EBREAK" (static storage, never NULL). */
const char *sph_wave_status_name(int status);

/** The wave at one point and time (fixed frame, bed at z = 0). */
struct sph_wave_point {
  double eta;     /**< free-surface elevation above the bed at (x[, y], t) [m] */
  double eta_x;   /**< ∂η/∂x [-] */
  double eta_y;   /**< ∂η/∂y [-] (0 for the Stokes wave) */
  double eta_t;   /**< ∂η/∂t [m/s] */
  double u, v, w; /**< velocity components along x, y, z [m/s] (v = 0 for the Stokes wave) */
  double p;       /**< gauge pressure [Pa] */
};

/* ---------------------------------------------------------------------------------------------
 * Stokes fifth order (Fenton 1985)
 * ------------------------------------------------------------------------------------------- */

/** Breaking limit of a steady wave, H/L ≤ SPH_WAVE_BREAKING tanh(kd) (Miche 1944). */
#define SPH_WAVE_BREAKING 0.142

/** Input of sph_stokes5_init(). */
struct sph_stokes5_params {
  double depth;      /**< d > 0: mean water depth [m] (mean of η over a wave length) */
  double height;     /**< H > 0: crest-to-trough height [m] (amplitude A = H/2: pass 2A) */
  double length;     /**< L > 0: wave length [m], or 0 when `period` is given */
  double period;     /**< T > 0: period in the fixed frame [s], or 0 when `length` is given */
  double current;    /**< u_E: mean Eulerian current (Stokes' first definition) [m/s], default 0 */
  double g;          /**< gravity > 0 [m/s²], default 9.81 */
  double rho0;       /**< density > 0 for the pressure [kg/m³], default 1000 */
  double ursell_max; /**< largest accepted Ursell number H L²/d³ [-], default SPH_WAVE_URSELL_MAX */
};

/**
 * Default largest Ursell number H L²/d³ of the Stokes wave. The series is one in ε = kH/2 whose
 * coefficients grow like (1 − S)^−n ∝ (kd)^−2n in shallow water, so that its effective small
 * parameter there is ε/(kd)³ ∝ H L²/d³. At U = 20 and half the breaking height the series misses
 * the kinematic free-surface condition by 4 % of max|w| and the dynamic one by 0.5 % of gH; at
 * U = 40 by 34 % and 4 % (measured, docs/sph-waves.md §2.4).
 */
#define SPH_WAVE_URSELL_MAX 20.0

/** Defaults: depth, height, length and period 0 (to be set), current 0, g 9.81, rho0 1000,
 *  ursell_max SPH_WAVE_URSELL_MAX. */
void sph_stokes5_params_init(struct sph_stokes5_params *p);

/**
 * A Stokes wave ready for evaluation: Fenton's solution resolved for one set of parameters.
 * Fields are read-only results of sph_stokes5_init(); no pointers inside (copy it freely).
 *
 * Potential-flow solution in the frame moving with the wave (X = x − ct), Fenton (1985):
 *   kη = kd + Σ_{j=1..5} b[j] cos jθ,                θ = k(x − ct),
 *   u = u_E + C0 √(g/k) Σ_{i,j} ε^i j A_ij cosh(jkz) cos jθ,
 *   w =       C0 √(g/k) Σ_{i,j} ε^i j A_ij sinh(jkz) sin jθ,
 *   c = u_E + ū,   ū √(k/g) = C0 + ε² C2 + ε⁴ C4,
 *   p/ρ0 = R − g z − ½((u − c)² + w²),   R k/g = ½ C0² + kd + ε² E2 + ε⁴ E4 (Bernoulli),
 *   q √(k³/g) = C0 kd + ε² (C2 kd + D2) + ε⁴ (C4 kd + D4)  (volume flux under the wave, wave
 * frame).
 */
struct sph_stokes5 {
  double d, H, u_E, g, rho0; /**< the parameters [m, m, m/s, m/s², kg/m³] */
  double k;                  /**< wave number 2π/L [1/m] */
  double L;                  /**< wave length [m] */
  double c;                  /**< phase speed in the fixed frame, u_E + ū [m/s] */
  double T;                  /**< period in the fixed frame, L/c [s] */
  double omega;              /**< angular frequency kc [1/s] */
  double eps;                /**< ε = kH/2 [-] */
  double kd;                 /**< k d [-] */
  double ubar;               /**< ū: mean fluid speed in the frame of the wave [m/s] */
  double R;                  /**< Bernoulli constant in the frame of the wave [m²/s²] */
  double q;                  /**< volume flux per unit width in the frame of the wave [m²/s] */
  double u_mass; /**< mass-transport velocity c − q/d (Stokes' 2nd definition) [m/s] */
  double ursell; /**< H L²/d³ [-] */
  double C0, C2, C4, D2, D4, E2, E4;   /**< Fenton's coefficients at kd [-] */
  double B22, B31, B42, B44, B53, B55; /**< Fenton's surface coefficients at kd [-] */
  /**
   * Fenton's A_ij scaled by e^{j kd}, Â_ij = A_ij e^{jkd}, finite at any depth (A_ij itself and
   * cosh(jkz) overflow separately in deep water). Index [i][j], 1 ≤ j ≤ i ≤ 5, j ≡ i mod 2.
   */
  double A_hat[6][6];
  double b[6]; /**< surface harmonics kη = kd + Σ b[j] cos jθ, j = 1..5 [-] */
  double a[6]; /**< velocity harmonics Σ_i ε^i Â_ij, j = 1..5 [-] */
};

/**
 * Resolve the wave of `p` into `w`: the wave number (from the length, or from the period by
 * solving the dispersion relation ω = k c(k), with c(k) the fifth-order phase speed above
 * including the current, by GSL Brent on a bracket inside the validity range; the smallest such k
 * when the current makes several), then Fenton's coefficients.
 *
 * Errors (w is then unusable; msg, if not NULL, receives "<field>: <why>" in at most msglen bytes):
 *   SPH_WAVE_EINVAL     a parameter NaN, infinite or not positive (current: not finite), or
 *                       neither or both of length and period given;
 *   SPH_WAVE_EBREAK     H/L > SPH_WAVE_BREAKING tanh(kd), or H ≥ 0.89 d (no valid wave at all);
 *   SPH_WAVE_ESHALLOW   H L²/d³ > ursell_max (length given);
 *   SPH_WAVE_ECURRENT   c ≤ 0 (length given; the wave must travel towards +x);
 *   SPH_WAVE_ENOWAVE    no wave of that period within the range (period given);
 *   SPH_WAVE_ENOMEM, SPH_WAVE_ENOCONV   root solver allocation or convergence failure.
 */
int sph_stokes5_init(struct sph_stokes5 *w, const struct sph_stokes5_params *p, char *msg,
                     size_t msglen);

/**
 * η, ∂η/∂x, ∂η/∂t, u, w and p of the wave at (x, z) and time t (v = eta_y = 0). Cost: a few
 * exponentials and one sine/cosine pair.
 * Returns SPH_WAVE_SUCCESS inside the water (0 ≤ z ≤ η), SPH_WAVE_EINVAL for a NULL pointer or a
 * non-finite coordinate (out untouched), and SPH_WAVE_EOUTSIDE above the surface or below the bed:
 * η and its derivatives are then valid, u, w and p the series evaluated as written (analytic
 * continuation; p < 0 above the surface), or NaN farther than one wave length from the water.
 */
int sph_stokes5_eval(const struct sph_stokes5 *w, double x, double z, double t,
                     struct sph_wave_point *out);

/* ---------------------------------------------------------------------------------------------
 * Solitary wave, J(42–47)
 * ------------------------------------------------------------------------------------------- */

/** Largest accepted A/D of the solitary wave (the highest solitary wave, McCowan 1894). */
#define SPH_WAVE_SOLITARY_MAX 0.78

/** Input of sph_solitary_init(). */
struct sph_solitary_params {
  double depth;     /**< D > 0: still water depth [m] */
  double amplitude; /**< A > 0: crest elevation above the still water level [m], A/D ≤ 0.78 */
  double angle; /**< θ: direction of travel (cos θ, sin θ) from +x towards +y [rad], default 0 */
  double x0;    /**< position of the crest at t = 0 along the direction of travel [m], default
                     0 (J's x_0; see sph_solitary) */
  double g;     /**< gravity > 0 [m/s²], default 9.81 */
  double rho0;  /**< density > 0 for the pressure [kg/m³], default 1000 */
};

/** Defaults: depth and amplitude 0 (to be set), angle 0, x0 0, g 9.81, rho0 1000. */
void sph_solitary_params_init(struct sph_solitary_params *p);

/**
 * A solitary wave ready for evaluation, J(42–47) with ξ = x cos θ + y sin θ − c t − x0:
 *   η = A sech²(k ξ),  h = D + η,  (u, v) = c (η/h) (cos θ, sin θ),  w = (z/h) ∂η/∂t,
 *   k = √(3A/(4D³)),   c = √(g(A + D)),   p = ρ0 g (h − z).
 * η here is J's elevation above the still water level; sph_wave_point.eta is h, the elevation
 * above the bed, like the Stokes wave's.
 * Two departures from the printed equations (docs/sph-waves.md §3.2):
 *   - J(44) reads p = ρ g (z − h), negative in the water; the gauge pressure is ρ0 g (h − z)
 *     (hydrostatic below the moving surface, zero on it, positive in the water), used here.
 *   - J puts x_0 = −4k, a length written as an inverse length; x0 here is a length in metres
 *     inside the bracket of J(42), so that the crest passes ξ = 0 where x cos θ + y sin θ = x0 +
 *     c t. J's intent (the wave out of the domain at t = 0) is x0 = −4/k: η = A sech² 4 ≈ 1.3e-3 A
 *     at x = 0.
 * The velocity of J(45–47) is the depth-uniform long-wave velocity: it conserves mass in the
 * depth-integrated sense, ∂η/∂t + ∇·(h (u, v)) = 0 exactly, but is not divergence-free pointwise.
 */
struct sph_solitary {
  double D, A, g, rho0; /**< the parameters [m, m, m/s², kg/m³] */
  double theta;         /**< θ [rad] */
  double cos_theta, sin_theta;
  double x0; /**< [m] */
  double k;  /**< √(3A/(4D³)) [1/m] */
  double c;  /**< √(g(A + D)) [m/s] */
};

/**
 * Check `p` and fill `s`. Errors (msg, if not NULL, receives "<field>: <why>"):
 * SPH_WAVE_EINVAL (a parameter NaN, infinite or not positive), SPH_WAVE_EBREAK (A/D > 0.78).
 */
int sph_solitary_init(struct sph_solitary *s, const struct sph_solitary_params *p, char *msg,
                      size_t msglen);

/**
 * η (= h, above the bed), its derivatives, u, v, w and p of the solitary wave at (x, y, z), time t.
 * Returns SPH_WAVE_SUCCESS inside the water (0 ≤ z ≤ h), SPH_WAVE_EINVAL for a NULL pointer or a
 * non-finite coordinate (out untouched), SPH_WAVE_EOUTSIDE above the surface or below the bed
 * (values evaluated as written: p < 0 above the surface).
 */
int sph_solitary_eval(const struct sph_solitary *s, double x, double y, double z, double t,
                      struct sph_wave_point *out);

/**
 * `sabre-sph wave stokes5|solitary [options] --at ...`: one JSON object per point on stdout
 * (docs/sph-waves.md §4). Returns the exit code; bad input exits with CMN_EXIT_INPUT.
 */
int sph_cmd_wave(int argc, char **argv);

#ifdef __cplusplus
}
#endif

#endif
