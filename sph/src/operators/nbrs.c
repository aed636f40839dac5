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

#include "sabre/common.h"
#include "sabre/sph_solver.h"

static void reserve_pairs(struct sph_nbrs *nb) {
  size_t n = nb->list[SPH_KIND_SEGMENT].n;
  size_t np = n ? nb->list[SPH_KIND_SEGMENT].offset[n] : 0;
  if (np <= nb->cap_pairs && nb->dist_as) return;
  size_t cap = np + np / 2 + 16;
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
}

void sph_nbrs_build(struct sph_nbrs *nb, const struct sph_system *s, double skin) {
  build(nb, s, skin, 0);
}

void sph_nbrs_build_naive(struct sph_nbrs *nb, const struct sph_system *s, double skin) {
  build(nb, s, skin, 1);
}

/* Wall data of pair p (fluid a, segment j): γ term, ∇γ_as, distance to the element and to its
 * plane (signed, > 0 on the fluid side). */
static void pair_wall(const struct sph_system *s, const struct sph_kernel *k, size_t a, size_t j,
                      double *term, double gs[3], double *dist, double *off) {
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID], *seg = &s->part[SPH_KIND_SEGMENT];
  const double xa[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
  struct sph_wall_element e;
  sph_segment_vertices(s, j, xa, e.x);
  for (int c = 0; c < 3; c++) e.normal[c] = seg->normal[c][j];
  double q[3];
  *dist = sph_element_distance(s->dim, (const double(*)[3])e.x, xa, q);
  *off = 0.0;
  for (int c = 0; c < 3; c++) *off += (xa[c] - q[c]) * e.normal[c];
  *term = 0.0;
  gs[0] = gs[1] = gs[2] = 0.0;
  if (*dist < sph_kernel_support(k)) sph_gamma_element(k, xa, &e, term, gs);
}

/* γ_a, ∇γ_a and the side test from the pair data of row a (sums in list order, so that reused
 * and recomputed pair data give the same bits). A pair beyond the support has term and ∇γ_as
 * exactly +0 (pair_wall): adding it leaves the sums' bits unchanged (a sum started at +0 is never
 * −0, and x + 0 = x), so a row holding more pairs than needed (a list kept from an earlier build)
 * gives the bits of a fresh one. The side test looks at the elements within the support only, for
 * the same reason. */
static int sum_row(struct sph_nbrs *nb, struct sph_parts *f, size_t a, const double *dist,
                   double support) {
  const struct sph_nlist *nl = &nb->list[SPH_KIND_SEGMENT];
  double sum_term = 0.0, g[3] = {0.0, 0.0, 0.0}, dmin = INFINITY, side = 0.0;
  for (size_t p = nl->offset[a]; p < nl->offset[a + 1]; p++) {
    sum_term += nb->term_as[p];
    for (int c = 0; c < 3; c++) g[c] += nb->grad_gamma_as[c][p];
    /* Side test against the nearest element(s): outside when behind their summed normals. */
    if (dist && dist[p] < support) {
      if (dist[p] < dmin * (1.0 - 1e-9)) {
        dmin = dist[p];
        side = nb->dist_as[p];
      } else if (dist[p] <= dmin * (1.0 + 1e-9)) {
        side += nb->dist_as[p];
      }
    }
  }
  f->gamma[a] = 1.0 - sum_term;
  for (int c = 0; c < 3; c++) f->grad_gamma[c][a] = g[c];
  return side < 0.0;
}

void sph_nbrs_gamma(struct sph_nbrs *nb, struct sph_system *s, const struct sph_kernel *k) {
  struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const struct sph_nlist *nl = &nb->list[SPH_KIND_SEGMENT];
  size_t np = f->n ? nl->offset[f->n] : 0;
  double *dist = cmn_malloc((np + 1) * sizeof *dist);
  if (f->n + 1 > nb->cap_behind) {
    nb->cap_behind = f->n + f->n / 2 + 16;
    nb->behind = cmn_realloc(nb->behind, nb->cap_behind * sizeof *nb->behind);
  }
  unsigned char *behind = nb->behind;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 64)
#endif
  for (size_t a = 0; a < f->n; a++) {
    for (size_t p = nl->offset[a]; p < nl->offset[a + 1]; p++) {
      double gs[3];
      pair_wall(s, k, a, nl->index[p], &nb->term_as[p], gs, &dist[p], &nb->dist_as[p]);
      for (int c = 0; c < 3; c++) nb->grad_gamma_as[c][p] = gs[c];
    }
    behind[a] = (unsigned char)sum_row(nb, f, a, dist, sph_kernel_support(k));
  }
  free(dist);
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
        pair_wall(s, k, a, j, &nb->term_as[p], gs, &dist, &nb->dist_as[p]);
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
  memset(nb, 0, sizeof *nb);
}
