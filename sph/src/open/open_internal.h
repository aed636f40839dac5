/* Helpers shared by the open-boundary sources (sph/src/open/). */
#ifndef SABRE_SPH_OPEN_INTERNAL_H
#define SABRE_SPH_OPEN_INTERNAL_H

#include "sabre/sph_open.h"

/** Centre-line speed U_max of a Poiseuille generator [m/s]: d->u_max when given, else from the
 *  volume flux (closed forms for plates and circles, the series of the rectangle). */
double sph_open_duct_umax(const struct sph_open_poiseuille *d);

/** Add q [kg or kg/s] of open segment j to its vertices: equal shares among those that are not
 *  corners (SPH_FLAG_CORNER: shared with a wall segment), among all of them when every one is a
 *  corner (docs/sph-solver.md §10). acc is indexed by vertex. */
void sph_open_share(const struct sph_system *s, size_t j, double q, double *acc);

#endif
