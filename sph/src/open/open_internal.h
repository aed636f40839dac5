/* Helpers shared by the open-boundary sources (sph/src/open/). */
#ifndef SABRE_SPH_OPEN_INTERNAL_H
#define SABRE_SPH_OPEN_INTERNAL_H

#include "sabre/sph_open.h"

/** Centre-line speed U_max of a Poiseuille generator [m/s]: d->u_max when given, else from the
 *  volume flux (closed forms for plates and circles, the series of the rectangle). */
double sph_open_duct_umax(const struct sph_open_poiseuille *d);

/** Add the mass q [kg] of a particle that left at x through open segment j to its vertices: in
 *  proportion to the barycentric coordinates of x's foot point on the segment (all of it to a
 *  vertex when x crosses there), a corner's weight (SPH_FLAG_CORNER: shared with a wall segment)
 *  going to the other vertices in proportion (docs/sph-solver.md §10). acc is indexed by vertex. */
void sph_open_share(const struct sph_system *s, size_t j, const double x[3], double q, double *acc);

/** Add the mass flux q [kg/s] through open segment j to the rates of its vertices, J(15): q/d to
 *  each vertex that is not a corner; a corner's share is the flux through the part of the
 *  segment next to the wall, whose fluid the wall's vertex layer stands for, and goes to no
 *  vertex (nothing of a segment whose vertices are all corners). A dry vertex's share (wet
 *  fraction 0 in op: above the free surface) goes to the segment's wet vertices that are not
 *  corners, so that the fluid enters below the surface; with none, nothing. Returns the flux
 *  given to the vertices, the segment's share of the boundary's mass flux
 *  (docs/sph-solver.md §10). */
double sph_open_share_flux(const struct sph_system *s, const struct sph_open *op, size_t j,
                           double q, double *acc);

/** sum += x with Kahan's compensation *c (the low-order bits that sum has lost; start it at 0):
 *  the boundaries' mass ledgers add a small mass per step to a large total over up to 10⁶ steps,
 *  where the plain sum drifts by hundreds of units in the last place, ~10⁻¹³ of the total, against
 *  the 10⁻¹² of the cases' mass balance (tests/sph/test_open_mass.c, test_ledger_sum). */
static inline void sph_open_kahan_add(double *sum, double *c, double x) {
  const double y = x - *c, t = *sum + y;
  *c = (t - *sum) - y;
  *sum = t;
}

#endif
