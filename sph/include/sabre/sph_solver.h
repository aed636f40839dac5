/*
 * SABRE sph/ — the weakly-compressible SPH solver with unified semi-analytical walls (USAW):
 * boundary-corrected operators, continuity in time-summation form with volume diffusion,
 * momentum, Tait EOS (riemann/), vertex values, time step, predictor–corrector, diagnostics,
 * probes, wall forces, checkpoints and the `run` command. Equations as implemented, with their
 * M()/J() references: docs/sph-solver.md; case-file keys: docs/sph-case-file.md.
 *
 * Particle data live in the infra store (struct sph_system, sabre/sph.h), pressure included (so
 * the output carries it); the solver keeps the fields the store does not carry (accelerations,
 * viscosity, the state at the start of a step) in struct sph_solver, indexed like the store. Every
 * per-particle solver array is reallocated by sph_solver_sync() when the store grows, so that open
 * boundaries (particle creation and deletion, mass-varying vertices, J 10–15) slot in without
 * changing the step.
 *
 * Units: SI. Like the rest of sph/, these functions stop the program on errors they cannot report;
 * case-file errors go through common/ (file, line, key; exit code 2).
 */
#ifndef SABRE_SPH_SOLVER_H
#define SABRE_SPH_SOLVER_H

#include <stddef.h>
#include <stdint.h>

#include "sabre/riemann.h"
#include "sabre/sph.h"
#include "sabre/sph_flux.h"
#include "sabre/sph_open.h"
#include "sabre/sph_walls.h"

struct cmn_case;

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * Neighbourhoods and wall integrals
 * ------------------------------------------------------------------------------------------- */

/**
 * Everything a fluid particle a needs about its neighbours: lists of fluid (F), vertex (V) and
 * segment (S) particles within `radius` = 2h + skin, the vertex → fluid list for Shepard values,
 * and per F–S pair the wall integral ∇γ_as, J(3), and the distance from a to the segment's plane.
 */
struct sph_tri_axes;
struct sph_edge_link;
struct sph_row_slot;

struct sph_nbrs {
  struct sph_cells cells;
  struct sph_nlist list[SPH_NKINDS]; /**< query fluid; other = kind */
  struct sph_nlist vf;               /**< query vertex, other fluid */
  double radius;                     /**< list radius [m] */
  double *grad_gamma_as[3];          /**< per pair of list[SEGMENT] [1/m] */
  double *dist_as;                   /**< per pair: (r_a − r_s)·n_s, distance to the plane [m] */
  double *term_as;                   /**< per pair: the segment's term of γ_a (γ_a = 1 − Σ) */
  size_t cap_pairs;
  struct sph_tri_axes *tri_axes; /**< 3D: per segment, the axes of its frame (set by the builds) */
  size_t cap_axes;
  struct sph_edge_link *edge_link; /**< 3D: per segment edge, its coplanar neighbour (builds) */
  size_t cap_links;
  struct sph_row_slot *row_slot; /**< 3D: per thread and segment, its place in the row summed */
  size_t cap_slots, stamp;
  size_t edges_shared; /**< 3D: edge integrals the last sph_nbrs_gamma took from a neighbour */
  struct sph_edge_share *row_share; /**< per thread, the edge values of the row being summed */
  double *row_dist;                 /**< per thread, the distances to the row's elements */
  unsigned char *row_exact;         /**< per thread, 1 where row_dist is exact, 0 a lower bound */
  size_t cap_row; /**< entries of row_share, row_dist and row_exact (kept between calls) */
  /* After sph_nbrs_gamma, from the side test at those positions: */
  unsigned char *behind; /**< per fluid particle: 1 if behind its nearest wall element(s), else 0 */
  size_t cap_behind;
  size_t nescaped; /**< how many fluid particles are behind a wall */
  long escaped;    /**< the lowest index of those, or −1 */
};

/** Build cells and lists for s with radius 2h + skin (skin ≥ 0 [m]). Reuses nb's arrays. */
void sph_nbrs_build(struct sph_nbrs *nb, const struct sph_system *s, double skin);
/** The same with the naive O(N²) search (tests). */
void sph_nbrs_build_naive(struct sph_nbrs *nb, const struct sph_system *s, double skin);
/**
 * γ_a = 1 − Σ_s term_s and ∇γ_a = Σ_s ∇γ_as, J(2)–J(4), for every fluid particle from the wall
 * integrals of sabre/sph_walls.h (closed form, no time integration), stored in s->part[FLUID].gamma
 * and grad_gamma; ∇γ_as and the distances per pair into nb. Particles on a wall are not expected
 * (fluid is created at least min_wall_distance from the walls).
 */
void sph_nbrs_gamma(struct sph_nbrs *nb, struct sph_system *s, const struct sph_kernel *k);
/**
 * Rebuild the lists when the positions have not changed since the last sph_nbrs_gamma() (the
 * start of a step is the end of the previous one): the pair data are copied from the old rows
 * instead of recomputed, and γ_a, ∇γ_a re-summed in the new list order, so the result is bitwise
 * that of sph_nbrs_build() + sph_nbrs_gamma(). Falls back to those if the fluid count changed.
 */
void sph_nbrs_rebuild_reuse(struct sph_nbrs *nb, struct sph_system *s, const struct sph_kernel *k,
                            double skin);
void sph_nbrs_free(struct sph_nbrs *nb);

/* ---------------------------------------------------------------------------------------------
 * Boundary-corrected operators at a fluid particle a (sph/src/operators/)
 *
 * Sums run over b ∈ P = F ∪ V (volume terms, V_b = m_b/ρ_b) and s ∈ S (wall terms), with the
 * masses, densities and γ of the store; fields are given per kind (index enum sph_kind), vector
 * fields as three component arrays per kind. r_ab = r_a − r_b, ∇w_ab = ∇_a w(r_ab).
 * ------------------------------------------------------------------------------------------- */

struct sph_op {
  const struct sph_system *sys;
  const struct sph_kernel *kernel;
  const struct sph_nbrs *nb;
  /** The no-pull rule of sph_op_grad_pressure for vertex pairs: 0 (numerics.no_pull: radial, the
   *  default) leaves the whole pull out while a approaches the vertex along r_a − r_v; 1 (normal)
   *  leaves out only its part along the vertex's unit normal, while a approaches the wall along
   *  that normal. */
  int no_pull_normal;
};

/**
 * Grad^{γ,k}_a(f), M(37) [f/m]:
 *   1/γ_a Σ_b V_b (ρ_a^{2k} f_b + ρ_b^{2k} f_a)/(ρ_a^k ρ_b^k) ∇w_ab
 *   − 1/γ_a Σ_s (ρ_a^{2k} f_s + ρ_s^{2k} f_a)/(ρ_a^k ρ_s^k) ∇γ_as.
 * k = 1 is Ferrand's J(6) / M(11); k = 0 the paper's default.
 */
void sph_op_grad(const struct sph_op *op, double k, const double *const f[SPH_NKINDS], size_t a,
                 double out[3]);
/**
 * Div^{γ,k}_a(B), M(38) [B/m]:
 *   1/(γ_a ρ_a^{2k}) Σ_b V_b ρ_a^k ρ_b^k (B_b − B_a)·∇w_ab
 *   − 1/(γ_a ρ_a^{2k}) Σ_s ρ_a^k ρ_s^k (B_s − B_a)·∇γ_as.
 * k = 1 is J(7) / M(8) (with ρ_s/ρ_a on the wall term).
 */
double sph_op_div(const struct sph_op *op, double k, const double *const B[SPH_NKINDS][3],
                  size_t a);
/**
 * Lap^γ_a(β, A), J(8) with the harmonic mean β̄_ab = 2β_aβ_b/(β_a + β_b), J(9) [β A/m²]:
 *   1/γ_a Σ_b V_b 2 β̄_ab A_ab/r_ab² r_ab·∇w_ab − 1/γ_a Σ_s q_as |∇γ_as|,
 * where q_as = (β_s ∂A/∂n|_s + β_a ∂A/∂n|_a) is the wall flux along the inward normal, given per
 * F–S pair (same order as nb->list[SEGMENT]) as three component arrays, or NULL for no wall term
 * (homogeneous Neumann). A is a vector field (unused components may be NULL → 0).
 */
void sph_op_lap(const struct sph_op *op, const double *const beta[SPH_NKINDS],
                const double *const A[SPH_NKINDS][3], const double *const wall_flux[3], size_t a,
                double out[3]);

/* ---------------------------------------------------------------------------------------------
 * Configuration (docs/sph-case-file.md)
 * ------------------------------------------------------------------------------------------- */

enum sph_diffusion { SPH_DIFFUSION_NONE = 0, SPH_DIFFUSION_FERRARI = 1, SPH_DIFFUSION_BREZZI = 2 };
/** c_ab of the Ferrari term: max(c_a, c_b), M(50); or 2K/r_ab with K = c0 Δr/η, M(48), M(52). */
enum sph_diffusion_speed { SPH_DSPEED_MAX = 0, SPH_DSPEED_ETA = 1 };
/** When the neighbour lists are rebuilt (numerics.list_rebuild): when some fluid particle has
 *  moved more than skin/2 since the last build, checked before each of the three evaluations of a
 *  step; or at the start of every step. The results are bitwise the same (docs/sph-solver.md §1).
 */
enum sph_list_rebuild { SPH_LISTS_WHEN_NEEDED = 0, SPH_LISTS_EVERY_STEP = 1 };
/** numerics.wall_impedance (operators/pressure.h): none; acoustic, ω = 1 for every fluid–wall
 * pair; contact, ω = max(0, 1 − d/reach) for a particle at distance d > 0 from the element. */
enum sph_wall_impedance_form {
  SPH_IMPEDANCE_NONE = 0,
  SPH_IMPEDANCE_ACOUSTIC = 1,
  SPH_IMPEDANCE_CONTACT = 2
};

/** Hydrostatic correction of the Shepard vertex values: none, full g·r_vb, tangential M(83). */
enum sph_vertex_hydro { SPH_VHYDRO_NONE = 0, SPH_VHYDRO_FULL = 1, SPH_VHYDRO_TANGENTIAL = 2 };
/** Vertex masses m_v = ρ_v V_v: V_v the geometric volume of the wall layer nearest to the vertex
 *  (sph_walls_vertex_volumes), or a layer φΔr thick with φ fitted to the initial summation
 *  density (docs/sph-solver.md §6). */
enum sph_vertex_volume { SPH_VVOL_GEOMETRIC = 0, SPH_VVOL_FITTED = 1 };

#define SPH_MAX_PROBES 64
#define SPH_MAX_FORCE_GROUPS 16
#define SPH_MAX_VERTEX_GROUPS 16

/** Vertex pressure: Shepard M(16–17) (with numerics.vertex_hydrostatic) or the order-m weighted
 *  least squares of M(64–74) (sabre/sph_robin.h). */
enum sph_vertex_method { SPH_VVALUES_SHEPARD = 0, SPH_VVALUES_ROBIN = 1 };
/** What a vertex does when its order-m fit is undetermined (SPH_ROBIN_ETOOFEW). */
enum sph_vertex_too_few { SPH_VTOOFEW_ERROR = 0, SPH_VTOOFEW_LOWER = 1 };

/** How the pressure of the vertices of one wall group is computed (case section vertex_values). */
struct sph_vertex_bc {
  int method;       /**< enum sph_vertex_method */
  int order;        /**< m of M(66), 1..SPH_ROBIN_M_MAX */
  double mu[3];     /**< μ1, μ2, μ3 of M(64) (μ2 ≠ 0), n into the fluid */
  int gravity_flux; /**< μ3 += μ2 ρ_v g·n_v: ∂p/∂n = ρ g·n for Neumann (M §7.2) */
  int tangential;   /**< hydrostatic correction of the constraint, M(83); 0: M(82) */
  int too_few;      /**< enum sph_vertex_too_few */
  int wall;         /**< group: index into geometry.walls (−1 for the default) */
  int nedges;       /**< 0: the whole wall */
  long edges[64];   /**< 1-based element numbers within the wall */
};

/** Imposed volume flux in a periodic flow, M §5 (sabre/sph_flux.h). */
enum sph_flux_select { SPH_FLUXSEL_OFF = 0, SPH_FLUXSEL_M63 = 1, SPH_FLUXSEL_M58 = 2 };

struct sph_force_group {
  char name[64];
  int wall;       /**< index into geometry.walls */
  int nedges;     /**< 0: the whole wall */
  long edges[64]; /**< 1-based element numbers within the wall (source_index) */
};

struct sph_config {
  /* fluid */
  double rho0, c0, xi, nu;
  double gravity[3];
  /* initial state */
  double u0[3];
  /** initial.velocity[c] as an expression of x, y, z (cmn_expr, docs/case-files.md) [m/s]; ""
   *  when it is the number u0[c] */
  char u0_expr[3][256];
  char p0_expr[256];   /**< initial.pressure as an expression of x, y, z [Pa], or "" */
  char rho0_expr[256]; /**< initial.density as an expression of x, y, z [kg/m³], or "" */
  int hydrostatic;     /**< initial pressure hydrostatic below free_surface */
  double free_surface; /**< level of p = 0 along −g [m] (NaN: top of the fluid + Δr/2) */
  /** initial.wave: 1 when a wave (`wave`, source SPH_OPEN_STOKES5 or SPH_OPEN_SOLITARY) gives the
   *  initial free surface (fluid particles at or above it are removed), velocity and pressure */
  int initial_wave;
  struct sph_open_group wave;
  /* numerics */
  double grad_k;          /**< k of M(37)/M(38) */
  int diffusion;          /**< enum sph_diffusion */
  int diffusion_speed;    /**< enum sph_diffusion_speed */
  double eta;             /**< η of M(48) */
  double brezzi_lambda;   /**< Λ, J §II.C */
  int gravity_correction; /**< ϱ_ab of M(81): 0 none, 1 linear (ρ0/c0², as printed), 2 local
                               (ρ̄/c(ρ̄)², second-order exact for the Tait EOS) */
  int vertex_hydro;       /**< enum sph_vertex_hydro */
  int wall_impedance;     /**< enum sph_wall_impedance_form: the wall value of a fluid–wall pair
                               is raised by ω ρ_a c_a |u_n| while the particle approaches the wall
                               (docs/sph-solver.md §4) */
  double wall_impedance_reach;  /**< contact form: distance from a wall element within which the
                                     impedance acts, ω = 1 − d/reach [Δr] */
  int open_gradient_difference; /**< 1 (numerics.open_gradient: difference; default symmetric): the
                                 * pressure gradient is exact for constants next to open
                                 * boundaries in proportion to their share of the wall terms
                                 * (sph_op_grad_pressure, docs/sph-solver.md §10) */
  int gamma_dynamic;            /**< γ by dγ/dt = v·∇γ, M(4), instead of its closed form */
  int no_pull_normal;           /**< numerics.no_pull: normal (1; default radial, 0): a wall
                                 * vertex's pull is left out in its part along the vertex's
                                 * normal only (sph_op.no_pull_normal, docs/sph-solver.md §4) */
  int lone_ambient;             /**< numerics.lone_particle: ambient (1; default eos, 0): a fluid
                                 * particle whose kernel holds a fluid fraction
                                 * φ_a = Σ_b m_b w_ab / (ρ0 γ_a) below lone_fraction (a droplet)
                                 * takes no tension, p = max(p(ρ), 0), and the lower bound of
                                 * density_band does not stop the run for it
                                 * (docs/sph-solver.md §4) */
  double lone_fraction;         /**< numerics.lone_fraction: that threshold [-] (default 0.35:
                                 * below a line of particles in 2D, a sheet in 3D) */
  int wall_vertex_mass_density; /**< numerics.wall_vertex_mass: density (1; default constant, 0):
                                 * at the start of each step a wall vertex's mass becomes
                                 * V_v ρ_v, its wall layer compressing with the fluid
                                 * (docs/sph-solver.md §4) */
  /** α of numerics.artificial_viscosity [-]: sph_solver_init() adds ν_α = α h c0 / (2(d + 2))
   *  [m²/s] to nu in the solver's copy of the configuration (docs/sph-solver.md §4) */
  double artificial_viscosity;
  int vertex_volume;   /**< enum sph_vertex_volume */
  double vertex_layer; /**< thickness of the wall layer of the vertex volumes [Δr] */
  long repack_steps;   /**< pseudo-time steps of the initial repacking (0: none) */
  /** largest random displacement of the repacking's start, per coordinate, of the particles it
   *  moves [Δr] (repack.perturbation; 0: the lattice as it is) */
  double repack_perturbation;
  /** layer equilibrium after the repacking (repack.layer_equilibrium; 0: off): each horizontal
   *  layer of the fluid moved vertically to where its mean vertical acceleration is zero
   *  (docs/sph-solver.md §8) */
  int layer_equilibrium;
  /** simulated time of the settling run after the repacking [s] (repack.settle; 0: none): the
   *  case's own dynamics from the initial state, then every velocity set to zero and the clock
   *  to t = 0 (docs/sph-solver.md §8) */
  double settle;
  double cfl, viscous_factor, force_factor, gamma_factor;
  double skin_over_h; /**< neighbour-list skin / h */
  int list_rebuild;   /**< enum sph_list_rebuild */
  double dt_max;
  double density_band[2]; /**< stop when ρ/ρ0 leaves [lo, hi] (a droplet below lo does not
                           *   stop the run with lone_ambient) */
  /* time and output */
  double t_end, output_interval;
  long diagnostics_every; /**< steps between rows of diagnostics.csv */
  long checkpoint_steps;  /**< 0: none */
  double checkpoint_minutes;
  long max_steps; /**< stop (with a checkpoint) after this many steps; 0: no limit */
  /* probes and forces */
  int nprobes, ngauges;
  double probes[SPH_MAX_PROBES][3];
  double gauges[SPH_MAX_PROBES][3];
  int nforces;
  struct sph_force_group forces[SPH_MAX_FORCE_GROUPS];
  /* vertex values: the default and per-wall-group overrides (a vertex takes the group of its
   * first segment, as for force groups) */
  struct sph_vertex_bc vertex_bc;
  int nvertex_groups;
  struct sph_vertex_bc vertex_groups[SPH_MAX_VERTEX_GROUPS];
  /* imposed volume flux, M(56–63) */
  int flux_method;       /**< enum sph_flux_select */
  double flux_velocity;  /**< target v = Q/A [m/s] */
  double flux_point[3];  /**< a point of the measuring slice's mid-plane [m] */
  double flux_normal[3]; /**< flow direction n_A (unit) */
  double flux_width;     /**< slice width Δr_A [m] */
  double flux_area;      /**< cross-section A [m^(d−1)] */
  double flux_force0;    /**< initial driving acceleration F^0 [m/s²] */
  /* open boundaries (section open_boundaries, sabre/sph_open.h) */
  struct sph_open_config open;
};

/**
 * Read every section but `geometry` (which sph_geometry_read() owns) into cfg, with the defaults
 * of docs/sph-case-file.md. dim and dr are needed for vector sizes and defaults. Bad input stops
 * the program (fatal case mode) or returns -1 with the message in cmn_case_error().
 */
int sph_config_read(struct sph_config *cfg, struct cmn_case *c, int dim);

/* ---------------------------------------------------------------------------------------------
 * Solver state and step
 * ------------------------------------------------------------------------------------------- */

/** Phases of a step timed by the solver (wall seconds accumulated in sph_solver.timing). */
enum sph_phase {
  SPH_PHASE_LISTS,      /**< neighbour lists (cell sort, pair lists) */
  SPH_PHASE_WALLS,      /**< wall integrals γ_a, ∇γ_as (closed forms, J 2–4) */
  SPH_PHASE_VERTEX,     /**< vertex and segment values (Shepard or least squares), M(16–17) */
  SPH_PHASE_FORCES,     /**< pair loops of the momentum equation and the diffusion rate */
  SPH_PHASE_CONTINUITY, /**< pair loop of the time-summation continuity, M(84) */
  SPH_PHASE_STEP,       /**< the whole of sph_solver_step() (the rest is the integration) */
  SPH_NPHASES
};

struct sph_solver {
  struct sph_config cfg;
  struct sph_system sys;
  struct sph_kernel kernel;
  struct rmn_eos eos;
  struct sph_nbrs nb;
  double time;
  long step;
  double dt;
  /* per-particle solver fields, per kind, capacity cap[kind] */
  double *acc[3];          /**< fluid acceleration [m/s²] */
  double *x0[3], *v0[3];   /**< fluid state at the start of the step */
  double *rho_n, *gamma_n; /**< fluid ρ^n, γ^n */
  double *sum_w[2];        /**< fluid Σ_{b∈P} m_b w_ab at x0 ([0]) and at the corrector ([1]) */
  double *sum_wf[2];       /**< the fluid part Σ_{b∈F} m_b w_ab of sum_w, at x0 and at the
                                corrector: the vertex part follows on from it */
  int sum_w_valid;         /**< sum_wf[0] holds the fluid parts at the current positions (the
                                previous corrector's, store unchanged since), and without open
                                boundaries (constant vertex masses) sum_w[0] the whole sums */
  double *grad_gamma_n[3]; /**< fluid ∇γ^n (for the dynamic γ) */
  double *mu[SPH_NKINDS];  /**< dynamic viscosity ν ρ [Pa s] */
  double *diff;            /**< fluid volume-diffusion rate d(γρ)/dt [kg/m³/s] */
  double *csound;          /**< fluid sound speed c(ρ) of the forces' evaluation [m/s] */
  double *vol;             /**< fluid volume m/ρ of the forces' evaluation [m^dim] */
  double *inv_rho2;        /**< fluid 1/ρ² of the forces' evaluation [m⁶/kg²] */
  double *impedance;       /**< fluid ρ c [kg/m²/s] (numerics.wall_impedance) */
  int *seg_group;          /**< force group of each segment (−1 none) */
  int *vert_group;         /**< force group of each vertex (−1 none) */
  double *vertex_dm;       /**< numerics.wall_vertex_mass: density: per vertex, the change of its
                                mass at the start of the step [kg] (scratch) */
  size_t cap_vertex_dm;
  size_t cap[SPH_NKINDS];
  double vertex_phi;          /**< vertex layer thickness / Δr of the vertex masses [-] */
  double repack_residual[2];  /**< largest defect × h at the start (after the perturbation) and at
                               *   the end of the repacking [-] */
  size_t repack_fixed;        /**< fluid particles held by the repacking's lid */
  int layer_count;            /**< layers of the layer equilibrium (0: none) */
  double *layer_shift;        /**< each layer's shift upwards [Δr], the highest first (owned;
                               *   NULL without the layer equilibrium) */
  double layer_residual;      /**< largest |mean vertical acceleration| / |g| of a layer at the
                               *   equilibrium found [-] */
  long settle_steps;          /**< steps of the settling run (repack.settle; 0: none) */
  double settle_speed;        /**< largest fluid speed at the end of the settling run, before
                               *   the velocities are set to zero [m/s] */
  double timing[SPH_NPHASES]; /**< wall seconds spent in each phase since set-up (the set-up's
                                   own evaluations included; zero it to time a run of steps) */
  int *vert_bc; /**< per vertex: −1 the default vertex_bc, else a vertex_groups index */
  size_t cap_vert_bc;
  /** First vertex whose value failed in the last sph_solver_boundary_values() (−1: none), its
   *  SPH_ROBIN_* status and a message naming the vertex id and position. */
  long vertex_fail;
  int vertex_fail_status;
  char vertex_fail_msg[512];
  /* imposed volume flux (cfg.flux_method != OFF) */
  struct sph_flux_ctrl flux_ctrl; /**< controller history ṽ^{n−1}, ṽ^{n−2}, Δt^{n−1}, F^{n−1} */
  double flux_v;       /**< ṽ measured at the start of the last step, M(56–57) [m/s] */
  double flux_force;   /**< driving acceleration F^n of the last step, M(58)/M(63) [m/s²] */
  long evaluated_step; /**< step whose start state sph_solver_evaluate() saw, or −1 */
  int gamma_current;   /**< nb's wall data are those of the current positions */
  /* neighbour lists kept over several steps (cfg.list_rebuild) */
  int lists_valid;   /**< nb's lists cover the fluid as it is (0 after sph_solver_sync) */
  double *x_list[3]; /**< fluid positions at the last build of the lists [m] */
  long list_builds;  /**< builds of the lists by the step and evaluation since set-up (the
                          set-up's own builds not counted); zero it to count a run of steps */
  /* open boundaries (sabre/sph_open.h): NULL without open groups */
  struct sph_open *open;
  double stage_time; /**< time of the state whose boundary values are evaluated: sv->time, or
                          t + Δt/2 in the predictor [s] */
  int open_off;      /**< 1 while the repacking runs: open segments keep their wall values */
};

/**
 * Set up a solver on a filled system (moved into sv; s is left empty): kernel, EOS, initial
 * density and pressure (uniform or hydrostatic), masses m_a = ρ_a Δr^d, vertex masses
 * m_v = φ ρ_v A_v Δr (A_v: the vertex's share of its segments) with φ such that the summation
 * Σ_b m_b w_ab best equals γ_a ρ_a for the initial fluid (least squares), vertex and segment
 * values. mesh_source (may be NULL): per segment the index of its wall in geometry.walls and its
 * element number there, for force groups.
 */
void sph_solver_init(struct sph_solver *sv, const struct sph_config *cfg, struct sph_system *s,
                     const int *seg_wall, const long *seg_edge);
void sph_solver_free(struct sph_solver *sv);
/** After the store changed between steps (particles created or removed, positions or masses set
 *  by hand): grow the solver's per-particle arrays to the store's sizes and drop the cached
 *  evaluation, wall data and neighbour lists, so that the next step starts from the store as it
 *  is (the lists are rebuilt there). */
void sph_solver_sync(struct sph_solver *sv);

/** Lists, γ, boundary values and forces of the current state (what a step starts with; also
 *  called before wall forces and probes are written). Cheap to call twice: the step reuses it. */
void sph_solver_evaluate(struct sph_solver *sv);
/**
 * Initial repacking (docs/sph-solver.md §8): moves the fluid particles, before t = 0, towards an
 * arrangement in which the zeroth-order defect of the pressure gradient, Σ_{b∈F∪V} V_b ∇w_ab −
 * ∇γ_a (docs/sph-solver.md §2), vanishes, so that fluid at uniform pressure next to walls, edges
 * and corners is at rest. A damped pseudo-dynamics of `steps` steps under the solver's own
 * momentum equation at a uniform pressure without gravity (fluid V_b = Δr^d, vertex volumes
 * m_v/ρ_v of the state on entry), without viscosity and wall impedance (terms of the
 * pseudo-velocities; both are restored on return): the force is then
 * −(2p/ρ) times the defect, the gradient of a potential, so the damped motion settles. Particles
 * on a free surface (kernel completeness Σ_{b∈P} V_b w_ab / γ_a < 0.75) and their neighbours within
 * 2h stay where they are (a lid: a free surface has a defect of its own). The other particles
 * first move by a uniform random displacement in [−ε, ε] Δr per coordinate, ε =
 * cfg.repack_perturbation (0, the default: none), from GSL's mt19937 at its default seed, one
 * draw per particle and coordinate in particle order, held or not (the same start on every run
 * and thread count): a lattice is a symmetric critical point of the defect's potential, where
 * the pseudo-dynamics can stop on a saddle. The pseudo-dynamics is
 * FIRE (Bitzek et al. 2006: velocities turned towards the force, the step grown while the power
 * stays positive, the motion stopped when it turns negative), starting from the solver's CFL and
 * force limits, with at most h/10 of displacement per step. On return the fluid velocities are
 * zero and gravity is restored; masses and densities are uniform (ρ0 (1 + 1e-6), m = ρ Δr^d) and
 * must be set by the caller for the new positions; lists and wall data are stale
 * (sph_solver_sync() was called). sv->repack_residual[0..1] receive the largest defect × h before
 * and after, sv->repack_fixed the number of particles held. Returns 0, or -1 with a message when
 * a particle ended behind a wall.
 */
int sph_solver_repack(struct sph_solver *sv, long steps, char *msg, size_t msglen);
/**
 * EOS for every fluid particle, then the vertex pressures — Shepard M(16–17) with the hydrostatic
 * correction, or per wall group (sph_solver_vertex_groups) the order-m least squares M(64–74) with
 * M(83) or M(82) — and segment values as the mean of their vertices. A failed least-squares fit
 * (SPH_ROBIN_ETOOFEW/ESINGULAR/EINVAL) sets sv->vertex_fail to the lowest failing vertex index and
 * sv->vertex_fail_msg (vertex id, position, normal, distinct distances); sph_solver_step() then
 * stops with that message. The vertex keeps its plain Shepard value meanwhile.
 */
void sph_solver_boundary_values(struct sph_solver *sv);
/** Assign each vertex its vertex_values group: the first of cfg.vertex_groups naming the wall
 *  (seg_wall, index into geometry.walls) and element (seg_edge, 1-based) of its first segment;
 *  otherwise, or with seg_wall NULL, the default cfg.vertex_bc. Called by sph_solver_init(). */
void sph_solver_vertex_groups(struct sph_solver *sv, const int *seg_wall, const long *seg_edge);
/** Cross-averaged velocity ṽ = Q_SPH/A in the imposed-flux slice of cfg, M(56–57) [m/s]. */
double sph_solver_flux_measure(const struct sph_solver *sv);
/** Accelerations of the fluid, M(14): −Grad^{γ,k}(p)/ρ + Lap^γ(μ, v)/ρ + g, with the wall shear
 *  stress M(19–20); also the volume-diffusion rate. Needs sph_nbrs_gamma() and boundary values. */
void sph_solver_forces(struct sph_solver *sv);
/** Time step from the CFL, viscous, force, γ-variation and neighbour-skin limits (after forces). */
double sph_solver_timestep(const struct sph_solver *sv);
/**
 * One predictor–corrector step (docs/sph-solver.md §5) of at most dt_limit (pass INFINITY):
 * returns 0, or −1 with a message in msg when the run must stop (NaN, a particle leaving through
 * a wall, a density outside the band): the message names the particle, position and step.
 */
int sph_solver_step(struct sph_solver *sv, double dt_limit, char *msg, size_t msglen);

/**
 * The linearised dynamics of the fluid about its current state, meant for a state at rest
 * (docs/sph-solver.md §7.1): J = ∂a/∂x [1/s²], a the fluid accelerations of sph_solver_evaluate()
 * and x the fluid positions, by central differences with displacements ±eps [m] of one coordinate
 * at a time (eps about 10⁻⁷ Δr; 2n evaluations of lists, γ, wall values and forces). Each
 * particle's density follows the time summation from the current state, ρ_a(x) = (γ_a ρ_a +
 * Σ_{b∈F∪V} m_b [w(r_ab) − w(r⁰_ab)])/γ_a(x) (masses fixed, no diffusion: the volume diffusion acts
 * on time scales of its own); lists, the geometric γ and the wall values are formed afresh at every
 * evaluation (also with numerics.gamma dynamic, whose γ is restored on return). Velocity-dependent
 * terms see the current velocities. Closed domains: open boundaries (sv->open) are not linearised.
 * J: caller-owned, n × n row-major, n = dim × fluid count, index a·dim + c for coordinate c of
 * particle a. The positions, densities and γ are restored and evaluated again on return.
 */
void sph_solver_jacobian(struct sph_solver *sv, double eps, double *J);
/**
 * Eigenvalues λ of the n × n row-major matrix J (destroyed; GSL gsl_eigen_nonsymm) into
 * lambda_re/lambda_im, and the growth rates rate[i] = Re sqrt(λ_i) [1/s] of ẍ = J x (a real λ > 0
 * is a static instability; a complex λ gives an oscillation that grows at that rate or decays), in
 * GSL's order (n = 0: nothing). Returns 0, or −1 if the QR iteration did not converge (outputs
 * unset).
 */
int sph_stability_rates(size_t n, double *J, double *lambda_re, double *lambda_im, double *rate);
/**
 * sph_stability_rates() and, when amp is not NULL, the eigenvectors too (GSL gsl_eigen_nonsymmv,
 * each normalised to unit Euclidean norm): amp[i·n + j] = |i-th component of the j-th mode|
 * (caller-owned, n × n; the modes in the order of lambda_re). Costs about three times the
 * eigenvalues alone. Returns 0, or −1 if the QR iteration did not converge (outputs unset).
 */
int sph_stability_modes(size_t n, double *J, double *lambda_re, double *lambda_im, double *rate,
                        double *amp);

/** One row of diagnostics.csv. mass: the fluid particles', the open vertices' and the wall
 *  vertices' set-up masses (sph_parts.wall_mass; with numerics.wall_vertex_mass: density a wall
 *  vertex's mass follows its layer's density, which moves no mass) [kg]. */
struct sph_diagnostics {
  double time, dt, count, mass, kinetic, potential, internal, max_speed, max_drho;
};
void sph_solver_diagnostics(const struct sph_solver *sv, struct sph_diagnostics *d);
/** Specific internal energy e(ρ) = ∫_ρ0^ρ p/ρ'² dρ' of the Tait EOS [J/kg]. */
double sph_internal_energy(const struct rmn_eos *eos, double rho);
/** Shepard-interpolated pressure at point x (fluid particles) [Pa]; NaN when no fluid is near. */
double sph_solver_probe_pressure(const struct sph_solver *sv, const double *x);
/** Free-surface elevation above the horizontal position of x (along −g): the highest fluid
 *  particle within h of the vertical line, plus Δr/2 [m]; NaN when there is none. */
double sph_solver_gauge(const struct sph_solver *sv, const double *x);
/** Kernel-sum level above the horizontal position of x (along −g) [m]: the highest point of the
 *  vertical line where the fluid fills half of the kernel's room,
 *  Σ_F V_b w(x − x_b) = ½ (γ(x) − Σ_V V_v w(x − x_v)) (V = m/ρ; γ of the walls at x by
 *  sph_gamma_eval; the vertex sum is the wall layer the fluid particles do not cover). H exactly
 *  for a lattice whose top row is Δr/2 below H, next to walls as well. Searched down from Δr
 *  above the highest fluid particle within 2h of the line (steps of Δr/4, then GSL's Brent solver
 *  to 1e-9 Δr). NaN when no fluid is within 2h of the line or the sum never reaches ½ (a film
 *  thinner than about Δr). Allocates O(particles near the line); no state. */
double sph_solver_level(const struct sph_solver *sv, const double *x);
/** The gauges' vertical: the unit vector −g/|g| (y when g = 0), written to up. */
void sph_gauge_up(const double gravity[3], double up[3]);
/** Force of the fluid on each force group [N], out[group][3]: pressure −Σ_s p_s |s| n_s over the
 *  group's segments, plus the reaction to the viscous wall terms of Lap^γ (M 19–20). */
void sph_solver_wall_forces(const struct sph_solver *sv, double (*out)[3]);
/** Skew-adjoint defect M(27): <Grad^{γ,k} f, B> + <f, Div^{γ,k} B> over the fluid (V_a weights). */
double sph_skew_adjoint_defect(const struct sph_solver *sv, const double *const f[SPH_NKINDS],
                               const double *const B[SPH_NKINDS][3]);

/* ---------------------------------------------------------------------------------------------
 * Checkpoints: the whole store (through its field table), time, step and output counters.
 * ------------------------------------------------------------------------------------------- */
#define SPH_MAX_DIGESTS 32
/** Most particle outputs a run may ask for: time.end / time.output_interval ≤ this. */
#define SPH_MAX_OUTPUTS 1000000
struct sph_run_counters {
  double next_output;
  long outputs;
  double *output_times;
  /** Digests (cmn_case_digest) of the case's top-level sections except `time`, by name: written
   *  into the checkpoint, and compared on reading so that a restart continues the same numerics.
   *  ndigest = 0: none written, no check. */
  int ndigest;
  char digest_name[SPH_MAX_DIGESTS][32];
  unsigned long long digest[SPH_MAX_DIGESTS];
};
/** Fill rc's digests from the resolved case c (after every section was read). */
void sph_run_counters_digest(struct sph_run_counters *rc, const struct cmn_case *c);
/** Write atomically (tmp file + rename). Returns 0 or −1 (errno). */
int sph_checkpoint_write(const struct sph_solver *sv, const struct sph_run_counters *rc,
                         const char *path);
/** Read into an initialised solver (same case): replaces the store, time and step. Returns 0 or
 *  −1 with a message: not a checkpoint, truncated, another dimension, dr, h or wall count, or
 *  (when both rc and the file carry digests) a section of the case other than `time` that differs
 *  from the run that wrote it ("the case's numerics section differs ..."). */
int sph_checkpoint_read(struct sph_solver *sv, struct sph_run_counters *rc, const char *path,
                        char *msg, size_t msglen);

/** Say why the time step dt (≤ 0 or NaN) is not positive: a non-finite particle state, or the
 *  limit (force, CFL) that gave it, with the particle that set it. For sph_solver_step(). */
void sph_solver_explain_dt(const struct sph_solver *sv, double dt, char *msg, size_t msglen);

/**
 * Evaluate the initial expressions of cfg (initial.pressure, initial.density, initial.velocity)
 * at every fluid particle of s before the set-up does: the first value that is not finite, or not
 * in range (pressure above the EOS's minimum, positive density), is an error at the key's file,
 * line and column (cmn_case_fail: exits in fatal mode). Returns 0 or -1.
 */
int sph_config_check_initial(const struct sph_config *cfg, struct cmn_case *c,
                             const struct sph_system *s);

/**
 * Check that every probe of cfg lies in the case's domain before the set-up: a pressure probe
 * (probes.pressure) inside the box spanned by the fluid and wall particles of s widened by h, a
 * gauge (probes.gauges) on a vertical line (along −g; along y without gravity) that crosses that
 * box. Periodic directions are not checked (positions wrap there). The first probe outside is an
 * error at its key's file, line and column naming the point and the box (cmn_case_fail: exits in
 * fatal mode). Returns 0 or -1.
 */
int sph_config_check_probes(const struct sph_config *cfg, struct cmn_case *c,
                            const struct sph_system *s);

/** `sabre-sph run CASE.yaml [--set k=v]... [--output DIR] [--restart FILE] [--threads N]`. */
int sph_cmd_run(int argc, char **argv);
/**
 * `sabre-sph stability CASE.yaml [--set key=value]... [--output DIR] [--modes N] [--eps E]
 * [--min-rate R] [--max-unknowns N] [--from CHECKPOINT] [--threads N]`
 * (sph/src/solver/stability_cmd.c): builds the solver as `run` does (repacking and settling
 * included; with --from, the checkpoint's state instead), forms J with sph_solver_jacobian() and
 * its modes with sph_stability_modes(), prints a summary and the N fastest-growing modes on stdout
 * and writes every mode into DIR/stability.csv (columns in --help). Returns 0, CMN_EXIT_FAILURE
 * if the eigensolver fails; bad input (open boundaries, more unknowns than --max-unknowns, a bad
 * or mismatched checkpoint, bad options) exits with CMN_EXIT_INPUT.
 */
int sph_cmd_stability(int argc, char **argv);

#ifdef __cplusplus
}
#endif
#endif /* SABRE_SPH_SOLVER_H */
