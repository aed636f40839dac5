/*
 * What the solver's sources share beyond the public sph_solver.h (solver.c defines it).
 */
#ifndef SPH_SOLVER_INTERNAL_H
#define SPH_SOLVER_INTERNAL_H

#include <stddef.h>

#include "sabre/sph_solver.h"

/* Σ_{b∈F∪V} m_b w_ab of fluid particle a at the current positions over its neighbour lists (which
 * must be valid there), with the arithmetic of the time-summation continuity (fluid part first,
 * the vertex part added on), so that its value has the continuity's bits [kg/m^dim]. */
double sph_solver_kernel_sum(const struct sph_solver *sv, size_t a);

#endif
