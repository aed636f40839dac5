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

/* The axes of a triangle's frame, which do not depend on the point: the unit normal nu oriented
 * like the element's normal, e1 along x1 − x0, e2 = nu × e1, sigma = +1 if (x0, x1, x2) turn
 * counter-clockwise about nu, else −1. */
struct sph_tri_axes {
  double nu[3], e1[3], e2[3], sigma;
  double x0[3];     /* the first vertex [m] */
  double normal[3]; /* the element's unit normal (as given) */
  double u[3][2];   /* the vertices in the frame (e1, e2), relative to x0 [m] */
  double dir[3][2]; /* unit direction of edge j → j+1 in the frame */
  double c[2];      /* the centroid in the frame, relative to x0 [m] */
  double rad;       /* largest distance from the centroid to a vertex [m] */
};
void sph_gamma3d_axes(const struct sph_wall_element *e, struct sph_tri_axes *ax);

/* The edge integrals of one triangle at one point, shared with the coplanar triangle across each
 * edge (the interior edges of a meshed face are computed once per point instead of twice). Edge
 * i runs from x_i to x_{i+1}; its value is the pair (∫ w, γ term) of the sub-triangle (foot
 * point, x_i, x_{i+1}) in units of h, before the triangle's orientation sign, and changes sign
 * with the edge's direction. */
struct sph_edge_share {
  int have;           /**< in: bit i set if value[i] is given (the neighbour's, signed for this
                           triangle's direction of edge i) */
  double value[3][2]; /**< in: the given values; out: edge i's values when bit i of got is set */
  int got;            /**< out: bits of the edges whose values are in value[] (0: none, the
                           triangle beyond the support or treated as a whole) */
};

/*
 * One fluid–triangle pair of the solver in one pass (3D): the term and ∇γ_as as
 * sph_gamma3d_element with m = NULL (zero beyond the support), the distance from a to the closed
 * triangle [m] and the signed distance from a to its plane [m] (> 0 on the side of the normal), all
 * from one frame of the triangle at a. Agrees with sph_gamma3d_element and sph_element_distance to
 * round-off (tests/sph/test_gamma.c). ax: sph_gamma3d_axes of e (computed once per element); sh:
 * NULL, or the edge values shared with the coplanar neighbours (struct sph_edge_share).
 */
void sph_gamma3d_pair(const struct sph_kernel *k, const double *a, const struct sph_wall_element *e,
                      const struct sph_tri_axes *ax, struct sph_edge_share *sh, double *term,
                      double grad[3], double *dist, double *off);

/*
 * The same from the offset d = a − x0 of the point from the triangle's first vertex (ax->x0; the
 * minimum image in a periodic domain), without the element's vertices: the frame at a is the
 * precomputed one shifted by d (three dot products), the edges' directions and the bounding circle
 * are the element's. Returns 0, or 1 with nothing computed when a lies within
 * SPH_GAMMA_PLANE_TOL·h of the triangle's plane, where the one-sided limit needs the vertices: the
 * caller then uses sph_gamma3d_pair. It gives no distance to the triangle: the support test needs
 * only |off| (a lower bound of it) and the bounding circle, which cull inside; where the caller
 * needs more, sph_gamma3d_offset_bound gives a sharper bound (plane and bounding circle) and
 * sph_gamma3d_offset_distance the distance. term,
 * ∇γ_as and off agree with sph_gamma3d_pair to round-off and are zero beyond the support
 * (tests/sph/test_gamma.c).
 */
int sph_gamma3d_pair_offset(const struct sph_kernel *k, const double d[3],
                            const struct sph_tri_axes *ax, struct sph_edge_share *sh, double *term,
                            double grad[3], double *off);

/* A lower bound [m] of the distance from the point at offset d from ax->x0 to the closed triangle,
 * from the distance to its plane and to its bounding circle in the plane (equal to the plane
 * distance where the point faces the triangle; at most round-off above the distance). */
double sph_gamma3d_offset_bound(const double d[3], const struct sph_tri_axes *ax);

/* The distance [m] from the point at offset d from ax->x0 to the closed triangle: the value
 * sph_gamma3d_pair gives, to round-off. */
double sph_gamma3d_offset_distance(const double d[3], const struct sph_tri_axes *ax);

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
