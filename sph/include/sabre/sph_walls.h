/*
 * SABRE sph/ — the Wendland C2 kernel and the unified semi-analytical wall integrals
 * (docs/theory.md §3, §3.1; derivations with equation references in docs/sph-gamma.md):
 *
 *   γ_a     = ∫_{Ω ∩ B(a)} w dV                                   J(2), M(2)
 *   ∇γ_as   = (∫_s w dS) n_s,   ∇γ_a = Σ_s ∇γ_as                  J(3), J(4), M(9), M(10)
 *   dγ_a/dt = v_a · ∇γ_a                                          M(4)
 *
 * Dimension d ∈ {1, 2, 3} is chosen at run time. A wall element ("segment" s) is a boundary point
 * with normal ±1 (1D), a line segment (2D) or a triangle (3D). γ_a is evaluated without time
 * integration by Gauss' theorem on Ω, one closed-form term per element; ∇γ_as is closed form too
 * in 2D and 3D, so every value is exact to round-off (measured errors in docs/sph-gamma.md).
 *
 * Units: lengths in m, w in 1/m^d, γ dimensionless, ∇γ in 1/m.
 */
#ifndef SABRE_SPH_WALLS_H
#define SABRE_SPH_WALLS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Wendland C2 kernel, M(1): w(r) = α_d/h^d (1 − q/2)^4 (1 + 2q) for q = r/h ≤ 2, 0 beyond;
 * α_1 = 3/4, α_2 = 7/(4π), α_3 = 21/(16π). Filled by sph_kernel_init(); treat as read-only.
 */
struct sph_kernel {
  int dim;        /**< d ∈ {1, 2, 3} */
  double h;       /**< smoothing length [m]; support radius 2h */
  double inv_h;   /**< 1/h [1/m] */
  double alpha;   /**< α_d [-] */
  double w_norm;  /**< α_d/h^d [1/m^d] */
  double dw_norm; /**< α_d/h^(d+1) [1/m^(d+1)] */
};

/** Set up the kernel for dimension dim and smoothing length h [m]. Returns 0, or -1 (k untouched)
 *  if k is NULL, dim ∉ {1, 2, 3} or h ∉ [1e-100, 1e100] (NaN included). */
int sph_kernel_init(struct sph_kernel *k, int dim, double h);
/** w(r) [1/m^d], M(1); r ≥ 0 is a distance (|r| is used). */
double sph_kernel_w(const struct sph_kernel *k, double r);
/** dw/dr [1/m^(d+1)] = α_d/h^(d+1) · (−5q (1 − q/2)^3); ≤ 0, zero at r = 0 and r ≥ 2h. */
double sph_kernel_dwdr(const struct sph_kernel *k, double r);
/** Support radius 2h [m]. */
static inline double sph_kernel_support(const struct sph_kernel *k) { return 2.0 * k->h; }

/**
 * One boundary element: 1D point (x[0][0]), 2D segment (x[0], x[1]; components 0 and 1), 3D
 * triangle (x[0], x[1], x[2]). normal: unit, pointing INTO the fluid (normal[0] = ±1 in 1D); it
 * must be perpendicular to the element (sph_gamma_eval checks this).
 */
struct sph_wall_element {
  double x[3][3];
  double normal[3];
};

/**
 * A point closer than SPH_GAMMA_PLANE_TOL·h to the plane (line, point) of an element and to the
 * element itself is treated as lying on it: its γ term is replaced by the one-sided limit from the
 * fluid (the solid-angle limit). γ changes by at most ≈ 0.74·SPH_GAMMA_PLANE_TOL across that band.
 */
#define SPH_GAMMA_PLANE_TOL 1e-12

/**
 * sph_gamma_eval moves a point on the walls (within SPH_GAMMA_PLANE_TOL·h of an element's plane)
 * that lies within SPH_GAMMA_SNAP_TOL·h of an element vertex (or else of a 3D edge) onto it, so
 * that all elements sharing it agree on where the point is (γ changes by ≲ SPH_GAMMA_SNAP_TOL).
 * This resolves corners of interior angle ≳ 2·10⁻² rad.
 */
#define SPH_GAMMA_SNAP_TOL 1e-10

/**
 * Contribution of one element to γ_a and ∇γ_a at point a (a[0..d-1] used).
 *
 * gamma_term [-] is the term subtracted from 1 (docs/theory.md §3.1, docs/sph-gamma.md eq. G1):
 *   γ_a = 1 − Σ_s gamma_term_s,  gamma_term_s = ∫_s G_d(|r|) (r·n_s)/|r|^d dS,
 * with G_d(r) = ∫_0^r w ρ^(d−1) dρ − 1/ω_d; it is ≥ 0 when a is on the fluid side of s.
 * grad_gamma_as [1/m] is ∇γ_as = (∫_s w dS) n_s, J(3); components beyond d are set to 0.
 * Both are 0 when s lies outside the support of a. Closed form in 1D, 2D and 3D.
 *
 * When a lies on the element (within SPH_GAMMA_PLANE_TOL·h), gamma_term is the limit for a
 * approaching along +n_s (e.g. 1/2 inside the element, 1/4 at an end of a 2D segment, β/(4π) at a
 * triangle vertex of angle β). Points on the walls need a common approach direction for all the
 * elements they touch: use sph_gamma_eval() for those. No validation (hot path).
 */
void sph_gamma_element(const struct sph_kernel *k, const double *a,
                       const struct sph_wall_element *e, double *gamma_term,
                       double grad_gamma_as[3]);

/**
 * γ_a, J(2), and ∇γ_a = Σ_s ∇γ_as, J(4), at point a from n elements (those outside the support
 * contribute 0). a must lie in the fluid domain Ω or on its boundary.
 *
 * Points on the walls (solid-angle limit): γ is continuous up to the wall, but each element's term
 * jumps across the element's plane. If a lies on the walls (within SPH_GAMMA_PLANE_TOL·h of an
 * element's plane and SPH_GAMMA_SNAP_TOL·h of the element), it is first moved onto a vertex or edge
 * within SPH_GAMMA_SNAP_TOL·h; then, for the elements that contain it, the term is replaced by its
 * limit as a + ε m, ε → 0+, where m is the angle-weighted pseudo-normal of those elements (a
 * vertex, edge or interior point of each); docs/sph-gamma.md §6. This gives 1/2 on a flat wall,
 * Θ/(2π) at a 2D corner of interior angle Θ (1/4 for a right angle), 1/4 on a 3D right-angle edge
 * and 1/8 in a 3D box corner.
 *
 * Returns 0, or -1 on bad input (a NULL pointer; e may be NULL if n = 0; kernel not initialised, a
 * normal that is not unit or not perpendicular to its element within 1e-6, a degenerate element, or
 * a point on the walls with no direction into the fluid, e.g. on a zero-thickness plate); outputs
 * are then NaN.
 */
int sph_gamma_eval(const struct sph_kernel *k, const double *a, size_t n,
                   const struct sph_wall_element *e, double *gamma, double grad_gamma[3]);

/**
 * Dynamic form of γ, M(4): dγ/dt = v·∇γ, integrated by the trapezoidal rule over dt:
 *   γ_new = γ_old + dt/2 (v_old·∇γ_old + v_new·∇γ_new).
 * v is the particle velocity relative to the walls [m/s]; dim components are used.
 */
double sph_gamma_dynamic_step(double gamma_old, const double *v_old, const double *grad_old,
                              const double *v_new, const double *grad_new, int dim, double dt);

struct sph_system;

/**
 * Geometric vertex volumes [m^d]: volume[i] (i over the vertex store of s) is the part of the wall
 * layer, the fluid within `thickness` [m] of the walls, that vertex i stands for. The layer is cut
 * into the parts nearest to each element (no double counting where elements meet at a concave
 * edge or corner) and each element's part goes to the element's vertex nearest to it (the
 * vertex's Voronoi cell within the element). Flat wall meshed at spacing Δr: Δr^(d−1) thickness
 * per vertex; in a right-angled box with thickness Δr/2: 1/2 of that on 3D edges and 2D corners,
 * 1/4 at 3D corners (the reference implementation's vertex volumes). Each element is sampled at
 * about 8 points per Δr (s->dr) along each direction, the depth by bisection: exact on 2D meshes
 * at spacing Δr, about 1 % at 3D edges and corners; the sum is the layer's volume to about 1e-4.
 * The caller owns `volume` (the vertex count of s). Returns 0, or -1 for a negative thickness or
 * Δr ≤ 0 (volume zeroed).
 */
int sph_walls_vertex_volumes(const struct sph_system *s, double thickness, double *volume);

#ifdef __cplusplus
}
#endif

#endif
