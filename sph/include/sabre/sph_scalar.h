/*
 * SABRE sph/ — scalar mode for fixed particles: a scalar field u on fluid particles that do not
 * move, with unified semi-analytical walls, advanced by the wave equation
 *
 *   u_tt = c² Lap u,                                                                M(75)
 *
 * with the boundary-corrected Laplacian M(18) (f = 1, B = u), evaluated by the solver's operator
 * sph_op_lap() (sabre/sph_solver.h, J(8) with β = 1):
 *
 *   Lap^γ_a(u) = 1/γ_a Σ_{b∈F∪V} V_b 2 (u_a − u_b) w'(r_ab)/r_ab − 2/γ_a Σ_{s∈S} ∂u/∂n|_s |∇γ_as|.
 *
 * Wall conditions per boundary group (M §6.1, docs/sph-scalar.md):
 *   - Robin μ1 u + μ2 ∂u/∂n = μ3, M(64) (Neumann: μ1 = 0): the vertex value u_v is the weighted
 *     least-squares value of order m, M(66–74) (sph_robin_*, sabre/sph_robin.h); the wall flux is
 *     ∂u/∂n|_s = (μ3 − μ1 u_s)/μ2, M(65), with u_s the mean of the segment's vertex values;
 *   - Dirichlet u = g: u_v = g, and ∂u/∂n at the vertex from the weighted least-squares fit
 *     u_a ≈ g + Σ_{j=1..m} c_j x_a^j (x_a = r_av·n_v, weights V_a w_va as M 72), ∂u/∂n|_v = c_1
 *     (beyond the paper); ∂u/∂n|_s is the mean over the segment's vertices.
 * n is the unit normal into the fluid throughout.
 *
 * Time integration: velocity Verlet (kick–drift–kick) on (u, u_t), one Laplacian per step,
 * second-order and time-reversible; eliminating u_t gives the central difference
 * u^{n+1} − 2u^n + u^{n−1} = Δt² c² Lap(u^n), the "second-order finite difference scheme" of
 * M §6.2. Stable for Δt < 2/(c √ρ(−Lap)), ρ the spectral radius (sph_scalar_spectral_radius()).
 *
 * Storage: the particle store (sabre/sph.h) with ρ = 1 for every particle, so that mass = volume:
 * V_a = Δr^d for the fluid, V_v = φ A_v Δr for the vertices (A_v the vertex's share of its
 * segments' measure, Σ_{s∋v}|s|/d; 1 in 1D) with the wall-layer thickness φ a parameter.
 *
 * Units: lengths in m, t in s, c in m/s, u in any unit [u]; Lap u in [u]/m².
 * Like the rest of sph/, set-up errors that cannot be reported stop the program (cmn_error);
 * boundary-value failures are returned as SPH_ROBIN_* statuses naming the vertex.
 */
#ifndef SABRE_SPH_SCALAR_H
#define SABRE_SPH_SCALAR_H

#include <stddef.h>

#include "sabre/sph.h"
#include "sabre/sph_robin.h"
#include "sabre/sph_solver.h"
#include "sabre/sph_walls.h"

#ifdef __cplusplus
extern "C" {
#endif

enum sph_scalar_bc_type { SPH_SCALAR_ROBIN = 0, SPH_SCALAR_DIRICHLET = 1 };

/** Wall condition of one boundary group. */
struct sph_scalar_bc {
  int type;                      /**< enum sph_scalar_bc_type */
  struct sph_robin_params robin; /**< ROBIN: μ1, μ2, μ3, order m, tolerances; length L = 2h is
                                      set by sph_scalar_init() when robin.length is 0 */
  double value;                  /**< DIRICHLET: g [u] */
  int order;                     /**< DIRICHLET: degree m ≥ 1 of the fit giving ∂u/∂n */
};

/** Defaults: homogeneous Neumann, m = 1 (sph_robin_params_init with length 0). */
void sph_scalar_bc_init(struct sph_scalar_bc *bc);

struct sph_scalar {
  struct sph_system sys; /**< fixed particles (owned); ρ = 1, mass = volume */
  struct sph_kernel kernel;
  struct sph_nbrs nb; /**< lists (radius 2h) and ∇γ_as per fluid–segment pair */
  double c;           /**< wave speed [m/s] */
  double phi;         /**< vertex layer thickness / Δr [-] */
  int nbc;
  struct sph_scalar_bc *bc; /**< nbc groups (owned copy) */
  int *seg_bc, *vert_bc;    /**< group of each segment / vertex */
  double *u[SPH_NKINDS];    /**< u per kind: fluid (state), vertex and segment (boundary values) */
  double *ut;               /**< u_t of the fluid [u/s] */
  double *lap;              /**< Lap^γ u of the fluid at the current u [u/m²] */
  double *dudn[SPH_NKINDS]; /**< ∂u/∂n at vertices and segments (index VERTEX, SEGMENT) [u/m] */
  double *flux;             /**< per fluid–segment pair: 2 ∂u/∂n|_s, the wall term of M(18) */
  size_t flux_cap;          /**< allocated length of flux (grown if the lists are rebuilt) */
  double *one[SPH_NKINDS];  /**< β = 1 for sph_op_lap() */
  double time;              /**< [s] */
  long step;
  struct sph_robin_ws ws;
};

/**
 * The wall layer the fluid cells leave uncovered, in units of Δr: φ = max(0, d_min/Δr − 1/2),
 * d_min the smallest distance from a fluid particle to a wall element within its lists. A lattice
 * whose first particles sit Δr/2 from the walls tiles the domain (φ = 0); one whose first
 * particles sit Δr from the walls leaves a layer Δr/2 thick to the vertices (φ = 1/2: in 1D the
 * particle sums are then the trapezoidal rule, the vertex carrying half a cell).
 */
double sph_scalar_auto_layer(const struct sph_system *s, const struct sph_nbrs *nb);

/**
 * Set up the scalar mode on a filled system s (moved into sc; s is left empty): kernel, lists
 * (the fluid does not move: built once), γ and ∇γ_as (closed form), volumes (vertex layer phi;
 * phi < 0: sph_scalar_auto_layer()), and the boundary groups: seg_bc[j] ∈ [0, nbc) is the group of
 * segment j; a vertex takes the group of the first segment that uses it. u and u_t start at 0.
 * Stops (cmn_error) on bad arguments.
 */
void sph_scalar_init(struct sph_scalar *sc, struct sph_system *s, double c, double phi, int nbc,
                     const struct sph_scalar_bc *bc, const int *seg_bc);
void sph_scalar_free(struct sph_scalar *sc);

/**
 * Vertex values u_v and normal derivatives of the current fluid field: Robin/Neumann M(64–74),
 * Dirichlet as above; segment values and fluxes as the mean of their vertices; the wall flux of
 * M(18) per fluid–segment pair. Returns SPH_ROBIN_SUCCESS, or the status of the first vertex that
 * failed (ETOOFEW, ESINGULAR, EINVAL), its index in *bad_vertex (may be NULL; −1 on success).
 */
int sph_scalar_boundary_values(struct sph_scalar *sc, long *bad_vertex);

/** Boundary values, then sc->lap = Lap^γ u, M(18), at every fluid particle. Same returns. */
int sph_scalar_laplacian(struct sph_scalar *sc, long *bad_vertex);

/**
 * One velocity-Verlet step of length dt > 0 [s] of u_tt = c² Lap u (sc->lap must be the
 * Laplacian of the current u: call sph_scalar_laplacian() once before the first step; each step
 * leaves it up to date). Returns 0, or −1 with a message naming the vertex or the particle in msg
 * (boundary-value failure, or a non-finite u).
 */
int sph_scalar_step(struct sph_scalar *sc, double dt, char *msg, size_t msglen);

/**
 * Estimate of the spectral radius of the linear part of u ↦ Lap^γ u (boundary values included)
 * [1/m²] by `iters` power iterations from a sawtooth start; u, u_t and lap are left unchanged.
 * Returns NaN if a boundary value fails.
 */
double sph_scalar_spectral_radius(struct sph_scalar *sc, int iters);

/** Δt limit of velocity Verlet, 2/(c √radius) [s]. */
double sph_scalar_dt_limit(const struct sph_scalar *sc, double radius);

/**
 * `sabre-sph scalar CASE.yaml [--set key=value]... [--output DIR]`: read the case
 * (docs/sph-scalar.md), run the wave equation and write used_case.yaml, series.csv, profiles.csv
 * and vertices.csv into DIR. Returns the exit code.
 */
int sph_cmd_scalar(int argc, char **argv);

#ifdef __cplusplus
}
#endif
#endif /* SABRE_SPH_SCALAR_H */
