/*
 * Geometric vertex volumes (docs/sph-solver.md §6): the volume of the wall layer, the fluid within
 * a distance t of the walls, that each vertex particle stands for. The layer is cut into the parts
 * nearest to each element (so that the slabs of two elements meeting at a concave edge or corner
 * are not counted twice), and each element's part goes to the element's vertex nearest to it (the
 * vertex's Voronoi cell within the element; on a Delaunay mesh of a plane these cells make up the
 * vertex's Voronoi cell). On a flat wall meshed at spacing Δr a vertex gets Δr^(d−1) t;
 * in a right-angled box with t = Δr/2 the vertices of an edge (3D) or a corner (2D) get half of
 * that and the corners of a box (3D) a quarter, up to the sampling error. This is what the
 * reference implementation's pre-processor computes for its vertex masses (a wall layer Δr/2
 * thick, the fluid's first row Δr from the wall).
 *
 * Each element is sampled at the centroids of a regular subdivision (about eight points per Δr
 * along the element); at each sample the depth up to which the element is the nearest one is
 * found by bisection, and the sample stands for its sub-element's measure times that depth.
 */
#include <math.h>
#include <stdlib.h>

#include "sabre/common.h"
#include "sabre/sph.h"
#include "sabre/sph_walls.h"

/* Number of sample points per Δr along an element (per direction). */
#define SAMPLES_PER_DR 8.0

struct element {
  double v[3][3]; /* vertices (minimum image next to the centroid) */
  double c[3];    /* centroid */
  double radius;  /* largest distance of a vertex from the centroid */
};

static double dist3(const struct sph_domain *dom, const double *a, const double *b) {
  double d[3];
  sph_domain_delta(dom, a, b, d);
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* Is x, at distance z from element j, nearer to another element? cand: the candidates of j. */
static int nearer_elsewhere(const struct sph_system *s, const size_t *cand, size_t ncand, size_t j,
                            const double *x, double z) {
  for (size_t q = 0; q < ncand; q++) {
    const size_t i = cand[q];
    if (i == j) continue;
    double v[3][3], foot[3];
    sph_segment_vertices(s, i, x, v);
    if (sph_element_distance(s->dim, (const double(*)[3])v, x, foot) < z * (1.0 - 1e-12)) return 1;
  }
  return 0;
}

int sph_walls_vertex_volumes(const struct sph_system *s, double thickness, double *volume) {
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT], *vx = &s->part[SPH_KIND_VERTEX];
  const int dim = s->dim;
  for (size_t i = 0; i < vx->n; i++) volume[i] = 0.0;
  if (!(thickness >= 0.0) || !(s->dr > 0.0)) return -1;
  if (thickness == 0.0 || sg->n == 0) return 0;
  const size_t n = sg->n;
  struct element *el = cmn_malloc(n * sizeof *el);
  for (size_t j = 0; j < n; j++) {
    const double c[3] = {sg->x[0][j], sg->x[1][j], sg->x[2][j]};
    sph_segment_vertices(s, j, c, el[j].v);
    el[j].radius = 0.0;
    for (int k = 0; k < 3; k++) el[j].c[k] = c[k];
    for (int k = 0; k < dim; k++)
      el[j].radius = fmax(el[j].radius, dist3(&s->domain, c, el[j].v[k]));
  }
  /* Candidates of element j: the elements that can be nearer than t to a point of j's layer. */
  size_t *off = cmn_malloc((n + 1) * sizeof *off), cap = 8 * n + 16, len = 0;
  size_t *cand = cmn_malloc(cap * sizeof *cand);
  for (size_t j = 0; j < n; j++) {
    off[j] = len;
    for (size_t i = 0; i < n; i++) {
      if (dist3(&s->domain, el[j].c, el[i].c) > el[j].radius + el[i].radius + 2.0 * thickness)
        continue;
      if (len == cap) cand = cmn_realloc(cand, (cap *= 2) * sizeof *cand);
      cand[len++] = i;
    }
  }
  off[n] = len;

  for (size_t j = 0; j < n; j++) {
    const double *nrm[3] = {sg->normal[0], sg->normal[1], sg->normal[2]};
    const double normal[3] = {nrm[0][j], nrm[1][j], nrm[2][j]};
    const double(*v)[3] = (const double(*)[3])el[j].v;
    /* Sub-elements: 1D one point; 2D m pieces; 3D m² sub-triangles (m per longest edge). */
    double diam = 0.0;
    for (int a = 0; a < dim; a++)
      for (int b = a + 1; b < dim; b++) diam = fmax(diam, dist3(&s->domain, v[a], v[b]));
    const int m = dim == 1 ? 1 : (int)fmax(1.0, ceil(SAMPLES_PER_DR * diam / s->dr - 1e-6));
    const int nsub = dim == 3 ? m * m : m;
    const double sub_measure = sg->measure[j] / nsub;
    for (int q = 0; q < nsub; q++) {
      double bary[3] = {1.0, 0.0, 0.0};
      if (dim == 2) {
        bary[1] = (q + 0.5) / m;
        bary[0] = 1.0 - bary[1];
      } else if (dim == 3) {
        /* Row r, position i: upright sub-triangles i < m − r, then the inverted ones. */
        int r = 0, rest = q, upright = 1;
        for (;; r++) {
          const int row = 2 * (m - r) - 1;
          if (rest < row) {
            upright = rest % 2 == 0;
            rest /= 2;
            break;
          }
          rest -= row;
        }
        bary[1] = (rest + (upright ? 1.0 : 2.0) / 3.0) / m;
        bary[2] = (r + (upright ? 1.0 : 2.0) / 3.0) / m;
        bary[0] = 1.0 - bary[1] - bary[2];
      }
      double foot[3] = {0.0, 0.0, 0.0};
      for (int a = 0; a < dim; a++)
        for (int k = 0; k < 3; k++) foot[k] += bary[a] * v[a][k];
      /* The distance to another element grows at most as fast as the depth z along the normal,
       * so element j is the nearest over a depth interval [0, z*]: bisection for z*. */
      const size_t *cj = cand + off[j], ncj = off[j + 1] - off[j];
      double kept = thickness;
      double x[3];
      for (int k = 0; k < 3; k++) x[k] = foot[k] + thickness * normal[k];
      if (nearer_elsewhere(s, cj, ncj, j, x, thickness)) {
        double lo = 0.0, hi = thickness;
        for (int it = 0; it < 40; it++) {
          const double z = 0.5 * (lo + hi);
          for (int k = 0; k < 3; k++) x[k] = foot[k] + z * normal[k];
          if (nearer_elsewhere(s, cj, ncj, j, x, z))
            hi = z;
          else
            lo = z;
        }
        kept = 0.5 * (lo + hi);
      }
      /* The element's vertex nearest to the foot point takes the sample (ties share it): the
       * vertex's Voronoi cell within the element. */
      double d2[3], dmin = INFINITY;
      for (int a = 0; a < dim; a++) {
        d2[a] = 0.0;
        for (int k = 0; k < 3; k++) d2[a] += (foot[k] - v[a][k]) * (foot[k] - v[a][k]);
        dmin = fmin(dmin, d2[a]);
      }
      int ntie = 0;
      for (int a = 0; a < dim; a++) ntie += d2[a] <= dmin * (1.0 + 1e-9);
      for (int a = 0; a < dim; a++)
        if (d2[a] <= dmin * (1.0 + 1e-9)) volume[sg->vertex[a][j]] += sub_measure * kept / ntie;
    }
  }
  free(cand);
  free(off);
  free(el);
  return 0;
}
