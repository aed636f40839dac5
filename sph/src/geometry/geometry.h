/* Internal helpers shared by the geometry sources (sph/src/geometry/). */
#ifndef SABRE_SPH_GEOMETRY_H
#define SABRE_SPH_GEOMETRY_H

#include "sabre/sph.h"

/** 3D refinement splits edges longer than GEOM_EDGE_MAX · Δr (a square of side Δr cut in two
 *  triangles has a diagonal of √2 Δr, which must stay). */
#define GEOM_EDGE_MAX 1.5

static inline void geom_cross(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/** Format a message into msg (for the functions that report bad input to their caller) and
 *  return -1. */
int geom_fail(char *msg, size_t msglen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/** Unit normal of an element from its vertex order (1D: normal1d). Zero for degenerate ones. */
void geom_element_normal(int dim, const double v[3][3], double normal1d, double *n);
/** Length (2D) or area (3D) of an element; 1 in 1D. */
double geom_element_measure(int dim, const double v[3][3]);
/** Coordinates of the vertices of element e (unused rows zero). */
void geom_element_vertices(const struct sph_mesh *m, size_t e, double v[3][3]);
/** Move vertices on the hi side of periodic directions to the lo side and merge them with their
 *  images (within tol), so that a wall crossing a periodic boundary is one closed wall. */
void geom_mesh_identify_periodic(struct sph_mesh *m, const struct sph_domain *dom, double tol);

#endif
