/* From a checked wall mesh and fluid regions to particles: vertex and segment particles for the
 * walls, fluid particles on a lattice of spacing Δr inside the walls. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geometry/geometry.h"
#include "sabre/common.h"
#include "sabre/sph.h"

void sph_system_add_walls(struct sph_system *s, const struct sph_mesh *m) {
  if (m->dim != s->dim) cmn_error("mesh of dimension %d for a %dD system", m->dim, s->dim);
  int dim = s->dim;
  size_t v0 = sph_system_append(s, SPH_KIND_VERTEX, m->nvert);
  size_t s0 = sph_system_append(s, SPH_KIND_SEGMENT, m->nelem);
  struct sph_parts *pv = &s->part[SPH_KIND_VERTEX], *ps = &s->part[SPH_KIND_SEGMENT];
  for (size_t i = 0; i < m->nvert; i++)
    for (int a = 0; a < 3; a++) pv->x[a][v0 + i] = m->vert[i][a];
  uint8_t *seen = cmn_calloc(m->nvert + 1, 1); /* bit 0: a wall element, bit 1: an open one */
  for (size_t e = 0; e < m->nelem; e++) {
    size_t j = s0 + e;
    double v[3][3];
    geom_element_vertices(m, e, v);
    for (int k = 1; k < dim; k++) { /* minimum image around the first vertex */
      double d[3];
      sph_domain_delta(&s->domain, v[0], v[k], d);
      for (int a = 0; a < 3; a++) v[k][a] = v[0][a] + d[a];
    }
    double meas = geom_element_measure(dim, v);
    for (int a = 0; a < 3; a++) {
      double c = 0;
      for (int k = 0; k < dim; k++) c += v[k][a] / dim;
      ps->x[a][j] = c;
      ps->normal[a][j] = m->normal[e][a];
    }
    ps->measure[j] = meas;
    ps->flags[j] = m->flags[e];
    for (int k = 0; k < dim; k++) {
      size_t iv = m->elem[e][k];
      ps->vertex[k][j] = v0 + iv;
      seen[iv] |= m->flags[e] & SPH_FLAG_OPEN ? 2u : 1u;
      for (int a = 0; a < 3; a++) pv->normal[a][v0 + iv] += meas * m->normal[e][a];
    }
  }
  for (size_t i = 0; i < m->nvert; i++) {
    size_t iv = v0 + i;
    double len =
        sqrt(pv->normal[0][iv] * pv->normal[0][iv] + pv->normal[1][iv] * pv->normal[1][iv] +
             pv->normal[2][iv] * pv->normal[2][iv]);
    for (int a = 0; a < 3; a++) pv->normal[a][iv] = len > 0 ? pv->normal[a][iv] / len : 0.0;
    if (seen[i] & 2u) pv->flags[iv] |= SPH_FLAG_OPEN;
    if (seen[i] == 3u) pv->flags[iv] |= SPH_FLAG_CORNER;
  }
  free(seen);
}

/* Point-in-polygon by crossings of a ray towards +x. */
static int polygon_contains(size_t n, const double (*p)[2], const double *x) {
  int in = 0;
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    if ((p[i][1] > x[1]) != (p[j][1] > x[1]) &&
        x[0] < p[j][0] + (x[1] - p[j][1]) * (p[i][0] - p[j][0]) / (p[i][1] - p[j][1]))
      in = !in;
  }
  return in;
}

/* tol: lattice points on the region's faces (first_row = 1 puts the last one on hi) belong to
 * it whatever the rounding. */
static int region_contains(const struct sph_region *r, int dim, const double *x, double tol) {
  for (int a = 0; a < dim; a++)
    if (x[a] < r->lo[a] - tol || x[a] > r->hi[a] + tol) return 0;
  return r->type == 0 || polygon_contains(r->npts, (const double(*)[2])r->pts, x);
}

static double corner_angle(const double v[3][3], int k) {
  const double *p = v[k], *a = v[(k + 1) % 3], *b = v[(k + 2) % 3];
  double u[3], w[3], c[3];
  for (int i = 0; i < 3; i++) {
    u[i] = a[i] - p[i];
    w[i] = b[i] - p[i];
  }
  geom_cross(u, w, c);
  return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
               u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
}

/*
 * Side of the walls of point x from its wall neighbours: +1 fluid side, 0 other side; distance to
 * the nearest element in *dist. The sign uses the pseudo-normal of the nearest point's feature
 * (sum of the normals of the elements that contain that point, angle-weighted at a 3D vertex),
 * which is correct at edges and vertices of a closed mesh (Bærentzen & Aanæs 2005).
 */
static int wall_side(const struct sph_system *t, const sph_nbr_t *cand, size_t ncand,
                     const double *x, double *dist) {
  int dim = t->dim;
  double dmin = INFINITY, qmin[3] = {0, 0, 0};
  for (size_t k = 0; k < ncand; k++) {
    double v[3][3], q[3];
    sph_segment_vertices(t, cand[k], x, v);
    double d = sph_element_distance(dim, v, x, q);
    if (d < dmin) {
      dmin = d;
      memcpy(qmin, q, sizeof q);
    }
  }
  *dist = dmin;
  double tol = 1e-9 * dmin + 1e-12 * t->dr, n[3] = {0, 0, 0};
  const struct sph_parts *ps = &t->part[SPH_KIND_SEGMENT];
  for (size_t k = 0; k < ncand; k++) {
    size_t j = cand[k];
    double v[3][3], q[3];
    sph_segment_vertices(t, j, x, v);
    /* Only the elements that share the nearest point: at equal distances from several walls
     * (a point midway across a channel) their normals would cancel. */
    if (sph_element_distance(dim, v, x, q) > dmin + tol ||
        fabs(q[0] - qmin[0]) + fabs(q[1] - qmin[1]) + fabs(q[2] - qmin[2]) > tol)
      continue;
    double w = 1;
    if (dim == 3)
      for (int c = 0; c < 3; c++)
        if (fabs(q[0] - v[c][0]) + fabs(q[1] - v[c][1]) + fabs(q[2] - v[c][2]) <= tol)
          w = corner_angle(v, c);
    for (int a = 0; a < 3; a++) n[a] += w * ps->normal[a][j];
  }
  double side = 0;
  for (int a = 0; a < 3; a++) side += (x[a] - qmin[a]) * n[a];
  return side > 0;
}

/* Breadth-first along lattice edges (n[0] x n[1] x n[2] points): unknown sides (−1) take the side
 * of the queued points' neighbours. */
static void propagate(signed char *side, const long *n, int dim, size_t *queue, size_t tail) {
  for (size_t head = 0; head < tail;) {
    size_t i = queue[head++], stride = 1;
    for (int a = 0; a < dim; a++) {
      long c = (long)(i / stride % (size_t)n[a]);
      if (c > 0 && side[i - stride] < 0) {
        side[i - stride] = side[i];
        queue[tail++] = i - stride;
      }
      if (c + 1 < n[a] && side[i + stride] < 0) {
        side[i + stride] = side[i];
        queue[tail++] = i + stride;
      }
      stride *= (size_t)n[a];
    }
  }
}

int sph_system_wall_side(const struct sph_system *s, const double *x, double *dist) {
  size_t nseg = s->part[SPH_KIND_SEGMENT].n;
  *dist = INFINITY;
  if (nseg == 0) return -1;
  sph_nbr_t *all = cmn_malloc(nseg * sizeof *all);
  for (size_t j = 0; j < nseg; j++) all[j] = (sph_nbr_t)j;
  int side = wall_side(s, all, nseg, x, dist);
  free(all);
  return side;
}

size_t sph_system_fill(struct sph_system *s, const struct sph_geometry *g) {
  int dim = s->dim;
  double dr = g->dr;
  /* Search reach: beyond it a lattice step (dr) cannot cross a wall, so far points can take the
   * side of their lattice neighbours. */
  double reach = 2 * dr + g->min_wall_distance;
  size_t added = 0;
  for (int r = 0; r < g->nregions; r++) {
    const struct sph_region *reg = &g->regions[r];
    long n[3] = {1, 1, 1};
    size_t total = 1;
    for (int a = 0; a < dim; a++) {
      double cells = (reg->hi[a] - reg->lo[a]) / dr;
      n[a] = (long)floor(cells + 1e-9);
      if (n[a] < 1) n[a] = 1;
      if (s->domain.periodic[a] &&
          fabs(reg->hi[a] - reg->lo[a] - (s->domain.hi[a] - s->domain.lo[a])) < 1e-9 * dr &&
          fabs(cells - (double)n[a]) > 1e-6)
        cmn_warning(
            "fluid region %d spans the periodic direction %c but its length is not a "
            "multiple of dr: the spacing across the periodic boundary differs",
            r, "xyz"[a]);
      total *= (size_t)n[a];
      if (total > (size_t)1 << 34)
        cmn_input_error("fluid region %d: more than 2^34 lattice points at dr = %g", r, dr);
    }
    /* Candidates in a scratch system that shares the walls of s. */
    struct sph_system t = *s;
    sph_parts_init(&t.part[SPH_KIND_FLUID], SPH_KIND_FLUID);
    struct sph_parts *pc = &t.part[SPH_KIND_FLUID];
    sph_parts_append(pc, total);
    for (size_t i = 0; i < total; i++) {
      size_t rest = i;
      for (int a = 0; a < dim; a++) {
        pc->x[a][i] = reg->lo[a] + ((double)(rest % (size_t)n[a]) + g->first_row) * dr;
        rest /= (size_t)n[a];
      }
    }
    struct sph_cells cells = {0};
    struct sph_nlist nl = {0};
    sph_cells_build(&cells, &t, reach);
    sph_nlist_build(&nl, &cells, &t, SPH_KIND_FLUID, SPH_KIND_SEGMENT, reach);
    signed char *side = cmn_malloc(total);
    double *dist = cmn_malloc(total * sizeof *dist);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 256)
#endif
    for (size_t i = 0; i < total; i++) {
      double x[3] = {pc->x[0][i], pc->x[1][i], pc->x[2][i]};
      dist[i] = INFINITY;
      side[i] = nl.offset[i] == nl.offset[i + 1]
                    ? -1
                    : (signed char)wall_side(&t, nl.index + nl.offset[i],
                                             nl.offset[i + 1] - nl.offset[i], x, &dist[i]);
    }
    /* Far points take the side of their lattice neighbours. A part of the lattice with no point
     * near a wall (a region far inside, or wrongly far outside, the walls) gets the side of one of
     * its points from the nearest of all the walls. */
    size_t *queue = cmn_malloc(total * sizeof *queue), tail = 0;
    for (size_t i = 0; i < total; i++)
      if (side[i] >= 0) queue[tail++] = i;
    propagate(side, n, dim, queue, tail);
    size_t nseg = t.part[SPH_KIND_SEGMENT].n;
    sph_nbr_t *all = cmn_malloc((nseg + 1) * sizeof *all);
    for (size_t j = 0; j < nseg; j++) all[j] = (sph_nbr_t)j;
    for (size_t i = 0; i < total && nseg > 0; i++) {
      if (side[i] >= 0) continue;
      double x[3] = {pc->x[0][i], pc->x[1][i], pc->x[2][i]}, d;
      side[i] = (signed char)wall_side(&t, all, nseg, x, &d);
      queue[0] = i;
      propagate(side, n, dim, queue, 1);
    }
    free(all);
    free(queue);
    uint8_t *drop = cmn_malloc(total);
    double dmin = g->min_wall_distance - 1e-9 * dr;
    for (size_t i = 0; i < total; i++) {
      double x[3] = {pc->x[0][i], pc->x[1][i], pc->x[2][i]};
      int keep = side[i] != 0 && !(dist[i] < dmin) && region_contains(reg, dim, x, 1e-9 * dr);
      for (int q = 0; q < r && keep; q++) keep = !region_contains(&g->regions[q], dim, x, 0.0);
      drop[i] = !keep;
    }
    sph_parts_remove(pc, drop);
    size_t first = sph_system_append(s, SPH_KIND_FLUID, pc->n);
    struct sph_parts *pf = &s->part[SPH_KIND_FLUID];
    for (size_t i = 0; i < pc->n; i++)
      for (int a = 0; a < 3; a++) pf->x[a][first + i] = pc->x[a][i];
    added += pc->n;
    free(drop);
    free(side);
    free(dist);
    sph_nlist_free(&nl);
    sph_cells_free(&cells);
    sph_parts_free(pc);
  }
  return added;
}

void sph_system_from_geometry(struct sph_system *s, const struct sph_geometry *g) {
  sph_system_init(s, g->dim);
  s->dr = g->dr;
  s->h = g->h_over_dr * g->dr;
  s->domain = g->domain;
  sph_system_add_walls(s, &g->walls);
  sph_system_fill(s, g);
}
