/*
 * Neighbourhoods of the fluid particles and the wall integrals per fluid–segment pair:
 * γ_a = 1 − Σ_s term_s, ∇γ_as and ∇γ_a, J(2)–J(4), through sabre/sph_walls.h (closed form).
 * The lists are built with radius 2h + skin so that one build serves while no particle has moved
 * more than skin/2 since (several steps; the solver decides when to rebuild), the pairs at both
 * ends of the time-summation continuity included (M 84 / J 10–11). Rows are sorted by neighbour
 * index (sph_nlist_build), and every loop over a row leaves out the pairs beyond the support, so
 * the results do not depend on the radius or the time of the build.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "sabre/common.h"
#include "sabre/sph_solver.h"
#include "walls/gamma_impl.h"

static void reserve_pairs(struct sph_nbrs *nb) {
  size_t n = nb->list[SPH_KIND_SEGMENT].n;
  size_t np = n ? nb->list[SPH_KIND_SEGMENT].offset[n] : 0;
  if (np <= nb->cap_pairs && nb->dist_as) return;
  size_t cap = np + np / 8 + 16;
  for (int c = 0; c < 3; c++)
    nb->grad_gamma_as[c] = cmn_realloc(nb->grad_gamma_as[c], cap * sizeof(double));
  nb->dist_as = cmn_realloc(nb->dist_as, cap * sizeof(double));
  nb->term_as = cmn_realloc(nb->term_as, cap * sizeof(double));
  nb->cap_pairs = cap;
}

/* A list with no neighbours at all (no particle of that kind): built here, which also keeps
 * sph_nlist_build() from copying out of an empty buffer (memcpy from NULL, flagged by UBSan). */
static int empty_list(struct sph_nlist *nl, const struct sph_system *s, enum sph_kind query,
                      enum sph_kind other) {
  if (s->part[other].n != 0 && s->part[query].n != 0) return 0;
  size_t n = s->part[query].n;
  nl->query = query;
  nl->other = other;
  nl->n = n;
  nl->offset = cmn_realloc(nl->offset, (n + 1) * sizeof *nl->offset);
  memset(nl->offset, 0, (n + 1) * sizeof *nl->offset);
  return 1;
}

/* The coplanar triangle across each edge of each triangle (3D), so that sph_nbrs_gamma computes
 * the edge integrals of a meshed face once per particle (struct sph_edge_share). */
struct sph_edge_link {
  long seg;    /* the neighbour across edge i of segment j, −1 if none (or not coplanar) */
  int edge;    /* its index of that edge */
  double sign; /* +1 if it runs the edge in the same direction, −1 if opposite */
};

struct edge_key {
  size_t lo, hi, id; /* the edge's vertex indices (lo < hi) and 3 × segment + edge */
};

static int edge_key_cmp(const void *x, const void *y) {
  const struct edge_key *a = x, *b = y;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return a->id < b->id ? -1 : (a->id > b->id);
}

/* Two triangles sharing an edge lie in one plane when their unit normals (oriented like the
 * elements') agree to 1e-13: the planes then differ by less than 1e-13 × the distance from the
 * edge, round-off for the integrals. */
static int coplanar(const struct sph_tri_axes *u, const struct sph_tri_axes *v) {
  const double c0 = u->nu[1] * v->nu[2] - u->nu[2] * v->nu[1];
  const double c1 = u->nu[2] * v->nu[0] - u->nu[0] * v->nu[2];
  const double c2 = u->nu[0] * v->nu[1] - u->nu[1] * v->nu[0];
  const double dot = u->nu[0] * v->nu[0] + u->nu[1] * v->nu[1] + u->nu[2] * v->nu[2];
  return dot > 0.0 && c0 * c0 + c1 * c1 + c2 * c2 < 1e-26;
}

static void link_edges(struct sph_nbrs *nb, const struct sph_system *s) {
  const struct sph_parts *seg = &s->part[SPH_KIND_SEGMENT];
  const size_t ne = 3 * seg->n;
  if (ne > nb->cap_links) {
    nb->cap_links = ne;
    nb->edge_link = cmn_realloc(nb->edge_link, ne * sizeof *nb->edge_link);
  }
  for (size_t i = 0; i < ne; i++) nb->edge_link[i] = (struct sph_edge_link){-1, 0, 0.0};
  int periodic = 0; /* across a periodic boundary a vertex stands for several images: no links */
  for (int k = 0; k < s->domain.dim; k++) periodic |= s->domain.periodic[k];
  if (periodic) return;
  struct edge_key *key = cmn_malloc(ne * sizeof *key);
  for (size_t j = 0; j < seg->n; j++)
    for (int i = 0; i < 3; i++) {
      const size_t u = seg->vertex[i][j], v = seg->vertex[(i + 1) % 3][j];
      key[3 * j + i] = (struct edge_key){u < v ? u : v, u < v ? v : u, 3 * j + (size_t)i};
    }
  qsort(key, ne, sizeof *key, edge_key_cmp);
  for (size_t r = 0; r < ne;) {
    size_t end = r + 1;
    while (end < ne && key[end].lo == key[r].lo && key[end].hi == key[r].hi) end++;
    if (end - r == 2) { /* an edge of exactly two triangles */
      const size_t x = key[r].id, y = key[r + 1].id, jx = x / 3, jy = y / 3;
      const int ix = (int)(x % 3), iy = (int)(y % 3);
      if (jx != jy && coplanar(&nb->tri_axes[jx], &nb->tri_axes[jy])) {
        const double sign = seg->vertex[ix][jx] == seg->vertex[iy][jy] ? 1.0 : -1.0;
        nb->edge_link[x] = (struct sph_edge_link){(long)jy, iy, sign};
        nb->edge_link[y] = (struct sph_edge_link){(long)jx, ix, sign};
      }
    }
    r = end;
  }
  free(key);
}

static void build(struct sph_nbrs *nb, const struct sph_system *s, double skin, int naive) {
  nb->radius = 2.0 * s->h + skin;
  if (!naive) sph_cells_build(&nb->cells, s, nb->radius);
  for (int k = 0; k < SPH_NKINDS; k++) {
    if (empty_list(&nb->list[k], s, SPH_KIND_FLUID, (enum sph_kind)k)) continue;
    if (naive)
      sph_nlist_build_naive(&nb->list[k], s, SPH_KIND_FLUID, (enum sph_kind)k, nb->radius);
    else
      sph_nlist_build(&nb->list[k], &nb->cells, s, SPH_KIND_FLUID, (enum sph_kind)k, nb->radius);
  }
  if (empty_list(&nb->vf, s, SPH_KIND_VERTEX, SPH_KIND_FLUID))
    ;
  else if (naive)
    sph_nlist_build_naive(&nb->vf, s, SPH_KIND_VERTEX, SPH_KIND_FLUID, nb->radius);
  else
    sph_nlist_build(&nb->vf, &nb->cells, s, SPH_KIND_VERTEX, SPH_KIND_FLUID, nb->radius);
  reserve_pairs(nb);
  /* 3D: the triangles' frame axes, once per build (the walls do not move during a run) */
  const struct sph_parts *seg = &s->part[SPH_KIND_SEGMENT];
  if (s->dim == 3 && seg->n > 0) {
    if (seg->n > nb->cap_axes) {
      nb->cap_axes = seg->n;
      nb->tri_axes = cmn_realloc(nb->tri_axes, seg->n * sizeof *nb->tri_axes);
    }
    const struct sph_parts *vx = &s->part[SPH_KIND_VERTEX];
    for (size_t j = 0; j < seg->n; j++) {
      const size_t iv = seg->vertex[0][j];
      const double near[3] = {vx->x[0][iv], vx->x[1][iv], vx->x[2][iv]};
      struct sph_wall_element e;
      sph_segment_vertices(s, j, near, e.x);
      for (int c = 0; c < 3; c++) e.normal[c] = seg->normal[c][j];
      sph_gamma3d_axes(&e, &nb->tri_axes[j]);
    }
    link_edges(nb, s);
  }
}

void sph_nbrs_build(struct sph_nbrs *nb, const struct sph_system *s, double skin) {
  build(nb, s, skin, 0);
}

void sph_nbrs_build_naive(struct sph_nbrs *nb, const struct sph_system *s, double skin) {
  build(nb, s, skin, 1);
}

/* Triangle j's precomputed frame (3D) and the offset d of fluid particle a from its first vertex
 * (minimum image). */
static const struct sph_tri_axes *pair_axes(const struct sph_nbrs *nb, const struct sph_system *s,
                                            size_t a, size_t j, double d[3]) {
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const double xa[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
  sph_domain_delta(&s->domain, nb->tri_axes[j].x0, xa, d);
  return &nb->tri_axes[j];
}

/* Wall data of pair p (fluid a, segment j): γ term, ∇γ_as, distance to the element and to its
 * plane (signed, > 0 on the fluid side). Returns 1 if *dist is the distance, 0 if it is the plane
 * distance |off|, a lower bound of it (3D off the triangle's plane: settle_distances measures
 * where needed). */
static int pair_wall(const struct sph_nbrs *nb, const struct sph_system *s,
                     const struct sph_kernel *k, size_t a, size_t j, struct sph_edge_share *sh,
                     double *term, double gs[3], double *dist, double *off) {
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID], *seg = &s->part[SPH_KIND_SEGMENT];
  const double xa[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
  if (s->dim == 3) { /* the triangle's precomputed frame, shifted to a (the hot path of 3D runs) */
    double d[3];
    const struct sph_tri_axes *ax = pair_axes(nb, s, a, j, d);
    if (sph_gamma3d_pair_offset(k, d, ax, sh, term, gs, off) == 0) {
      *dist = fabs(*off);
      return 0;
    }
  }
  struct sph_wall_element e;
  sph_segment_vertices(s, j, xa, e.x);
  for (int c = 0; c < 3; c++) e.normal[c] = seg->normal[c][j];
  if (s->dim == 3) { /* a on the triangle's plane: the frame from the vertices */
    sph_gamma3d_pair(k, xa, &e, &nb->tri_axes[j], sh, term, gs, dist, off);
    return 1;
  }
  double q[3];
  *dist = sph_element_distance(s->dim, (const double(*)[3])e.x, xa, q);
  *off = 0.0;
  for (int c = 0; c < 3; c++) *off += (xa[c] - q[c]) * e.normal[c];
  *term = 0.0;
  gs[0] = gs[1] = gs[2] = 0.0;
  if (*dist < sph_kernel_support(k)) sph_gamma_element(k, xa, &e, term, gs);
  return 1;
}

/* The side test (sum_row) reads the distances of the nearest elements within the support only.
 * Where pair_wall gave the plane distance as a lower bound (exact[i] = 0), the distance is
 * computed only for the elements that may be among the nearest: an element of zero term and
 * ∇γ_as is beyond the support; the one of largest ∇γ_as is measured first; any other is measured
 * when its plane distance, then its bounding-circle bound, are within 4e-9 (relative) of the
 * least distance found so far (sum_row's ties are 1e-9 wide), and the rest are set beyond the
 * support: sum_row then decides as it would with every distance exact. */
static void settle_distances(const struct sph_nbrs *nb, const struct sph_system *s, size_t a,
                             double *dist, unsigned char *exact, double support) {
  const struct sph_nlist *nl = &nb->list[SPH_KIND_SEGMENT];
  const size_t first = nl->offset[a], n = nl->offset[a + 1] - first;
  const double tie = 1.0 + 4e-9;
  double best = INFINITY, gmax = 0.0, d[3];
  size_t at = n;
  for (size_t i = 0; i < n; i++) {
    if (exact[i]) {
      best = fmin(best, dist[i]);
      continue;
    }
    const size_t p = first + i;
    const double g2 = nb->grad_gamma_as[0][p] * nb->grad_gamma_as[0][p] +
                      nb->grad_gamma_as[1][p] * nb->grad_gamma_as[1][p] +
                      nb->grad_gamma_as[2][p] * nb->grad_gamma_as[2][p];
    if (g2 == 0.0 && nb->term_as[p] == 0.0) {
      dist[i] = INFINITY;
      exact[i] = 1;
    } else if (g2 > gmax) {
      gmax = g2;
      at = i;
    }
  }
  if (at < n) {
    const struct sph_tri_axes *ax = pair_axes(nb, s, a, nl->index[first + at], d);
    dist[at] = sph_gamma3d_offset_distance(d, ax);
    exact[at] = 1;
    best = fmin(best, dist[at]);
  }
  for (size_t i = 0; i < n; i++) {
    if (exact[i]) continue;
    if (dist[i] < support && dist[i] <= best * tie) {
      const struct sph_tri_axes *ax = pair_axes(nb, s, a, nl->index[first + i], d);
      const double lb = sph_gamma3d_offset_bound(d, ax);
      if (lb < support && lb <= best * tie) {
        dist[i] = sph_gamma3d_offset_distance(d, ax);
        best = fmin(best, dist[i]);
        continue;
      }
    }
    dist[i] = INFINITY;
  }
}

/* γ_a, ∇γ_a and the side test from the pair data of row a (dist: the distances to the row's
 * elements, from its first pair; NULL: no side test) (sums in list order, so that reused
 * and recomputed pair data give the same bits). A pair beyond the support has term and ∇γ_as
 * exactly +0 (pair_wall): adding it leaves the sums' bits unchanged (a sum started at +0 is never
 * −0, and x + 0 = x), so a row holding more pairs than needed (a list kept from an earlier build)
 * gives the bits of a fresh one. The side test looks at the elements within the support only, for
 * the same reason. */
static int sum_row(struct sph_nbrs *nb, struct sph_parts *f, size_t a, const double *dist,
                   double support) {
  const struct sph_nlist *nl = &nb->list[SPH_KIND_SEGMENT];
  double sum_term = 0.0, g[3] = {0.0, 0.0, 0.0}, dmin = INFINITY, side = 0.0;
  const size_t first = nl->offset[a];
  for (size_t p = first; p < nl->offset[a + 1]; p++) {
    sum_term += nb->term_as[p];
    for (int c = 0; c < 3; c++) g[c] += nb->grad_gamma_as[c][p];
    /* Side test against the nearest element(s): outside when behind their summed normals. */
    const double d = dist ? dist[p - first] : INFINITY;
    if (d < support) {
      if (d < dmin * (1.0 - 1e-9)) {
        dmin = d;
        side = nb->dist_as[p];
      } else if (d <= dmin * (1.0 + 1e-9)) {
        side += nb->dist_as[p];
      }
    }
  }
  f->gamma[a] = 1.0 - sum_term;
  for (int c = 0; c < 3; c++) f->grad_gamma[c][a] = g[c];
  return side < 0.0;
}

/* Where segment j sits in the row being summed by one thread: valid when stamp is that row's. */
struct sph_row_slot {
  size_t stamp, pos;
};

/* The edge values of segment j that a coplanar neighbour earlier in the row has already computed,
 * signed for j's direction of the edge. */
static void share_from_row(const struct sph_nbrs *nb, size_t j, size_t stamp,
                           const struct sph_row_slot *slot, const struct sph_edge_share *row,
                           struct sph_edge_share *sh) {
  sh->have = 0;
  for (int i = 0; i < 3; i++) {
    const struct sph_edge_link *L = &nb->edge_link[3 * j + (size_t)i];
    if (L->seg < 0 || slot[L->seg].stamp != stamp) continue;
    const struct sph_edge_share *o = &row[slot[L->seg].pos];
    if (!(o->got >> L->edge & 1)) continue;
    sh->have |= 1 << i;
    sh->value[i][0] = L->sign * o->value[L->edge][0];
    sh->value[i][1] = L->sign * o->value[L->edge][1];
  }
}

void sph_nbrs_gamma(struct sph_nbrs *nb, struct sph_system *s, const struct sph_kernel *k) {
  struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const struct sph_nlist *nl = &nb->list[SPH_KIND_SEGMENT];
  if (f->n + 1 > nb->cap_behind) {
    nb->cap_behind = f->n + f->n / 2 + 16;
    nb->behind = cmn_realloc(nb->behind, nb->cap_behind * sizeof *nb->behind);
  }
  unsigned char *behind = nb->behind;
  /* 3D: per thread, the edge values of the row being summed (shared across coplanar edges) */
  const int share = s->dim == 3 && nb->edge_link != NULL;
  size_t maxrow = 0;
  for (size_t a = 0; a < f->n; a++)
    if (nl->offset[a + 1] - nl->offset[a] > maxrow) maxrow = nl->offset[a + 1] - nl->offset[a];
  int nthreads = 1;
#ifdef _OPENMP
  nthreads = omp_get_max_threads();
#endif
  /* per thread, the edge values and the distances to the elements of the row being summed (side
   * test): kept in nb, so that a step allocates nothing once they have grown */
  const size_t need = (maxrow + 1) * (size_t)nthreads;
  if (need > nb->cap_row || !nb->row_dist) {
    nb->cap_row = need + need / 4;
    nb->row_share = cmn_realloc(nb->row_share, nb->cap_row * sizeof *nb->row_share);
    nb->row_dist = cmn_realloc(nb->row_dist, nb->cap_row * sizeof *nb->row_dist);
    nb->row_exact = cmn_realloc(nb->row_exact, nb->cap_row * sizeof *nb->row_exact);
  }
  struct sph_edge_share *rows = share ? nb->row_share : NULL;
  double *dists = nb->row_dist;
  const size_t nseg = s->part[SPH_KIND_SEGMENT].n;
  if (share && nseg * (size_t)nthreads > nb->cap_slots) { /* fresh slots: stamps start at 1 */
    free(nb->row_slot);
    nb->cap_slots = nseg * (size_t)nthreads;
    nb->row_slot = cmn_calloc(nb->cap_slots, sizeof *nb->row_slot);
    nb->stamp = 0;
  }
  const size_t base = nb->stamp; /* row a's stamp: base + a + 1, unique over the calls */
  if (share) nb->stamp += f->n + 1;
  size_t shared = 0;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : shared)
#endif
  for (size_t a = 0; a < f->n; a++) {
    struct sph_edge_share *row = NULL;
    struct sph_row_slot *slot = NULL;
    int tid = 0;
#ifdef _OPENMP
    tid = omp_get_thread_num();
#endif
    double *dist = dists + (size_t)tid * (maxrow + 1);
    unsigned char *exact = nb->row_exact + (size_t)tid * (maxrow + 1);
    if (share) {
      row = rows + (size_t)tid * (maxrow + 1);
      slot = nb->row_slot + (size_t)tid * nseg;
    }
    const size_t first = nl->offset[a], stamp = base + a + 1;
    for (size_t p = first; p < nl->offset[a + 1]; p++) {
      const size_t j = nl->index[p];
      double gs[3];
      struct sph_edge_share *sh = share ? &row[p - first] : NULL;
      if (sh) {
        share_from_row(nb, j, stamp, slot, row, sh);
        slot[j] = (struct sph_row_slot){stamp, p - first};
      }
      exact[p - first] = (unsigned char)pair_wall(nb, s, k, a, j, sh, &nb->term_as[p], gs,
                                                  &dist[p - first], &nb->dist_as[p]);
      for (int c = 0; c < 3; c++) nb->grad_gamma_as[c][p] = gs[c];
      if (sh && sh->got) shared += (size_t)((sh->have & 1) + (sh->have >> 1 & 1) + (sh->have >> 2));
    }
    if (s->dim == 3) settle_distances(nb, s, a, dist, exact, sph_kernel_support(k));
    behind[a] = (unsigned char)sum_row(nb, f, a, dist, sph_kernel_support(k));
  }
  nb->edges_shared = shared;
  /* Every particle behind a wall is flagged; the count and the lowest index come from the flags
   * in index order, so they do not depend on the thread count. */
  nb->nescaped = 0;
  nb->escaped = -1;
  for (size_t a = 0; a < f->n; a++) {
    if (!behind[a]) continue;
    if (nb->nescaped++ == 0) nb->escaped = (long)a;
  }
}

void sph_nbrs_rebuild_reuse(struct sph_nbrs *nb, struct sph_system *s, const struct sph_kernel *k,
                            double skin) {
  struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  /* Keep the old fluid–segment rows and their pair data. */
  struct sph_nlist old = nb->list[SPH_KIND_SEGMENT];
  double *old_g[3] = {nb->grad_gamma_as[0], nb->grad_gamma_as[1], nb->grad_gamma_as[2]};
  double *old_term = nb->term_as, *old_off = nb->dist_as;
  if (old.n != f->n || !old_term) {
    sph_nbrs_build(nb, s, skin);
    sph_nbrs_gamma(nb, s, k);
    return;
  }
  memset(&nb->list[SPH_KIND_SEGMENT], 0, sizeof old);
  nb->list[SPH_KIND_SEGMENT].scratch = old.scratch; /* the work buffers go on with the list */
  old.scratch = NULL;
  for (int c = 0; c < 3; c++) nb->grad_gamma_as[c] = NULL;
  nb->term_as = nb->dist_as = NULL;
  nb->cap_pairs = 0;
  build(nb, s, skin, 0);
  const struct sph_nlist *nl = &nb->list[SPH_KIND_SEGMENT];
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 64)
#endif
  for (size_t a = 0; a < f->n; a++) {
    size_t q = old.offset[a]; /* both rows sorted by segment index */
    for (size_t p = nl->offset[a]; p < nl->offset[a + 1]; p++) {
      const size_t j = nl->index[p];
      while (q < old.offset[a + 1] && old.index[q] < j) q++;
      if (q < old.offset[a + 1] && old.index[q] == j) {
        nb->term_as[p] = old_term[q];
        nb->dist_as[p] = old_off[q];
        for (int c = 0; c < 3; c++) nb->grad_gamma_as[c][p] = old_g[c][q];
      } else { /* new in the list: beyond the old radius, but computed rather than assumed */
        double gs[3], dist;
        pair_wall(nb, s, k, a, j, NULL, &nb->term_as[p], gs, &dist, &nb->dist_as[p]);
        for (int c = 0; c < 3; c++) nb->grad_gamma_as[c][p] = gs[c];
      }
    }
    sum_row(nb, f, a, NULL, 0.0);
  }
  /* nb->behind, nescaped and escaped are those of the evaluation at these positions. */
  sph_nlist_free(&old);
  for (int c = 0; c < 3; c++) free(old_g[c]);
  free(old_term);
  free(old_off);
}

void sph_nbrs_free(struct sph_nbrs *nb) {
  sph_cells_free(&nb->cells);
  for (int k = 0; k < SPH_NKINDS; k++) sph_nlist_free(&nb->list[k]);
  sph_nlist_free(&nb->vf);
  for (int c = 0; c < 3; c++) free(nb->grad_gamma_as[c]);
  free(nb->dist_as);
  free(nb->term_as);
  free(nb->behind);
  free(nb->tri_axes);
  free(nb->edge_link);
  free(nb->row_slot);
  free(nb->row_share);
  free(nb->row_dist);
  free(nb->row_exact);
  memset(nb, 0, sizeof *nb);
}
