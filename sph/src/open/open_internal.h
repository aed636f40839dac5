/* Helpers shared by the open-boundary sources (sph/src/open/). */
#ifndef SABRE_SPH_OPEN_INTERNAL_H
#define SABRE_SPH_OPEN_INTERNAL_H

#include "sabre/sph_open.h"

/** Centre-line speed U_max of a Poiseuille generator [m/s]: d->u_max when given, else from the
 *  volume flux (closed forms for plates and circles, the series of the rectangle). */
double sph_open_duct_umax(const struct sph_open_poiseuille *d);

#endif
