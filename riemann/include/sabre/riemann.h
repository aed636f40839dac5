/*
 * SABRE riemann/ — the boundary (partial) Riemann problem and the exact two-wave Riemann solver of
 * the one-dimensional barotropic Euler equations
 *
 *     ∂ρ/∂t + ∂(ρu)/∂x = 0,   ∂(ρu)/∂t + ∂(ρu² + p(ρ))/∂x = 0,
 *
 * with the Tait equation of state. Equation numbers J(n) refer to Joly, Violeau, Leroy, Ferrand,
 * "Applying Riemann solvers to open boundaries in free surface and confined flows", SPHERIC 2016;
 * "docs/theory.md §n" to the theory notes shipped with the SABRE sources. All quantities are SI:
 * ρ in kg/m³, p in Pa (relative to the reference state, so p(ρ0) = 0), velocities and sound
 * speeds in m/s.
 *
 * Conventions (GSL/SUNDIALS style):
 *   - every fallible function returns an int status, RMN_SUCCESS (0) or one of enum rmn_status;
 *     rmn_strerror() names it. The library never prints, never exits and keeps no static state.
 *   - the caller owns every struct; the only allocated object is struct rmn_workspace
 *     (rmn_workspace_alloc / rmn_workspace_free), which holds the GSL solvers so that solving does
 *     not allocate. A workspace serves one thread at a time; give each thread its own.
 *   - the library calls GSL. GSL's default error handler aborts the program on a GSL error (for
 *     instance a singular Jacobian); an application using this library should call
 *     gsl_set_error_handler_off() once at start-up, after which such failures come back as
 *     RMN_ENOCONV. The SABRE applications and tests do so.
 *   - tolerances are parameters (struct rmn_params), never hidden constants.
 */
#ifndef SABRE_RIEMANN_H
#define SABRE_RIEMANN_H

#include <math.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * Status codes. One X-macro list generates the enum and rmn_strerror().
 * ------------------------------------------------------------------------------------------- */
#define RMN_STATUS_LIST(X)                                                              \
  X(RMN_SUCCESS, 0, "success")                                                          \
  X(RMN_EINVAL, 1, "invalid argument (NaN, infinite, or out of the documented range)")  \
  X(RMN_EDENSITY, 2, "non-positive density in a state that must be wet")                \
  X(RMN_ESUPERSONIC, 3,                                                                 \
    "state is not subsonic: |u_n| >= c, the boundary problem needs subsonic flow")      \
  X(RMN_ECAVITATION, 4, "cavitation: the imposed data require a density <= 0 (vacuum)") \
  X(RMN_ENOCONV, 5, "iterative solve did not converge")                                 \
  X(RMN_ENOMEM, 6, "memory allocation failed")                                          \
  X(RMN_ELAX, 7, "shock result violates the Lax entropy condition")                     \
  X(RMN_EUNDEFINED, 8, "linearised shock undefined for a zero interior normal velocity")

enum rmn_status {
#define RMN_X_ENUM(name, value, text) name = value,
  RMN_STATUS_LIST(RMN_X_ENUM)
#undef RMN_X_ENUM
};

/** Human-readable text of a status code (static storage, never NULL). */
const char *rmn_strerror(int status);
/** Symbolic name of a status code, e.g. "RMN_ESUPERSONIC" (static storage, never NULL). */
const char *rmn_status_name(int status);

/* ---------------------------------------------------------------------------------------------
 * Tait equation of state, J(1)/M(15), J(19), J(24–25):
 *   p(ρ) = ρ0 c0²/ξ ((ρ/ρ0)^ξ − 1)            (ξ = 1: p = c0² (ρ − ρ0))
 *   c(ρ) = c0 (ρ/ρ0)^((ξ−1)/2)
 *   ψ(ρ) = 2 c0/(ξ−1) (ρ/ρ0)^((ξ−1)/2)        (ξ = 1: ψ = c0 ln(ρ/ρ0))
 * ξ = 7 is water, ξ = 1 the isothermal gas, ξ = 2 the shallow-water equations with ρ ↔ h.
 * The pointwise functions are static inline (hot in fv1d and sph); they do not check their
 * arguments: ρ ≥ 0 and, for ξ = 1, ρ > 0. Use rmn_eos_check_density() where input is untrusted.
 * ------------------------------------------------------------------------------------------- */
struct rmn_eos {
  double rho0; /**< reference density ρ0 > 0 [kg/m³] */
  double c0;   /**< reference sound speed c0 > 0 [m/s] */
  double xi;   /**< Tait exponent ξ ≥ 1 [-] */
  /* Derived by rmn_eos_init(); do not set by hand. */
  double b;         /**< ρ0 c0²/ξ [Pa] */
  double half_xim1; /**< (ξ − 1)/2 */
  double psi_scale; /**< 2 c0/(ξ − 1), or c0 for ξ = 1 [m/s] */
  int isothermal;   /**< 1 when ξ == 1 */
  int integer_xi;   /**< ξ when ξ ∈ {2,...,7} is an integer (fast paths), else 0 */
};

/**
 * Fill *eos after checking the parameters: ρ0 > 0, c0 > 0, ξ ≥ 1, all finite.
 * Returns RMN_SUCCESS or RMN_EINVAL (and leaves *eos unchanged).
 */
int rmn_eos_init(struct rmn_eos *eos, double rho0, double c0, double xi);

/** RMN_SUCCESS when ρ is finite and > 0, RMN_EDENSITY when ρ ≤ 0, RMN_EINVAL for NaN/inf. */
int rmn_eos_check_density(double rho);

/** Lowest representable pressure, p(0) = −ρ0 c0²/ξ (−∞ for ξ = 1) [Pa]. */
double rmn_eos_min_pressure(const struct rmn_eos *eos);

/** (ρ/ρ0)^ξ with fast integer paths. */
static inline double rmn_eos_ratio_xi_(const struct rmn_eos *e, double r) {
  switch (e->integer_xi) {
    case 2:
      return r * r;
    case 3:
      return r * r * r;
    case 4: {
      double r2 = r * r;
      return r2 * r2;
    }
    case 5: {
      double r2 = r * r;
      return r2 * r2 * r;
    }
    case 6: {
      double r3 = r * r * r;
      return r3 * r3;
    }
    case 7: {
      double r3 = r * r * r;
      return r3 * r3 * r;
    }
    default:
      return pow(r, e->xi);
  }
}

/** Pressure p(ρ) [Pa], J(1). */
static inline double rmn_eos_pressure(const struct rmn_eos *e, double rho) {
  if (e->isothermal) return e->c0 * e->c0 * (rho - e->rho0);
  return e->b * (rmn_eos_ratio_xi_(e, rho / e->rho0) - 1.0);
}

/**
 * Pressure increment p(ρ_ref + δρ) − p(ρ_ref) [Pa] from the density increment δρ, without
 * cancellation for small δρ: b (ρ_ref/ρ0)^ξ expm1(ξ log1p(δρ/ρ_ref)). Used by the shock relations.
 */
static inline double rmn_eos_pressure_increment(const struct rmn_eos *e, double rho_ref,
                                                double drho) {
  if (e->isothermal) return e->c0 * e->c0 * drho;
  return e->b * rmn_eos_ratio_xi_(e, rho_ref / e->rho0) * expm1(e->xi * log1p(drho / rho_ref));
}

/**
 * Density increment δρ such that p(ρ_ref + δρ) − p(ρ_ref) = δp [kg/m³], the inverse of
 * rmn_eos_pressure_increment, accurate for small δp. Requires p(ρ_ref) + δp > p(0) (else NaN).
 */
static inline double rmn_eos_density_increment(const struct rmn_eos *e, double rho_ref, double dp) {
  if (e->isothermal) return dp / (e->c0 * e->c0);
  return rho_ref * expm1(log1p(dp / (e->b * rmn_eos_ratio_xi_(e, rho_ref / e->rho0))) / e->xi);
}

/**
 * ψ increment ψ(ρ_ref + δρ) − ψ(ρ_ref) [m/s], accurate for small δρ (J 25):
 * c0 log1p(δρ/ρ_ref) for ξ = 1, ψ(ρ_ref) expm1((ξ−1)/2 log1p(δρ/ρ_ref)) otherwise.
 */
static inline double rmn_eos_psi_increment(const struct rmn_eos *e, double rho_ref, double drho) {
  if (e->isothermal) return e->c0 * log1p(drho / rho_ref);
  double psi_ref = e->psi_scale * pow(rho_ref / e->rho0, e->half_xim1);
  return psi_ref * expm1(e->half_xim1 * log1p(drho / rho_ref));
}

/**
 * Density increment δρ with ψ(ρ_ref + δρ) − ψ(ρ_ref) = δψ [kg/m³], the inverse of
 * rmn_eos_psi_increment. For ξ > 1 requires ψ(ρ_ref) + δψ ≥ 0 (else NaN; = 0 is vacuum).
 */
static inline double rmn_eos_density_increment_from_psi(const struct rmn_eos *e, double rho_ref,
                                                        double dpsi) {
  if (e->isothermal) return rho_ref * expm1(dpsi / e->c0);
  double psi_ref = e->psi_scale * pow(rho_ref / e->rho0, e->half_xim1);
  return rho_ref * expm1(log1p(dpsi / psi_ref) / e->half_xim1);
}

/** Density ρ(p) [kg/m³], the inverse of J(1). Requires p ≥ p(0) for ξ > 1 (else NaN). */
static inline double rmn_eos_density(const struct rmn_eos *e, double p) {
  if (e->isothermal) return e->rho0 + p / (e->c0 * e->c0);
  if (e->integer_xi == 2) return e->rho0 * sqrt(1.0 + p / e->b);
  return e->rho0 * pow(1.0 + p / e->b, 1.0 / e->xi);
}

/** Sound speed c(ρ) = sqrt(dp/dρ) [m/s], J(19). */
static inline double rmn_eos_sound_speed(const struct rmn_eos *e, double rho) {
  if (e->isothermal) return e->c0;
  double r = rho / e->rho0;
  if (e->integer_xi == 3) return e->c0 * r;
  if (e->integer_xi) return r > 0.0 ? e->c0 * sqrt(rmn_eos_ratio_xi_(e, r) / r) : 0.0;
  return e->c0 * pow(r, e->half_xim1);
}

/** ψ(ρ) = ∫ c/ρ dρ [m/s], J(24–25). ψ(0) = 0 for ξ > 1; ψ → −∞ as ρ → 0 for ξ = 1. */
static inline double rmn_eos_psi(const struct rmn_eos *e, double rho) {
  if (e->isothermal) return e->c0 * log(rho / e->rho0);
  return e->psi_scale * rmn_eos_sound_speed(e, rho) / e->c0;
}

/** Sound speed from ψ: c = (ξ − 1)/2 ψ for ξ > 1, c0 for ξ = 1 [m/s]. */
static inline double rmn_eos_sound_speed_from_psi(const struct rmn_eos *e, double psi) {
  if (e->isothermal) return e->c0;
  return e->half_xim1 * psi;
}

/** Density from ψ, the inverse of J(25). For ξ > 1 requires ψ ≥ 0 (ψ = 0 is vacuum). */
static inline double rmn_eos_density_from_psi(const struct rmn_eos *e, double psi) {
  if (e->isothermal) return e->rho0 * exp(psi / e->c0);
  double s = psi / e->psi_scale; /* = (ρ/ρ0)^((ξ−1)/2) */
  if (e->integer_xi == 3) return e->rho0 * s;
  if (e->integer_xi == 2) return e->rho0 * s * s;
  return e->rho0 * pow(s, 1.0 / e->half_xim1);
}

/* ---------------------------------------------------------------------------------------------
 * Generalised Riemann invariants J(21–23) of the local normal problem J(16–18).
 * ------------------------------------------------------------------------------------------- */
/** R−1 = u_n + ψ(ρ) [m/s], J(21): conserved across a λ−1 expansion (left fan of the full problem).
 */
static inline double rmn_invariant_minus(const struct rmn_eos *e, double rho, double un) {
  return un + rmn_eos_psi(e, rho);
}
/** R0 = u_n [m/s], J(22). */
static inline double rmn_invariant_zero(double un) { return un; }
/** R+1 = u_n − ψ(ρ) [m/s], J(23): conserved across a λ+1 expansion, J(27), J(29). */
static inline double rmn_invariant_plus(const struct rmn_eos *e, double rho, double un) {
  return un - rmn_eos_psi(e, rho);
}

/* ---------------------------------------------------------------------------------------------
 * Local frame (n, t1[, t2]) of a boundary segment, J §III. n is the unit normal pointing INTO
 * the fluid. dim ∈ {1, 2, 3}. In 2D t1 = (−n_y, n_x); in 3D t1 is the unit vector orthogonal to n
 * built from the coordinate axis least aligned with n, t2 = n × t1 (right-handed).
 * ------------------------------------------------------------------------------------------- */
struct rmn_frame {
  int dim;
  double n[3], t1[3], t2[3];
};

/**
 * Build the frame from a normal (need not be unit length; it is normalised).
 * Returns RMN_EINVAL for dim ∉ {1,2,3} or a zero/NaN normal.
 */
int rmn_frame_from_normal(int dim, const double *normal, struct rmn_frame *frame);
/** Global vector v (dim components) → local (v·n, v·t1, v·t2) (dim components). */
void rmn_frame_to_local(const struct rmn_frame *frame, const double *v, double *local);
/** Local (v_n, v_t1, v_t2) → global vector (dim components). */
void rmn_frame_to_global(const struct rmn_frame *frame, const double *local, double *v);

/* ---------------------------------------------------------------------------------------------
 * Solver parameters and workspace.
 * ------------------------------------------------------------------------------------------- */
enum rmn_shock_model {
  RMN_SHOCK_EXACT = 0, /**< moving-shock Rankine–Hugoniot (docs/theory.md §1.1), the default */
  RMN_SHOCK_LINEARISED =
      1 /**< GPUSPH-style p2 − p_int = ρ_int u_int (u_int − u2); comparison only */
};

struct rmn_params {
  enum rmn_shock_model shock; /**< default RMN_SHOCK_EXACT */
  double tol_rel;             /**< relative tolerance of Newton/Brent iterations; default 1e-14 */
  int max_iter;               /**< iteration cap; default 100 */
  /** |ρ2 − ρ_int| ≤ contact_tol · ρ_int is classified as a contact wave (J 26–27); default 1e-12 */
  double contact_tol;
};

/** Defaults as documented in struct rmn_params. */
void rmn_params_default(struct rmn_params *params);
/** RMN_SUCCESS or RMN_EINVAL (tol_rel ∉ (0, 1e-2], max_iter < 1, contact_tol ∉ [0, 1)). */
int rmn_params_check(const struct rmn_params *params);

/** Opaque solver workspace (GSL multiroot and root solvers). */
struct rmn_workspace;
/** Allocate a workspace; NULL on allocation failure. */
struct rmn_workspace *rmn_workspace_alloc(void);
/** Free a workspace (NULL is accepted). */
void rmn_workspace_free(struct rmn_workspace *ws);

/* ---------------------------------------------------------------------------------------------
 * The boundary Riemann problem, J §III and docs/theory.md §1.1.
 *
 * Across the λ0 contact ρ and u_n are continuous, so the segment state is "state 2", connected to
 * the interior state across the λ+1 wave only. One quantity is imposed (pressure or normal
 * velocity); the other follows from R+1 (contact/expansion, J 27, 29) or from the moving-shock
 * Rankine–Hugoniot system solved by Newton (GSL multiroot, analytic Jacobian):
 *     ρ2 (u2 − S) = ρ_int (u_int − S),   ρ2 u2 (u2 − S) + p2 = ρ_int u_int (u_int − S) + p_int.
 * ------------------------------------------------------------------------------------------- */
enum rmn_wave { RMN_WAVE_CONTACT = 0, RMN_WAVE_EXPANSION = 1, RMN_WAVE_SHOCK = 2 };
enum rmn_flow { RMN_FLOW_INFLOW = 0, RMN_FLOW_OUTFLOW = 1 };
enum rmn_imposed { RMN_IMPOSE_PRESSURE = 0, RMN_IMPOSE_VELOCITY = 1 };

/** "contact", "expansion", "shock" (and "rarefaction" is not used here). */
const char *rmn_wave_name(enum rmn_wave wave);
/** "inflow", "outflow". */
const char *rmn_flow_name(enum rmn_flow flow);

/** Result of the normal (1D) boundary problem. */
struct rmn_normal_state {
  double rho;         /**< segment density ρ2 [kg/m³] */
  double p;           /**< segment pressure p2 [Pa] */
  double un;          /**< segment normal velocity u_n,2 (positive into the fluid) [m/s] */
  enum rmn_wave wave; /**< type of the λ+1 wave */
  enum rmn_flow flow; /**< inflow when u_n,2 ≥ 0 */
  double shock_speed; /**< S for a shock (0 for the linearised model), NaN otherwise [m/s] */
  int iterations;     /**< Newton iterations used (0 for closed-form branches) */
};

/**
 * Solve the normal boundary problem: interior (ρ_int, u_int) with u_int the normal velocity, and
 * the imposed pressure p [Pa] or normal velocity u_n [m/s] in `value`.
 * `ws` may be NULL only with params->shock == RMN_SHOCK_LINEARISED or when no shock arises; a
 * shock without workspace returns RMN_EINVAL.
 * Errors: RMN_EINVAL (NaN input, bad params), RMN_EDENSITY (ρ_int ≤ 0), RMN_ESUPERSONIC (interior
 * or result with |u_n| ≥ c), RMN_ECAVITATION (imposed pressure ≤ p(0), or an expansion to ψ ≤ 0),
 * RMN_ENOCONV (Newton), RMN_ELAX (shock result failing λ+1(int) < S < λ+1(2)),
 * RMN_EUNDEFINED (linearised model with imposed pressure and u_int = 0).
 * On error *out is left unchanged.
 */
int rmn_boundary_solve_normal(const struct rmn_eos *eos, const struct rmn_params *params,
                              struct rmn_workspace *ws, double rho_int, double un_int,
                              enum rmn_imposed imposed, double value, struct rmn_normal_state *out);

/** One boundary segment's input: geometry, interior state and imposed data. */
struct rmn_boundary_input {
  double normal[3];         /**< normal into the fluid (dim components, any length > 0) */
  double rho;               /**< interior density [kg/m³] (SPH: Shepard value J 33–35) */
  double u[3];              /**< interior velocity, global frame (dim components) [m/s] */
  enum rmn_imposed imposed; /**< which quantity is imposed */
  double value;             /**< imposed pressure [Pa] or normal velocity [m/s] */
  double ut[2]; /**< tangential velocity imposed on inflow, local (t1, t2) [m/s]; use 0 */
};

/** One boundary segment's result. */
struct rmn_boundary_result {
  double rho, p; /**< segment density [kg/m³] and pressure [Pa] */
  double u[3];   /**< segment velocity, global frame (dim components) [m/s] */
  double un;     /**< normal component [m/s] */
  double ut[2];  /**< tangential components on (t1, t2) [m/s] */
  enum rmn_wave wave;
  enum rmn_flow flow;
  double shock_speed; /**< as in struct rmn_normal_state */
  int status;         /**< RMN_SUCCESS or the error of this segment */
};

/**
 * Full boundary solve for one segment in dimension dim ∈ {1,2,3}: the normal problem plus the
 * tangential rules of J §III (inflow: imposed ut; outflow: interior tangential velocity).
 * Returns the status, also stored in out->status. On error the other fields of *out are NaN.
 */
int rmn_boundary_solve(const struct rmn_eos *eos, const struct rmn_params *params,
                       struct rmn_workspace *ws, int dim, const struct rmn_boundary_input *in,
                       struct rmn_boundary_result *out);

/**
 * Solve `count` segments (arrays of `count` elements, caller-owned; no allocation). Every segment
 * is solved even when some fail; each result carries its own status. Returns RMN_SUCCESS when all
 * succeeded, else the status of the first failure, whose index goes to *first_failed (if not NULL).
 * Thread-safe given one workspace per calling thread.
 */
int rmn_boundary_solve_batch(const struct rmn_eos *eos, const struct rmn_params *params,
                             struct rmn_workspace *ws, int dim, size_t count,
                             const struct rmn_boundary_input *in, struct rmn_boundary_result *out,
                             size_t *first_failed);

/**
 * Closed-form normal velocity behind a λ+1 shock (docs/theory.md §1.1, S eliminated):
 *   u2 = u_int + sqrt((p2 − p_int)(ρ2 − ρ_int)/(ρ2 ρ_int)),  ρ2 ≥ ρ_int.
 * Used to cross-check the Newton solve; returns NaN when ρ2 < ρ_int or ρ ≤ 0.
 */
double rmn_shock_velocity_closed_form(const struct rmn_eos *eos, double rho_int, double un_int,
                                      double rho2);

/**
 * Rankine–Hugoniot residuals of a moving shock (mass [kg/m²/s], momentum [Pa]) between the
 * state behind (ρ2,u2) and ahead (ρ_int,u_int) with speed S. Used by tests and the CLI.
 */
void rmn_shock_residuals(const struct rmn_eos *eos, double rho_int, double un_int, double rho2,
                         double un2, double s, double residual[2]);

/* ---------------------------------------------------------------------------------------------
 * The exact two-wave Riemann problem, docs/theory.md §1.2. Left state (ρ_L, u_L), right state (ρ_R,
 * u_R); ρ = 0 is a dry (vacuum) state and is legitimate here.
 * ------------------------------------------------------------------------------------------- */
enum rmn_exact_wave { RMN_EXACT_RAREFACTION = 0, RMN_EXACT_SHOCK = 1 };

/** "rarefaction" or "shock". */
const char *rmn_exact_wave_name(enum rmn_exact_wave wave);

struct rmn_exact {
  struct rmn_eos eos;              /**< copy of the equation of state used */
  double rho_l, u_l, rho_r, u_r;   /**< data */
  double rho_star, u_star, p_star; /**< star state; with vacuum ρ* = 0, u* = NaN, p* = p(0) */
  enum rmn_exact_wave left, right; /**< wave types (vacuum: both rarefactions) */
  int vacuum;                      /**< 1 when a vacuum (dry) region exists (or a side is dry) */
  /** Wave speeds [m/s]: a shock has head == tail == its speed; a rarefaction fan runs from head
   *  (outermost characteristic) to tail. Vacuum fronts are the tails. For ξ = 1 with a dry side
   *  the fan reaches infinity (tail = ∓HUGE_VAL). */
  double left_head, left_tail, right_head, right_tail;
  int iterations; /**< root-finder iterations (0 for closed forms) */
};

/**
 * Solve the exact Riemann problem. Needs a workspace (GSL Newton root finder kept in the bracket
 * of the root, Brent as fallback) unless the solution is closed form (two rarefactions or vacuum).
 * Errors: RMN_EINVAL (NaN, negative density, both states dry, bad params), RMN_ENOCONV.
 */
int rmn_exact_solve(const struct rmn_eos *eos, const struct rmn_params *params,
                    struct rmn_workspace *ws, double rho_l, double u_l, double rho_r, double u_r,
                    struct rmn_exact *sol);

/** Sample the self-similar solution at s = x/t [m/s]: density, velocity. */
void rmn_exact_sample(const struct rmn_exact *sol, double s, double *rho, double *u);

/**
 * The star-region function f(ρ) = f_L(ρ) + f_R(ρ) + u_R − u_L of docs/theory.md §1.2 whose root is
 * ρ* (exposed for tests and studies). Both states must be wet.
 */
double rmn_exact_star_function(const struct rmn_eos *eos, double rho, double rho_l, double u_l,
                               double rho_r, double u_r);

#ifdef __cplusplus
}
#endif
#endif /* SABRE_RIEMANN_H */
