/*
 * SABRE sph/ — open boundaries (inlets and outlets) driven by the boundary Riemann problem of J
 * §III: on each open segment (and each open vertex) the user imposes ONE quantity, the pressure or
 * the normal velocity, and the compatible other one follows from riemann/
 * (rmn_boundary_solve_batch) for the interior state that the fluid gives by Shepard interpolation,
 * J(33–35). Equations as implemented: docs/sph-solver.md §10; case-file keys:
 * docs/sph-case-file.md, `open_boundaries`.
 *
 * Scope: the boundary VALUES; the mass through the boundary into the vertex masses J(14–15) with
 * the open-boundary terms of the continuity J(11–13); particle creation at vertices that gained
 * a particle's mass and deletion of particles that cross an open segment (δm_v of J 14). The open
 * segments act on the fluid like walls carrying the solved ρ_s, p_s, v_s.
 *
 * Three layers:
 *   1. the case-file section, read into plain data (struct sph_open_config, a member of struct
 *      sph_config: copyable, no pointers), and checked against the wall mesh;
 *   2. the imposed value of one group at a point and time (struct sph_open_source: expressions,
 *      a table of time, or a generator: Poiseuille, Stokes fifth order, solitary, hydrostatic);
 *   3. the run-time state (struct sph_open, owned by struct sph_solver): which segments and
 *      vertices belong to which group, and at each force evaluation the Shepard interior states,
 *      one batch solve per group, the values written into the particle store, per-group means for
 *      the output, and the first failure.
 *
 * Units SI. Normals point INTO the fluid; a normal velocity u_n > 0 is an inflow. Like the rest of
 * sph/, case-file errors go through common/ (file, line, key; exit code 2); the run-time layer
 * never exits on a failed solve but reports it (sph_solver_step() stops the run with the message).
 */
#ifndef SABRE_SPH_OPEN_H
#define SABRE_SPH_OPEN_H

#include <stddef.h>

#include "sabre/riemann.h"
#include "sabre/sph.h"
#include "sabre/sph_waves.h"

struct cmn_case;
struct cmn_expr;
struct sph_solver;

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * 1. Configuration: the `open_boundaries` section (docs/sph-case-file.md)
 * ------------------------------------------------------------------------------------------- */

#define SPH_MAX_OPEN_GROUPS 16
/** Longest expression text + 1. */
#define SPH_OPEN_EXPR_LEN 256

/** Where the imposed value of a group comes from (exactly one per group). */
enum sph_open_source_kind {
  SPH_OPEN_VALUE = 0,       /**< `pressure`, `velocity` or `normal_velocity`: numbers or
                                 expressions of t, x, y (, z) */
  SPH_OPEN_TABLE = 1,       /**< `table`: a CSV table of time (t,p / t,un / t,u,v(,w)) */
  SPH_OPEN_POISEUILLE = 2,  /**< `poiseuille`: laminar duct profile along the inward normal */
  SPH_OPEN_STOKES5 = 3,     /**< `stokes5`: Fenton's fifth-order Stokes wave (sabre/sph_waves.h) */
  SPH_OPEN_SOLITARY = 4,    /**< `solitary`: the solitary wave of J(42–47) */
  SPH_OPEN_HYDROSTATIC = 5, /**< `hydrostatic`: p = ρ0 g (d − z), d given or measured */
};

/** Cross-sections of the `poiseuille` generator. */
enum sph_open_duct {
  SPH_DUCT_PLATES = 0, /**< 2D: between two plates 2R apart, u = U (1 − r²/R²) */
  SPH_DUCT_CIRCLE = 1, /**< 3D: circular pipe of radius R, u = U (1 − r²/R²) */
  SPH_DUCT_RECTANGLE =
      2, /**< 3D: rectangular duct 2a × 2b (Fourier series of the Poisson problem) */
};

/** Parameters of the `poiseuille` generator [m, m/s]. */
struct sph_open_poiseuille {
  int shape;        /**< enum sph_open_duct */
  double center[3]; /**< a point on the duct's axis (2D: on the mid-line) [m] */
  double radius;    /**< R: half the distance between the plates, or the pipe radius [m] */
  double half[2];   /**< a, b: half-widths of the rectangle along `axis` and across it [m] */
  double axis[3];   /**< unit vector in the boundary's plane along the side of half-width a */
  double u_max;     /**< centre-line speed U along the inward normal [m/s] (> 0: inflow); derived
                         from `flux` when that is given */
  double flux;      /**< the volume flux Q it implies (2D: per unit depth) [m^d/s] */
  double ramp;      /**< start-up time T [s]: the profile is multiplied by s²(3 − 2s),
                         s = min(t/T, 1), a C¹ rise from 0 at t ≤ 0 to 1 at t ≥ T; 0: none */
};

/** One open-boundary group: which segments, what is imposed, from where. Plain data. */
struct sph_open_group {
  char name[64];  /**< unique; the output is open_<name>.csv */
  int wall;       /**< index into geometry.walls */
  int nedges;     /**< 0: every open element of that wall (or of `faces`) */
  long edges[64]; /**< 1-based element numbers within the wall (each must be open) */
  unsigned faces; /**< box and channel walls: the faces selected instead of `edges`, bit 2a the
                       face at the low end of axis a, bit 2a + 1 the high end (0: none) */
  int nsolids;    /**< STL walls: the named solids selected instead of `edges` (0: none) */
  char solids[8][64];
  long solid_first[8], solid_last[8]; /**< their element ranges, set by sph_open_check_mesh */
  int imposed;                        /**< enum rmn_imposed */
  int source;                         /**< enum sph_open_source_kind */
  int shock; /**< enum rmn_shock_model: RMN_SHOCK_EXACT (default) or RMN_SHOCK_LINEARISED */
  /** `outflow_deficit`: the most mass an outflow vertex may owe, in masses ρ0 Δr^d of a created
   *  particle (default 1): its mass stays at or above its wall mass minus this, the flux it would
   *  let out beyond that stays in the fluid (mass_withheld) and leaves with the particles that
   *  cross (docs/sph-solver.md §10) */
  double outflow_deficit;
  /** SPH_OPEN_VALUE: the pressure [Pa] or the normal velocity into the fluid [m/s] in expr[0]
   *  (ncomp = 1), or the velocity vector's components [m/s] in expr[0..dim-1] (ncomp = dim); each
   *  a number or an expression of t, x, y (, z). */
  char expr[3][SPH_OPEN_EXPR_LEN];
  int ncomp;
  /** 1 when the velocity is given as a normal speed (normal_velocity, a t,un table, poiseuille),
   *  0 for a vector (velocity, a t,u,v(,w) table, the waves). */
  int normal;
  double tangential[3]; /**< `tangential_velocity`: the inflow's tangential velocity when the
                             source gives none (its normal part is removed per point) [m/s] */
  char table[512];      /**< SPH_OPEN_TABLE: path of the table file (resolved) */
  struct sph_open_poiseuille poiseuille;
  struct sph_stokes5_params stokes5;   /**< g and rho0 are the case's |gravity| and fluid.rho0 */
  struct sph_solitary_params solitary; /**< angle in radians here (degrees in the case file) */
  /** Waves and hydrostatic: the bed (z = 0 of the formulas) lies at elevation `bed` along −g; the
   *  waves travel along the horizontal unit vector `direction` (3D: y of the formulas is
   *  up × direction); Stokes waves have their crest at x = x0 + c t. */
  double bed, direction[3], x0;
  double depth;       /**< hydrostatic: water depth d above the bed [m] (when not measured) */
  int depth_measured; /**< hydrostatic: d measured at each evaluation (top fluid particle within
                           2h of the group's segments + Δr/2, minus `bed`) */
  int absorbing;      /**< hydrostatic with a given depth D: the level follows the outgoing
                           shallow-water Riemann invariant (docs/sph-solver.md §10): √(g d_b) =
                           (u_out − U + 2√(g d_int) + 2√(g D))/4, d_int measured as above and
                           u_out the mean Shepard outflow velocity of the group's segments that
                           see fluid, both of the same evaluation; U is `current` */
  double current;     /**< absorbing: the outward normal velocity U of the steady state whose
                           level is D (the incoming invariant U − 2√(g D)) [m/s], default 0 */
};

struct sph_open_config {
  int ngroups;
  struct sph_open_group group[SPH_MAX_OPEN_GROUPS];
};

/**
 * Read the `open_boundaries` section (a list; absent: no groups) into *oc. Needs the fluid,
 * gravity and geometry keys read by sph_config_read(): rho0, c0, xi, gravity and dim are passed in.
 * Every value is checked where it can be without the mesh: unknown choices, wrong types, a missing
 * `impose`, no value or more than one, a value of the wrong kind for `impose`, a constant pressure
 * at or below the EOS's vacuum pressure p(0), a constant speed not below c0, an expression that
 * does not compile, an unreadable table or one whose time column does not increase strictly, and
 * the generators' own parameter checks. Errors name the file, line and key (cmn_case_fail; the
 * program exits in fatal mode). Returns 0 or -1.
 */
int sph_open_config_read(struct sph_open_config *oc, struct cmn_case *c, int dim,
                         const double gravity[3], const struct rmn_eos *eos);

/**
 * Read a wave generator mapping at `base` (e.g. "initial.wave": exactly one of `stokes5` and
 * `solitary`, with the keys of the open-boundary generators) into *g: source SPH_OPEN_STOKES5 or
 * SPH_OPEN_SOLITARY, name = base, wall −1, imposed velocity. Needs a non-zero gravity and
 * dimension 2 or 3. Errors name the file, line and key; returns 0 or -1.
 */
int sph_open_wave_read(struct cmn_case *c, const char *base, int dim, const double gravity[3],
                       const struct rmn_eos *eos, struct sph_open_group *g);

/**
 * Check the groups against the wall mesh before anything is written: each selected element
 * (or face) exists and is flagged open (SPH_FLAG_OPEN), a group selects at least one element,
 * and every open element belongs to exactly one group. Element numbers are those of the mesh's
 * sources (source = wall index, source_index = element number). Errors name the file, line and key
 * (`open_boundaries[i].edges`, or `geometry.walls[k]` for an open element no group selects).
 * Returns 0 or -1.
 */
int sph_open_check_mesh(struct sph_open_config *oc, struct cmn_case *c,
                        const struct sph_mesh *walls);

/* ---------------------------------------------------------------------------------------------
 * 2. The imposed value of one group
 * ------------------------------------------------------------------------------------------- */

/** The data imposed at one point and time (global frame). */
struct sph_open_value {
  double p;    /**< imposed pressure [Pa] (imposed == RMN_IMPOSE_PRESSURE), else NaN */
  double un;   /**< imposed normal velocity into the fluid [m/s] (RMN_IMPOSE_VELOCITY), else NaN */
  double u[3]; /**< velocity whose part tangential to the boundary is the inflow's tangential
                    velocity, J §III [m/s] (its normal part equals un for imposed velocity) */
};

/** A group's value source ready for evaluation. Owns its compiled expressions and table. */
struct sph_open_source {
  const struct sph_open_group *group; /**< the configuration (not owned; must outlive this) */
  int dim;
  struct rmn_eos eos;         /**< for the hydrostatic profile */
  double g, up[3];            /**< |gravity| [m/s²] and −g/|g| (zero without gravity) */
  double side[3];             /**< up × direction (3D waves) */
  struct cmn_expr *expr[3];   /**< compiled expressions (SPH_OPEN_VALUE) */
  double *table;              /**< SPH_OPEN_TABLE: rows × ncols values, row-major (owned) */
  size_t nrows;               /**< rows of the table */
  int ncols;                  /**< 2 (t,p or t,un) or 1 + dim (t,u,v(,w)) */
  struct sph_stokes5 stokes5; /**< resolved Stokes wave */
  struct sph_solitary solitary;
  double duct_scale; /**< rectangle: U_max / f(0, 0) of the series profile f [1/m²] */
};

/**
 * Compile the group's expressions, read its table and resolve its generator. gravity: the case's
 * gravity vector; eos: the fluid's. Returns 0, or -1 with a message in msg (the configuration was
 * checked by sph_open_config_read(), so a failure here means the table file changed or an
 * internal error). On failure *src is left freed.
 */
int sph_open_source_init(struct sph_open_source *src, const struct sph_open_group *group, int dim,
                         const double gravity[3], const struct rmn_eos *eos, char *msg,
                         size_t msglen);
void sph_open_source_free(struct sph_open_source *src);

/**
 * The value imposed at point x [m] with unit normal n (into the fluid) at time t [s]; `level` is
 * the measured free-surface elevation along −g [m] for a `hydrostatic` source with
 * depth_measured (ignored otherwise; NaN or −∞ there means no fluid: p = 0). Conventions
 * (docs/sph-case-file.md): expressions and tables are evaluated as given; a Poiseuille profile is
 * zero outside the duct; the waves are evaluated at the point's height clamped to [bed, surface]
 * (at a point above the wave's surface, the surface values: p = 0 and the surface velocity); the
 * hydrostatic pressure is zero above the level. Pure function: no allocation, thread-safe.
 */
void sph_open_source_eval(const struct sph_open_source *src, double t, const double x[3],
                          const double n[3], double level, struct sph_open_value *out);

/**
 * A wave generator (stokes5 or solitary, src->group->source) at point x [m], time t [s]: returns
 * the elevation of the wave's free surface above x along −g [m] (bed + η); *p receives the gauge
 * pressure [Pa] and u the velocity [m/s], both at x's height clamped to [bed, surface] as in
 * sph_open_source_eval(). Pure function, thread-safe.
 */
double sph_open_source_wave(const struct sph_open_source *src, double t, const double x[3],
                            double *p, double u[3]);

/** Hydrostatic pressure of the Tait fluid at depth d ≥ 0 below the level of p = 0 [Pa]:
 *  b [(1 + (ξ−1) g d/c0²)^(ξ/(ξ−1)) − 1] (ξ = 1: b (e^{g d/c0²} − 1)), b = ρ0 c0²/ξ, i.e.
 *  ρ0 g d (1 + g d/(2 c0²) + ...): the profile of initial.pressure: hydrostatic. */
double sph_hydrostatic_pressure(const struct rmn_eos *eos, double g, double depth);

/* ---------------------------------------------------------------------------------------------
 * 3. Run-time state
 * ------------------------------------------------------------------------------------------- */

/** Per-group results of the last evaluation (means weighted by segment measure, over the group's
 *  segments that had fluid within 2h of their centroid). */
struct sph_open_stats {
  double time;          /**< time of the evaluation [s] */
  double imposed;       /**< mean imposed value: pressure [Pa] or normal velocity [m/s] */
  double p, un;         /**< mean solved pressure [Pa] and normal velocity into the fluid [m/s] */
  double p_int, un_int; /**< mean interior (Shepard) pressure and normal velocity */
  double volume_flux;   /**< Σ_s |s| u_n,s (> 0 into the fluid) [m^d/s; 2D per unit depth] */
  double mass_flux;     /**< Σ_s ρ_s |s| u_n,s, J(15) summed over the group's vertices (> 0 into
                             the fluid) [kg/s; 2D per unit depth] */
  double level;  /**< measured free-surface level (hydrostatic, measured), the imposed level of an
                      absorbing hydrostatic outlet, else NaN [m] */
  long nwave[3]; /**< segments per wave type (enum rmn_wave: contact, expansion, shock) */
  long ndry;     /**< segments not solved (no fluid within 2h, or above the local free
                      surface: wet fraction 0); they keep wall values */
};

/** One group's points: its segments, then its vertices. Arrays of npoints (owned). */
struct sph_open_points {
  size_t nseg, nvert, npoints;
  size_t *index;       /**< store index: segment for [0, nseg), vertex for [nseg, npoints) */
  double (*normal)[3]; /**< unit normal into the fluid: the segment's; for a vertex the
                            measure-weighted mean of its open segments' normals in this group */
  double *measure;     /**< segment measure; 0 for vertices */
  long *element;       /**< segment: element number within its wall (0 unknown); vertex: -1 */
  double (*zrange)[2]; /**< lowest and highest elevation along −g [m]: a segment's vertices', a
                            vertex's own (0 without gravity); set once (fixed boundaries) */
  /* the last evaluation */
  double *alpha;      /**< Shepard sum Σ_b V_b w_b, J(34) [-] */
  double *wet;        /**< wet fraction: 1 below the local free surface (and without gravity),
                            a segment's submerged part of its vertical extent when it
                            straddles it, 0 dry (docs/sph-solver.md §10) [-] */
  double *p_int;      /**< interior pressure, J(33) with numerics.vertex_hydrostatic [Pa] */
  double (*u_int)[3]; /**< interior velocity, J(35) [m/s] */
  struct sph_open_value *value;    /**< imposed data */
  struct rmn_boundary_input *in;   /**< the batch's input (wet points packed first) */
  struct rmn_boundary_result *out; /**< the batch's results, same order as `in` */
  size_t *slot;                    /**< point → position in in/out, or (size_t)-1 when dry */
  size_t nwet;                     /**< inputs of the last batch */
};

/** Open-boundary state of a solver (sv->open; NULL when the case has no open groups). */
struct sph_open {
  int ngroups;
  struct sph_open_source *src;                   /**< per group */
  struct sph_open_points *pts;                   /**< per group */
  struct sph_open_stats *stats;                  /**< per group */
  struct rmn_params params[SPH_MAX_OPEN_GROUPS]; /**< per group: shock model, default tolerances */
  int *seg_group;                                /**< per segment: its group, or −1 (a wall) */
  long *seg_point;     /**< per segment: its point index within its group, or −1 */
  int *vert_group;     /**< per vertex: its group, or −1 */
  long *vert_point;    /**< per vertex: its point index within its group, or −1 */
  double (*wall_v)[3]; /**< per open vertex, in vertex order: the store's velocity at creation
                            (the wall's), which sph_open_restore_walls() puts back */
  /* Mass through the boundary, J(14–15) (docs/sph-solver.md §10): per vertex of the store (0 for
   * vertices that are not open). */
  double *mdot;  /**< ṁ_v of the last evaluation, J(15) [kg/s; 2D per unit depth] */
  double *mass0; /**< m_v^n: the vertex masses at the start of the current step [kg] */
  double mass_step[SPH_MAX_OPEN_GROUPS];    /**< mass that entered through each group during the
                                                 last step, Δt Σ_v ṁ_v* plus what the floor of
                                                 its outflow vertices held back [kg] (> 0:
                                                 inflow) */
  double mass_entered[SPH_MAX_OPEN_GROUPS]; /**< Σ mass_step since the run began: Σ ∫ mass_flux
                                                 dt as the vertex masses took it [kg; 2D per unit
                                                 depth] */
  int no_io_terms; /**< tests only: 1 leaves the i/o terms of J(11) out of the continuity */
  /* Particle creation and deletion, δm_v of J(14) (docs/sph-solver.md §10). */
  double cell_volume; /**< Δr^d, the volume of a created particle: its mass is the vertex's solved
                           density times it [m^d] */
  long created[SPH_MAX_OPEN_GROUPS], deleted[SPH_MAX_OPEN_GROUPS]; /**< since the run began */
  /** Mass that left with particles deleted through each group beyond what the group's outflow
   *  vertices took back, since the run began [kg; 2D per unit depth]: a particle leaving through
   *  an outflow vertex (ṁ_v < 0) brings that vertex's mass back towards its wall mass by the
   *  particle's barycentric weight instead of adding the particle's mass to it
   *  (sph_open_delete_particles). Fluid + vertex masses − Σ mass_entered + Σ mass_released is
   *  constant. */
  double mass_released[SPH_MAX_OPEN_GROUPS];
  /** Outflow the vertices of each group did not take since the run began, being at the floor of
   *  their mass, m_base,v − outflow_deficit ρ0 Δr^d (sph_open_mass_set) [kg; 2D per unit depth]:
   *  mass_entered − ∫ mass_flux dt (≥ 0). */
  double mass_withheld[SPH_MAX_OPEN_GROUPS];
  /** The compensations of the three cumulative sums above (entered, released, withheld: Kahan
   *  summation, in the checkpoint): the sums reach 10⁴ times the mass in the domain in a long
   *  through-flow; open_channel_2d's balance is 1.4e-14 with them, 4.8e-13 without [kg]. */
  double mass_comp[3][SPH_MAX_OPEN_GROUPS];
  /** The entered mass of inflow vertices as a layer in the pressure gradient (sph_open_layer):
   *  per vertex, the volume m_v/ρ_v − m_base/ρ_v taken from the vertex (0 for the others) [m^d]
   *  and where it counts instead [m]. */
  double *layer_vol;
  double *layer_x[3];
  struct rmn_workspace *ws;
  double *work; /**< scratch of sph_open_boundary_values(): the Shepard sums of every point */
  /** First failure of the last evaluation: 0 none, else the riemann/ status; and its message
   *  (group, segment or vertex with its element and position, time, interior and imposed
   *  states). */
  int fail;
  char fail_msg[1536];
};

/**
 * Build the open-boundary state of a solver whose store holds the walls: each segment of a group
 * (its wall index seg_wall[j] and element number seg_edge[j], as for force groups; both may be
 * NULL only when there are no groups) and each vertex of an open segment of a group (the group
 * of its first such segment; corners shared with walls included). Returns NULL when the case has
 * no groups. Returns the state (owned by the caller: sph_open_free), or NULL with a message in msg
 * and *failed = 1 when a group selects nothing or an open segment belongs to no group (run.c
 * reports these earlier through sph_open_check_mesh).
 */
struct sph_open *sph_open_create(const struct sph_solver *sv, const int *seg_wall,
                                 const long *seg_edge, int *failed, char *msg, size_t msglen);
void sph_open_free(struct sph_open *op);

/**
 * The open-boundary values of the state in sv at time t (docs/sph-solver.md §10), after the wall
 * values (the fluid pressures p(ρ) must be current). For every point (segment centroid or vertex)
 * of every group: the interior state by Shepard over the fluid within 2h, J(33–35), with the
 * hydrostatic correction of numerics.vertex_hydrostatic and the same floor as the wall vertices,
 * ρ_int = ρ(p_int); the imposed value at the point; then ONE rmn_boundary_solve_batch call per
 * group over its points with fluid near them. The results overwrite ρ, p, v (and μ = ν ρ) of the
 * group's segments and vertices in the store; points without fluid keep their wall values. Stats
 * are updated. A failed solve sets op->fail and op->fail_msg (the first failing point in group
 * order); the other points keep their results. Serial and deterministic.
 */
void sph_open_boundary_values(struct sph_open *op, struct sph_solver *sv, double t);

/**
 * Put the wall velocity back on the open vertices before the wall pass of
 * sph_solver_boundary_values(): wall segments next to an open vertex (corners) take the mean of
 * their vertices' velocities, which must not be the open vertex's solved velocity of the previous
 * evaluation (the result would depend on the history, and a restart would not be bit-identical).
 */
void sph_open_restore_walls(struct sph_open *op, struct sph_solver *sv);

/**
 * Does group g select the element of wall `wall`, number `edge` (1-based), with inward unit
 * normal n and flags `flags`? By `edges`, by `faces` (the element's normal is the face's inward
 * normal), or, with neither, when the element is open.
 */
int sph_open_group_selects(const struct sph_open_group *g, int wall, long edge, const double n[3],
                           unsigned flags);

/**
 * Vertex masses through the predictor–corrector, J(14) (docs/sph-solver.md §10); no-ops for
 * op == NULL. sph_open_mass_begin(): keep m_v^n (at the start of a step, after the evaluation of
 * state n). sph_open_mass_set(op, sv, fac): m_v = m_v^n + fac ṁ_v with ṁ_v of the last evaluation
 * (fac = Δt/2 after the predictor's continuity: m*, ṁ^n; fac = 0 to put m^n back before the
 * corrector's continuity). sph_open_mass_end(op, sv, dt): m_v^{n+1} = m_v^n + Δt ṁ_v* (the
 * predictor's ṁ) and mass_step[g] = Δt × the group's mass flux. An outflow vertex (ṁ_v < 0) stops
 * at its floor, m_base,v − outflow_deficit ρ0 Δr^d of its group (or m_v^n when that is lower
 * already): mass_step[g] is then the vertices' actual change, Δt × the mass flux plus what the
 * floor held back, which mass_withheld[g] adds up.
 */
void sph_open_mass_begin(struct sph_open *op, const struct sph_solver *sv);
void sph_open_mass_set(struct sph_open *op, struct sph_solver *sv, double fac);
void sph_open_mass_end(struct sph_open *op, struct sph_solver *sv, double dt);

/**
 * Delete the fluid particles that left the domain through an open segment: those flagged behind
 * the walls (sv->nb.behind, from the last γ evaluation) whose nearest element is an open segment.
 * The segment's vertices take the particle's barycentric weights w_v (sph_open_share's rule:
 * corners' weights to the others): an inflow vertex (ṁ_v ≥ 0 at the last evaluation) gains
 * w_v m_a, J(14); an outflow vertex (ṁ_v < 0) has its mass brought back towards its wall mass,
 * m_v += w_v (m_base,v − m_v), and what the particle brought beyond that, w_v m_a minus that
 * change, leaves with it (mass_released): at an outflow the vertex's mass below its wall mass is
 * the fluid its flux let out before the particle crossed, and this rule keeps it in phase with the
 * particles instead of integrating the difference between the flux and the crossings
 * (docs/sph-solver.md §10). Compacts nb.behind with the store. Returns how many were deleted (0 for
 * op == NULL).
 */
size_t sph_open_delete_particles(struct sph_open *op, struct sph_solver *sv);
/**
 * The open segment through which fluid particle a has left the fluid domain, or -1: a is behind
 * the walls at the positions of the last γ evaluation (nb.behind) and the element nearest to it
 * is an open segment. -1 too for op == NULL, with the open boundaries switched off, or when the
 * nearest element is a wall. Used mid-step for the leaving particles (docs/sph-solver.md §10)
 * and after the step for the deletion.
 */
long sph_open_exit_segment(const struct sph_open *op, const struct sph_solver *sv, size_t a);
/**
 * Create a fluid particle at each open vertex whose mass exceeds its wall mass by at least
 * m = ρ_v Δr^d, ρ_v the vertex's solved density of the last evaluation (at most one per vertex and
 * call, vertices in index order): at r_v + (φ + ½)Δr n_v (n_v the vertex's open normal), with the
 * vertex's solved velocity and density, mass m (volume Δr^d), which the vertex loses. Returns how
 * many were created.
 */
size_t sph_open_create_particles(struct sph_open *op, struct sph_solver *sv);
/**
 * The entered mass of the inflow vertices as a layer (docs/sph-solver.md §10): for each open
 * vertex that is not a corner, whose solved velocity points into the fluid (u·n_v > 0) and whose
 * mass exceeds its wall mass, δm = m_v − m_base > 0 (the fluid that has entered and is not yet a
 * particle), layer_vol = δm/ρ_v and layer_x = r_v + (φ + ½ δm/(ρ_v Δr^d)) Δr n_v: the centre of the
 * layer δm stands for, in front of the wall layer (φΔr thick) of the vertex; at δm = ρ_v Δr^d, the
 * position of the particle the vertex then creates. 0 for every other vertex. From the store as it
 * is (vertex masses, solved values). No-op for op == NULL.
 */
void sph_open_layer(struct sph_open *op, const struct sph_solver *sv);

/**
 * The i/o terms of the time-summation continuity J(11) for fluid particle a, from the start
 * positions x0 (r_a^n), ρ_a^n and the open segments' and vertices' velocities in the store (those
 * of the last evaluation), with the virtual displacements δr = fac u of J(12–13) (fac = Δt/2 in
 * the predictor, Δt in the corrector):
 *   ρ_a^n/2 Σ_{s∈S^io} [∇γ_as(r_as^n + δr_s) + ∇γ_as(r_as^n)]·δr_s
 *   + Σ_{v∈V^io} m_v^n [w(r_av^n) − w(r_av^n + δr_v)],
 * over the open segments and vertices in a's lists. Returns 0 when op is NULL.
 */
double sph_open_continuity_terms(const struct sph_open *op, const struct sph_solver *sv, size_t a,
                                 const double xa0[3], double rho_a0, double fac);

/** Column names of open_<name>.csv (SPH_OPEN_CSV_COLUMNS of them, static storage). */
#define SPH_OPEN_CSV_COLUMNS 18
const char *const *sph_open_csv_columns(void);
/** One row of open_<name>.csv for group g from its last stats (time given by the caller). */
void sph_open_csv_row(const struct sph_open *op, int g, double time,
                      double row[SPH_OPEN_CSV_COLUMNS]);

#ifdef __cplusplus
}
#endif
#endif /* SABRE_SPH_OPEN_H */
