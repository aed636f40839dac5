/*
 * Internal interface of the wall integrals (sph/src/walls/): one implementation per dimension,
 * dispatched once per element by gamma.c. Derivations and equation numbers: docs/sph-gamma.md.
 */
#ifndef SPH_WALLS_GAMMA_IMPL_H
#define SPH_WALLS_GAMMA_IMPL_H

#include "sabre/sph_walls.h"

/*
 * Element term and ∇γ_as at a (see sph_gamma_element). If a lies on the element (within
 * SPH_GAMMA_PLANE_TOL·h), the term is the limit for a + ε m, ε → 0+: m is a unit direction with
 * m·n_s ≠ 0, or NULL for m = n_s.
 */
void sph_gamma1d_element(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, const double *m, double *term,
                         double grad[3]);
void sph_gamma2d_element(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, const double *m, double *term,
                         double grad[3]);
void sph_gamma3d_element(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, const double *m, double *term,
                         double grad[3]);

/*
 * Whether a lies on the closed element: within SPH_GAMMA_PLANE_TOL·h of its plane and within tol of
 * the element in that plane. If so, returns 1 and, if m is not NULL, adds weight·ν to m, ν the
 * element's unit normal and weight the angle of the element at a (angle-weighted pseudo-normal of
 * Bærentzen & Aanæs); else returns 0.
 */
int sph_gamma1d_incident(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, double tol, double m[3]);
int sph_gamma2d_incident(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, double tol, double m[3]);
int sph_gamma3d_incident(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, double tol, double m[3]);

/* 0 if the element is non-degenerate with a unit normal perpendicular to it (1e-6), else -1. */
int sph_gamma1d_check(const struct sph_wall_element *e);
int sph_gamma2d_check(const struct sph_wall_element *e);
int sph_gamma3d_check(const struct sph_wall_element *e);

#endif
