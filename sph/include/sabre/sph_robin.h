/*
 * SABRE sph/ — arbitrary-order Robin/Neumann vertex values, M(64–74), with the hydrostatic
 * correction of the constraint, M(83). Derivation with equation references: docs/sph-robin.md.
 *
 * A wall condition (μ1 f + μ2 ∂f/∂n)|_∂Ω = μ3, M(64), with n the unit normal INTO the fluid and
 * μ2 ≠ 0 (Neumann: μ1 = 0, μ2 = 1), is imposed at a vertex particle v by fitting, in the weighted
 * least-squares sense, the 1D polynomial along the vertex normal, M(66–67),
 *
 *   λ(x) = Σ_{i=2..m} β_i x^i + (μ3/μ2) x + β1 (1 − (μ1/μ2) x),      x_a = r_av · n_v,
 *
 * which satisfies the condition at x = 0 for every β, to the fluid values f_a with the weights
 * Λ_aa = V_a w_va, M(72–73); the vertex value is f_v = λ(0) = β1, M(74). The order m is the degree
 * of λ: m = 1 with μ1 = μ3 = 0 is the Shepard value M(16–17). With gravity (pressure), the fluid
 * values are first stripped of their hydrostatic variation along the wall, M(83):
 * y_a = f_a − (μ3/μ2) x_a − ρ_a [r_av − x_a n_v]·g.
 *
 * Here r_av = r_a − r_v (minimum image in periodic domains is the caller's business).
 * Units: any consistent set; lengths in m, weights V_a w_va dimensionless, μ3/μ2 in [f]/m.
 *
 * Like riemann/, this part of the library never prints and never exits: every fallible call
 * returns a status (SPH_ROBIN_SUCCESS == 0) that sph_robin_strerror() names. No allocation and no
 * static state: the workspace is a plain struct (one per thread), sized for SPH_ROBIN_M_MAX.
 * The solve calls GSL (Jacobi SVD), whose default error handler aborts on a GSL error; as with
 * riemann/, applications call gsl_set_error_handler_off() once at start-up (the SABRE programs and
 * tests do), after which such a failure comes back as SPH_ROBIN_ESINGULAR.
 */
#ifndef SABRE_SPH_ROBIN_H
#define SABRE_SPH_ROBIN_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest supported order m (degree of λ). The paper uses m = 1 and 2. */
#define SPH_ROBIN_M_MAX 6

#define SPH_ROBIN_STATUS_LIST(X)                                                                \
  X(SPH_ROBIN_SUCCESS, 0, "success")                                                            \
  X(SPH_ROBIN_EINVAL, 1,                                                                        \
    "invalid argument (NULL pointer, NaN or infinite value, order outside 1..SPH_ROBIN_M_MAX, " \
    "mu2 = 0, normal not of unit length, negative weight, non-positive length scale)")          \
  X(SPH_ROBIN_ETOOFEW, 2,                                                                       \
    "fewer than m distinct fluid distances along the vertex normal (the order-m fit is "        \
    "undetermined: lower the order or check the neighbour list)")                               \
  X(SPH_ROBIN_ESINGULAR, 3,                                                                     \
    "least-squares matrix of M(73) singular or ill-conditioned (reciprocal condition number "   \
    "below rcond_min)")                                                                         \
  X(SPH_ROBIN_ENOMEM, 4, "memory allocation failed")                                            \
  X(SPH_ROBIN_ENOCONV, 5, "root bracketing did not converge")

enum sph_robin_status {
#define SPH_ROBIN_X_ENUM(name, value, text) name = value,
  SPH_ROBIN_STATUS_LIST(SPH_ROBIN_X_ENUM)
#undef SPH_ROBIN_X_ENUM
};

/** Human-readable text of a status code (static storage, never NULL). */
const char *sph_robin_strerror(int status);
/** Symbolic name of a status code, e.g. "SPH_ROBIN_ETOOFEW" (static storage, never NULL). */
const char *sph_robin_status_name(int status);

/** Parameters of one boundary group. */
struct sph_robin_params {
  double mu1, mu2, mu3; /**< M(64): μ1 f + μ2 ∂f/∂n = μ3 on the wall, n into the fluid; μ2 ≠ 0 */
  int m;                /**< order (degree of λ), 1 ≤ m ≤ SPH_ROBIN_M_MAX; M(66) */
  double length;        /**< L > 0 [m]: distances are scaled by L in the fit (pass 2h) */
  double dist_tol;   /**< [-] distances x_a closer than dist_tol·L count as one, M §6.1 */
  double rcond_min;  /**< [-] smallest accepted σ_min/σ_max of the M(73) matrix */
  int hydro;         /**< 1: hydrostatic correction M(83) with `gravity`; 0: M(69)/M(82) */
  double gravity[3]; /**< g [m/s²] for M(83) (components beyond dim ignored) */
};

/**
 * Defaults: homogeneous Neumann (μ1, μ2, μ3) = (0, 1, 0), m = 1 (Shepard), the given length
 * scale, dist_tol = 1e-6, rcond_min = 1e-13, no hydrostatic correction.
 */
void sph_robin_params_init(struct sph_robin_params *p, double length);

/**
 * Accumulator of the M(73) normal equations for one vertex. Fields are private except n_used
 * (fluid particles with a positive weight added so far) and n_distinct (distinct scaled distances
 * found so far, counted up to m), which callers may read to word their messages.
 */
struct sph_robin_ws {
  int status; /**< first error met since sph_robin_begin() (sticky) */
  int dim, m, hydro;
  double normal[3], gravity[3];
  double kappa;   /**< (μ1/μ2) L: slope of the β1 column in scaled distance */
  double sigma;   /**< (μ3/μ2) L: known slope of λ in scaled distance [f] */
  double inv_len; /**< 1/L */
  double dist_tol;
  double rcond_min;
  size_t n_used;
  int n_distinct;
  double distinct[SPH_ROBIN_M_MAX];
  double a[SPH_ROBIN_M_MAX * SPH_ROBIN_M_MAX]; /**< X^T Λ X (upper triangle while adding) */
  double b[SPH_ROBIN_M_MAX];                   /**< X^T Λ y */
  /* scratch of the SVD solve (work: Σ⁻¹Uᵀb) */
  double v[SPH_ROBIN_M_MAX * SPH_ROBIN_M_MAX];
  double s[SPH_ROBIN_M_MAX], work[SPH_ROBIN_M_MAX], beta[SPH_ROBIN_M_MAX];
  double rcond; /**< σ_min/σ_max of the last solve (set by sph_robin_finish) */
};

/**
 * Start a vertex: validate p and the unit inward normal n_v[0..dim-1] (|n_v| = 1 within 1e-6; it
 * is renormalised). Returns SPH_ROBIN_SUCCESS or SPH_ROBIN_EINVAL (also kept in ws->status, so
 * that the following sph_robin_add()/sph_robin_finish() are no-ops returning it).
 */
int sph_robin_begin(struct sph_robin_ws *ws, const struct sph_robin_params *p, int dim,
                    const double *n_v);

/**
 * Add one fluid neighbour a: r_av = r_a − r_v [m] (dim components), its value f_a, its weight
 * Λ_aa = V_a w_va ≥ 0, M(72), and its density ρ_a (used only with p->hydro, M(83)). Particles
 * with zero weight (outside the kernel support) are skipped. A NaN/infinite input or a negative
 * weight makes the vertex fail with SPH_ROBIN_EINVAL at sph_robin_finish(). Hot path: no checks
 * of pointers.
 */
void sph_robin_add(struct sph_robin_ws *ws, const double *r_av, double f_a, double weight,
                   double rho_a);

/**
 * Solve M(73) through the SVD of the m×m matrix (GSL one-sided Jacobi, no allocation) and
 * return f_v = β1, M(74).
 * Returns SPH_ROBIN_SUCCESS; SPH_ROBIN_EINVAL (see above); SPH_ROBIN_ETOOFEW when fewer than m
 * distinct distances (pairwise further apart than dist_tol·L) carry a positive weight;
 * SPH_ROBIN_ESINGULAR when σ_min/σ_max < rcond_min (m distinct distances are necessary but not
 * sufficient when μ1 ≠ 0: the β1 column 1 − (μ1/μ2)x vanishes at x = μ2/μ1). *f_v is NaN on error.
 */
int sph_robin_finish(struct sph_robin_ws *ws, double *f_v);

/**
 * One-shot form over plain arrays: vertex at x_v with inward unit normal n_v; n fluid neighbours
 * at x[a][0..dim-1] with values f[a], volumes vol[a] [m^d] and kernel weights w[a] = w(|r_a − r_v|)
 * [1/m^d]; rho[a] is needed only with p->hydro (may be NULL otherwise). Positions must already be
 * unwrapped next to the vertex. Same statuses as sph_robin_finish(), plus SPH_ROBIN_EINVAL for
 * NULL arrays (with n > 0) or dim ∉ {1, 2, 3}.
 */
int sph_robin_vertex_value(const struct sph_robin_params *p, int dim, const double *x_v,
                           const double *n_v, size_t n, const double (*x)[3], const double *f,
                           const double *vol, const double *w, const double *rho,
                           struct sph_robin_ws *ws, double *f_v);

#ifdef __cplusplus
}
#endif

#endif
