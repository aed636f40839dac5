/* Built-in wall generators: 2D polygons and polylines, and axis-aligned boxes in any dimension
 * (the 1D interval is the 1D box; channels are boxes without their x faces, and in 3D periodic in
 * y also without their y faces). Elements come out coarse in 2D (one per polygon edge, split later
 * by sph_mesh_refine) and at spacing ≈ Δr on 3D box faces. */
#include <math.h>

#include "geometry/geometry.h"
#include "sabre/common.h"
#include "sabre/sph.h"

void sph_mesh_polygon(struct sph_mesh *m, size_t n, const double (*pts)[2], int closed,
                      int fluid_inside, const uint8_t *open_edges, int source) {
  /* Walking the wall, the fluid must be on the left: counter-clockwise around fluid inside. */
  int reverse = !fluid_inside;
  if (closed) {
    double area = 0;
    for (size_t i = 0; i < n; i++) {
      const double *p = pts[i], *q = pts[(i + 1) % n];
      area += p[0] * q[1] - q[0] * p[1];
    }
    reverse = (area > 0) != (fluid_inside != 0);
  }
  size_t v0 = m->nvert;
  for (size_t i = 0; i < n; i++) sph_mesh_add_vertex(m, (double[]){pts[i][0], pts[i][1], 0});
  size_t nedges = closed ? n : n - 1;
  for (size_t i = 0; i < nedges; i++) {
    size_t a = v0 + i, b = v0 + (i + 1) % n;
    uint8_t flags = open_edges && open_edges[i] ? SPH_FLAG_OPEN : 0;
    size_t v[3] = {reverse ? b : a, reverse ? a : b, 0};
    sph_mesh_add_element(m, v, 0, flags, source, (long)i + 1);
  }
}

/* Grid coordinate i of n along axis a: exactly lo at 0 and hi at n, and the same value for every
 * face that shares the edge, so the faces' vertices merge exactly. */
static double grid(const double *lo, const double *hi, const long *n, int a, long i) {
  return i == n[a] ? hi[a] : lo[a] + (hi[a] - lo[a]) * (double)i / (double)n[a];
}

void sph_mesh_box(struct sph_mesh *m, const double *lo, const double *hi, double dr, unsigned open,
                  unsigned skip, int source) {
  int dim = m->dim;
  if (dim == 1) {
    size_t v0 = m->nvert;
    sph_mesh_add_vertex(m, (double[]){lo[0], 0, 0});
    sph_mesh_add_vertex(m, (double[]){hi[0], 0, 0});
    for (int s = 0; s < 2; s++)
      if (!(skip >> s & 1u))
        sph_mesh_add_element(m, (size_t[]){v0 + (size_t)s, 0, 0}, s ? -1.0 : 1.0,
                             open >> s & 1u ? SPH_FLAG_OPEN : 0, source, s + 1);
    return;
  }
  if (dim == 2) {
    /* Counter-clockwise: bottom (y lo, bit 2), right (x hi, bit 1), top (y hi, bit 3), left
     * (x lo, bit 0). */
    size_t v0 = m->nvert;
    const double c[4][2] = {{lo[0], lo[1]}, {hi[0], lo[1]}, {hi[0], hi[1]}, {lo[0], hi[1]}};
    const unsigned face[4] = {2, 1, 3, 0};
    for (int i = 0; i < 4; i++) sph_mesh_add_vertex(m, (double[]){c[i][0], c[i][1], 0});
    for (int i = 0; i < 4; i++) {
      if (skip >> face[i] & 1u) continue;
      size_t v[3] = {v0 + (size_t)i, v0 + (size_t)(i + 1) % 4, 0};
      sph_mesh_add_element(m, v, 0, open >> face[i] & 1u ? SPH_FLAG_OPEN : 0, source, i + 1);
    }
    return;
  }
  long n[3];
  for (int a = 0; a < 3; a++) {
    n[a] = lround((hi[a] - lo[a]) / dr);
    if (n[a] < 1) n[a] = 1;
  }
  long tri = 0;
  for (int a = 0; a < 3; a++) {
    int b = (a + 1) % 3, c = (a + 2) % 3; /* e_b × e_c = e_a */
    for (int side = 0; side < 2; side++) {
      unsigned bit = 2u * (unsigned)a + (unsigned)side;
      if (skip >> bit & 1u) continue;
      uint8_t flags = open >> bit & 1u ? SPH_FLAG_OPEN : 0;
      size_t base = m->nvert;
      for (long j = 0; j <= n[c]; j++)
        for (long i = 0; i <= n[b]; i++) {
          double x[3];
          x[a] = side ? hi[a] : lo[a];
          x[b] = grid(lo, hi, n, b, i);
          x[c] = grid(lo, hi, n, c, j);
          sph_mesh_add_vertex(m, x);
        }
      for (long j = 0; j < n[c]; j++)
        for (long i = 0; i < n[b]; i++) {
          size_t p00 = base + (size_t)(j * (n[b] + 1) + i), p10 = p00 + 1;
          size_t p01 = p00 + (size_t)(n[b] + 1), p11 = p01 + 1;
          /* (b, c) order gives the normal +e_a: into the box on the lo face only. */
          if (side == 0) {
            sph_mesh_add_element(m, (size_t[]){p00, p10, p11}, 0, flags, source, ++tri);
            sph_mesh_add_element(m, (size_t[]){p00, p11, p01}, 0, flags, source, ++tri);
          } else {
            sph_mesh_add_element(m, (size_t[]){p00, p11, p10}, 0, flags, source, ++tri);
            sph_mesh_add_element(m, (size_t[]){p00, p01, p11}, 0, flags, source, ++tri);
          }
        }
    }
  }
  sph_mesh_merge_vertices(m, 0.0);
}
