/*
 * SABRE fv1d/ — the one-dimensional finite-volume reference solver of the barotropic Euler
 * equations
 *
 *     ∂U/∂t + ∂F(U)/∂x = 0,   U = (ρ, ρu),   F(U) = (ρu, ρu² + p(ρ)),          docs/theory.md §2
 *
 * with the Tait equation of state of riemann/ (J(1)). Cell averages on a uniform mesh; limited
 * slopes on the primitive variables (ρ, u) (MUSCL); a numerical flux at each face (exact Godunov
 * through rmn_exact_solve, HLL, Rusanov); method of lines integrated by SUNDIALS ARKODE ERKStep
 * (an SSP-RK3 Shu–Osher table by default). The end faces are reflective walls, periodic,
 * transmissive, or open: an open face carries F(U_s), where U_s is the segment state that the
 * riemann/ boundary solver (J §III, docs/theory.md §1.1) returns from the adjacent cell and the
 * imposed pressure or velocity, recomputed at every right-hand-side evaluation.
 *
 * Units are SI throughout: x in m, t in s, ρ in kg/m³, u in m/s, p in Pa relative to p(ρ0) = 0.
 *
 * Error policy: this is application code. Input errors in case files come back as -1 with the
 * message kept by the struct cmn_case (or exit when the case is in fatal mode); run failures
 * (NaN, vacuum, supersonic open boundary, SUNDIALS failure) are returned as -1 with a message in
 * fv1d_solver_error(); allocation failures stop the program through cmn_error().
 */
#ifndef SABRE_FV1D_H
#define SABRE_FV1D_H

#include <sabre/common.h>
#include <sabre/riemann.h>
#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * Parameters
 * ------------------------------------------------------------------------------------------- */
enum fv1d_flux { FV1D_FLUX_GODUNOV = 0, FV1D_FLUX_HLL = 1, FV1D_FLUX_RUSANOV = 2 };
enum fv1d_recon { FV1D_RECON_NONE = 0, FV1D_RECON_MINMOD = 1, FV1D_RECON_MC = 2 };
enum fv1d_bc_type {
  FV1D_BC_WALL = 0,         /**< reflective wall: mirror state, zero mass flux */
  FV1D_BC_PERIODIC = 1,     /**< both ends together */
  FV1D_BC_TRANSMISSIVE = 2, /**< zero gradient: flux F(U) of the adjacent cell */
  FV1D_BC_OPEN = 3          /**< riemann/ boundary solver with imposed p or u */
};
enum fv1d_signal_kind {
  FV1D_SIGNAL_CONSTANT = 0, /**< value */
  FV1D_SIGNAL_SINUSOID = 1, /**< value + amplitude sin(2π frequency t + phase) */
  FV1D_SIGNAL_RAMP = 2,     /**< start → value linearly over [t_start, t_start + duration] */
  FV1D_SIGNAL_TABLE = 3     /**< piecewise-linear in a (t, value) table, constant beyond its ends */
};
/** Names as used in case files, NULL-terminated, indexed by the enums above. */
extern const char *const fv1d_flux_names[];
extern const char *const fv1d_recon_names[];
extern const char *const fv1d_bc_names[];
extern const char *const fv1d_signal_names[];

/** A time-dependent imposed quantity. */
struct fv1d_signal {
  enum fv1d_signal_kind kind;
  double value;     /**< constant value, sinusoid mean, ramp final value [Pa or m/s] */
  double amplitude; /**< sinusoid amplitude */
  double frequency; /**< sinusoid frequency [Hz] */
  double phase;     /**< sinusoid phase [rad] */
  double start;     /**< ramp value before t_start */
  double t_start;   /**< ramp start time [s] */
  double duration;  /**< ramp duration [s] (0: a step at t_start) */
  size_t ntable;    /**< table length (≥ 1) */
  double *table_t;  /**< table times, strictly increasing [s] (owned, fv1d_params_free) */
  double *table_v;  /**< table values */
};

/** Value of a signal at time t. */
double fv1d_signal_eval(const struct fv1d_signal *signal, double t);

/** One end of the domain. */
struct fv1d_bc {
  enum fv1d_bc_type type;
  enum rmn_imposed imposed;  /**< open only: pressure [Pa] or velocity [m/s] */
  struct fv1d_signal signal; /**< open only. A velocity is the x component (global frame). */
};

/** Initial condition: background (number or expression in x), optional table, then regions. */
struct fv1d_region {
  double from, to; /**< cells whose centre lies in [from, to) [m] */
  double rho, u;   /**< state of the region */
};
struct fv1d_initial {
  double rho, u;             /**< uniform background (used when no expression) */
  struct cmn_expr *rho_expr; /**< ρ(x) [kg/m³] or NULL (cmn_expr of the variable x) */
  struct cmn_expr *p_expr;   /**< p(x) [Pa] or NULL (ρ from the EOS) */
  struct cmn_expr *u_expr;   /**< u(x) [m/s] or NULL */
  size_t ntable;             /**< profile table (x, rho, u) length, 0 if none */
  double *table_x, *table_rho, *table_u;
  size_t nregions;
  struct fv1d_region *regions;
};

struct fv1d_params {
  double x_min, x_max;   /**< domain [m] */
  long cells;            /**< number of cells */
  struct rmn_eos eos;    /**< fluid */
  struct rmn_params rmn; /**< riemann/ tolerances */
  enum fv1d_flux flux;
  enum fv1d_recon recon;
  struct fv1d_bc bc[2]; /**< [0] left (x_min), [1] right (x_max) */
  struct fv1d_initial initial;
  double t_end;      /**< end time [s] */
  char method[64];   /**< "ssprk3" or an ARKODE ERK table name */
  double cfl;        /**< Courant number: dt = cfl dx / max(|u| + c) */
  int adaptive;      /**< ARKODE error control (the CFL step becomes a stability bound) */
  double rtol, atol; /**< adaptive tolerances (atol relative to ρ0 and ρ0 c0) */
  long max_steps;
  size_t noutput;       /**< output times (profiles) */
  double *output_times; /**< strictly increasing, in (0, t_end] */
  long series_every;    /**< time-series row every this many steps */
  int progress;         /**< progress lines on stderr */
};

/** Defaults (documented in docs/fv1d.md); cells, t_end and the EOS must still be set. */
void fv1d_params_default(struct fv1d_params *params);
/** Free what the params own (tables, expressions, output times). */
void fv1d_params_free(struct fv1d_params *params);

/**
 * Read every section of a case file into *params (which it initialises). Relative table paths
 * are taken relative to `base_dir` (the case file's directory; NULL for the working directory).
 * Optional keys get their defaults written back into the case tree. Ends with
 * cmn_case_check_unused(). Returns 0, or -1 with the message in cmn_case_error(c) (or exits, if
 * the case is in fatal mode).
 */
int fv1d_case_read(struct cmn_case *c, const char *base_dir, struct fv1d_params *params);

/* ---------------------------------------------------------------------------------------------
 * Pointwise physics
 * ------------------------------------------------------------------------------------------- */
/** Physical flux F(U) = (ρu, ρu² + p(ρ)) of a primitive state. */
static inline void fv1d_flux_physical(const struct rmn_eos *eos, double rho, double u,
                                      double f[2]) {
  f[0] = rho * u;
  f[1] = rho * u * u + rmn_eos_pressure(eos, rho);
}

/** Internal (potential) energy per volume W(ρ) = ρ ∫_{ρ0}^{ρ} p(s)/s² ds ≥ 0 [J/m³]. */
double fv1d_internal_energy(const struct rmn_eos *eos, double rho);

/**
 * Numerical flux between the face states (ρ_L, u_L) and (ρ_R, u_R): exact Godunov (the riemann/
 * exact solution sampled at x/t = 0), HLL (Davis wave speeds) or Rusanov. Returns RMN_SUCCESS or
 * the riemann/ error of the exact solve. ws is needed for Godunov only.
 */
int fv1d_flux_numerical(enum fv1d_flux kind, const struct rmn_eos *eos,
                        const struct rmn_params *params, struct rmn_workspace *ws, double rho_l,
                        double u_l, double rho_r, double u_r, double f[2]);

/** Limited slope of a primitive variable from the backward and forward differences. */
double fv1d_recon_slope(enum fv1d_recon kind, double d_minus, double d_plus);

/* ---------------------------------------------------------------------------------------------
 * Solver
 * ------------------------------------------------------------------------------------------- */
/** Boundary diagnostics, refreshed at every right-hand-side evaluation. */
struct fv1d_boundary_state {
  double rho, u, p;                /**< face state (open: segment state U_s; u in the x frame) */
  double flux[2];                  /**< face flux (mass [kg/m²/s], momentum [Pa]) along +x */
  struct rmn_normal_state segment; /**< open ends: the riemann/ result (normal into the fluid) */
};

struct fv1d_solver;

/** Allocate a solver for the params (copied; tables stay owned by the caller's params, which
 *  must outlive the solver). The state is set from params->initial. */
struct fv1d_solver *fv1d_solver_create(const struct fv1d_params *params);
void fv1d_solver_destroy(struct fv1d_solver *s);

/** Number of cells, cell width [m], centre of cell i [m]. */
long fv1d_solver_cells(const struct fv1d_solver *s);
double fv1d_solver_dx(const struct fv1d_solver *s);
double fv1d_solver_x(const struct fv1d_solver *s, long i);
/** Current time [s]. */
double fv1d_solver_time(const struct fv1d_solver *s);
/**
 * The state vector: 2 N conserved values interleaved (ρ_0, (ρu)_0, ρ_1, ...), then 6 time
 * integrals of the end-face fluxes ∫F_left dt (mass, momentum, energy) and ∫F_right dt. May be
 * written before fv1d_integrate() starts (tests); sets nothing else.
 */
double *fv1d_solver_state(struct fv1d_solver *s);
/** Length of the state vector, 2 N + 6. */
long fv1d_solver_state_length(const struct fv1d_solver *s);
/** Last message of a failed call ("" if none). */
const char *fv1d_solver_error(const struct fv1d_solver *s);
/** Boundary diagnostics of the last RHS evaluation, side 0 left, 1 right. */
const struct fv1d_boundary_state *fv1d_solver_boundary(const struct fv1d_solver *s, int side);

/** Fill the state from params->initial (cell averages by 3-point Gauss quadrature). */
void fv1d_initial_apply(struct fv1d_solver *s);

/**
 * Semi-discrete right-hand side dy/dt at time t (y, ydot: state vectors as above), docs/theory.md
 * §2. Returns 0; 1 (recoverable: non-positive or NaN density, failed Riemann solve — a smaller step
 * may cure it) with a message in fv1d_solver_error().
 */
int fv1d_rhs_eval(struct fv1d_solver *s, double t, const double *y, double *ydot);

/** Largest |u| + c over the cells of state y [m/s]. */
double fv1d_max_wave_speed(const struct fv1d_solver *s, const double *y);

/** Conserved totals of state y: mass [kg/m²], momentum [kg/m/s], energy [J/m²] (per unit area). */
void fv1d_totals(const struct fv1d_solver *s, const double *y, double totals[3]);

/** Called at t = 0, after every step and at every output time. */
enum fv1d_event { FV1D_EVENT_START = 0, FV1D_EVENT_STEP = 1, FV1D_EVENT_OUTPUT = 2 };
typedef int (*fv1d_observer_fn)(struct fv1d_solver *s, enum fv1d_event event, long step, double t,
                                double dt, void *user);

/** Statistics of a run. */
struct fv1d_stats {
  long steps;            /**< accepted steps */
  long rhs_evals;        /**< right-hand sides evaluated by the integrator (RK stages) */
  long arkode_rhs_evals; /**< ARKODE's own count (ERKStepGetNumRhsEvals) */
  long failed_steps;     /**< error-test failures (adaptive) */
  double wall_time;      /**< [s] */
};

/**
 * Integrate from the current time with ARKODE ERKStep (docs/theory.md §2), stopping exactly at each
 * output time params->output_times[k] and ending at the last one (fv1d_case_read makes it t_end;
 * output times already passed are skipped). The observer (may be NULL) is called as documented at
 * fv1d_event; a non-zero return aborts the run. Returns 0 (reached the last output time), 1
 * (stopped after params->max_steps steps counted from the start, before it: the state is
 * consistent, the message in fv1d_solver_error() says where) or -1 (failure, message in
 * fv1d_solver_error()).
 */
int fv1d_integrate(struct fv1d_solver *s, fv1d_observer_fn observer, void *user,
                   struct fv1d_stats *stats);

/* ---------------------------------------------------------------------------------------------
 * Outputs (output.c)
 * ------------------------------------------------------------------------------------------- */
/** Write the x, rho, u, p profile of the current state. 0 / -1 (errno). */
int fv1d_output_profile(const struct fv1d_solver *s, const char *path);

/** Full run: profiles, time series, summary in `dir` (created). 0 / -1 with a message. */
struct fv1d_output;
struct fv1d_output *fv1d_output_open(const char *dir, struct fv1d_solver *s);
int fv1d_output_observer(struct fv1d_solver *s, enum fv1d_event event, long step, double t,
                         double dt, void *user);
/** Write the run summary and close the files. 0 / -1. */
int fv1d_output_close(struct fv1d_output *out, const struct fv1d_stats *stats, int status);

#ifdef __cplusplus
}
#endif
#endif /* SABRE_FV1D_H */
