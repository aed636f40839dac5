/*
 * The pressure gradient of the momentum equation M(14) (docs/sph-solver.md §4): Grad^{γ,k} of
 * M(37) in which a wall, i.e. its vertex particles and its segments, does not pull a particle that
 * moves towards it.
 */
#ifndef SPH_OPERATORS_PRESSURE_H
#define SPH_OPERATORS_PRESSURE_H

#include <stddef.h>

#include "sabre/sph_solver.h"

/**
 * Grad^{γ,k}_a(p), M(37) [Pa/m], with every wall pair left out whose pressure sum is negative
 * while particle a does not move away from the element: a vertex v with
 * (ρ_a/ρ_v)^k p_v + (ρ_v/ρ_a)^k p_a < 0 and (v_a − v_v)·(r_a − r_v) ≤ 0, a segment s with
 * (ρ_a/ρ_s)^k p_s + (ρ_s/ρ_a)^k p_a < 0 and (v_a − v_s)·n_s ≤ 0 (n_s into the fluid; v_v, v_s
 * the elements' own motion: a wall's velocity, 0 for open elements, which are fixed in space and
 * whose stored velocity is the fluid's at the boundary). With
 * p_a + p_wall < 0 those terms pull particle a towards the element (the wall term of a constant
 * field p is p times the zeroth-order defect of §2, which points out of the fluid), and nothing
 * else stops it: as a particle whose fluid neighbours recede (a free surface at a wall) moves
 * into the wall, γ_a falls with Σ m_b w_ab and its density stays at ρ0. A pull left out would
 * have done work ≥ 0 on the pair's relative motion (the force of a vertex pair is along r_a − r_v,
 * that of a segment along n_s), so the rule never adds kinetic energy to that of M(37); a
 * receding particle is held back as M(37) holds it. Fluid–fluid pairs are kept as they are.
 * Equals sph_op_grad() wherever the wall pressure sums are ≥ 0 (still water below its surface).
 *
 * impedance (NULL: none; struct sph_wall_impedance below). When given, the wall value of a pair
 * whose fluid particle approaches the element, u_n = (v_a − v_w)·n < 0 (n the element's unit
 * normal into the fluid; a vertex's normal normalised), is raised by −ω_ae Z_a u_n, Z_a = ρ_a c_a:
 * the pressure behind the acoustic wave that brings the relative normal velocity to zero, the
 * linearised boundary Riemann problem with the wall's normal velocity imposed (docs/sph-solver.md
 * §4). ω_ae = 1 for every pair (acoustic form), or the contact weight of a particle close to the
 * element (contact form, below). A receding particle sees the wall value unchanged. Open elements
 * (SPH_FLAG_OPEN) keep the values of their own Riemann solve.
 *
 * open_difference (numerics.open_gradient: difference): next to an open boundary the operator is
 * made exact for a constant field in proportion to χ_a, the share of the wet open segments
 * (SPH_FLAG_WET) in the wall terms of a's kernel (Σ_wet |term_as| / Σ_s |term_as|, 0 without
 * segments): every pair's
 * f_a-part loses χ_a f_a, so that χ_a = 1 (a particle that sees only open segments) gives the
 * difference form (ρ_a/ρ_b)^k (f_b − f_a) and χ_a = 0 (walls only, or the bulk) M(37) unchanged,
 * bit for bit. Without it the flowing rows' zeroth-order defect at an open boundary pushes the
 * fluid in proportion to the pressure level (docs/sph-solver.md §10).
 *
 * layer (NULL: none): per vertex b, a volume vol[b] [m^d] that counts at (x[0][b], x[1][b],
 * x[2][b]) instead of at r_b, with b's pressure and density (its volume at r_b is then
 * m_b/ρ_b − vol[b]): the entered mass of the inflow vertices (sph_open_layer,
 * docs/sph-solver.md §10). A vertex pair left out by the rule above is left out at both places.
 */
struct sph_vertex_layer {
  const double *vol;
  const double *const *x;
};

/**
 * The wall impedance of sph_op_grad_pressure. z: per fluid particle, Z_a = ρ_a c_a [kg/m²/s].
 * reach [m]: 0 for the acoustic form (ω_ae = 1 for every pair); > 0 for the contact form,
 * ω_ae = max(0, 1 − d_ae/reach) for d_ae > 0 and 0 for d_ae ≤ 0, d_ae = (r_a − r_e)·n_e the
 * distance of particle a from the element's plane (a segment's; for a vertex the plane through it
 * normal to its normal): the term acts on a particle that closes in on the element within reach,
 * in full at contact, and not on the fluid further off (which meets the fluid layer in front of
 * it, not the wall) nor on a particle behind the plane (round a convex edge).
 */
struct sph_wall_impedance {
  const double *z;
  double reach;
};
void sph_op_grad_pressure(const struct sph_op *op, double k, const double *const p[SPH_NKINDS],
                          size_t a, const struct sph_wall_impedance *impedance, int open_difference,
                          const struct sph_vertex_layer *layer, double out[3]);

/* χ_a of open_difference above. */
double sph_op_open_share(const struct sph_op *op, size_t a);

/*
 * The momentum equation's pair loops fused (solver.c): the caller sums the fluid pairs of a in one
 * pass over its fluid neighbours, in the list's order and with the arithmetic of
 * sph_op_grad_pressure and sph_op_lap (for a fluid pair: (ρ_a/ρ_b)^k p_b + p_a/(ρ_a/ρ_b)^k less
 * χ_a p_a ((ρ_a/ρ_b)^k + (ρ_b/ρ_a)^k), times V_b w'(r)/r r_ab; and V_b 2 β̄_ab w'(r)/r (A_a − A_b),
 * pairs at r = 0 left out), and these go on from that sum over the vertices and segments: the
 * result is bitwise that of the unfused operators (tests/sph/test_solver.c).
 */
void sph_op_grad_pressure_walls(const struct sph_op *op, double k,
                                const double *const p[SPH_NKINDS], size_t a,
                                const struct sph_wall_impedance *impedance, int open_difference,
                                const struct sph_vertex_layer *layer, const double g_fluid[3],
                                double out[3]);
/*
 * The viscous wall flux of M(19–20) for the pair q (segment j) of fluid particle a:
 * (μ_a + μ_s) (v_a − v_s)_t / max(z, z_min), z = nb->dist_as[q] the distance from a to the
 * segment's plane, (·)_t the part along the segment. Computed where it is used (the momentum
 * equation, the wall forces) rather than stored per pair: 24 bytes per fluid–segment pair.
 */
struct sph_wall_shear {
  const double *mu_fluid, *mu_segment; /* μ = ν ρ per particle [Pa s] */
  double zmin;                         /* the floor of z, Δr/2 [m] */
};
static inline void sph_wall_shear_flux(const struct sph_system *s, const struct sph_nbrs *nb,
                                       const struct sph_wall_shear *sh, size_t a, size_t q,
                                       double out[3]) {
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID], *sg = &s->part[SPH_KIND_SEGMENT];
  const size_t j = nb->list[SPH_KIND_SEGMENT].index[q];
  const double n[3] = {sg->normal[0][j], sg->normal[1][j], sg->normal[2][j]};
  double dv[3];
  const double z = nb->dist_as[q];
  for (int c = 0; c < 3; c++) dv[c] = f->v[c][a] - sg->v[c][j];
  const double dn = dv[0] * n[0] + dv[1] * n[1] + dv[2] * n[2];
  const double coef = (sh->mu_segment[j] + sh->mu_fluid[a]) / (z > sh->zmin ? z : sh->zmin);
  for (int c = 0; c < 3; c++) out[c] = coef * (dv[c] - dn * n[c]);
}

/* Lap^γ_a(β, A) of sph_op_lap from the fluid part l_fluid, with the wall flux of shear (NULL:
 * none) computed per pair. */
void sph_op_lap_walls(const struct sph_op *op, const double *const beta[SPH_NKINDS],
                      const double *const A[SPH_NKINDS][3], const struct sph_wall_shear *shear,
                      size_t a, const double l_fluid[3], double out[3]);

#endif
