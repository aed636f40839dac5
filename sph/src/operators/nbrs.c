/*
 * Neighbourhoods of the fluid particles and the wall integrals per fluid–segment pair:
 * γ_a = 1 − Σ_s term_s, ∇γ_as and ∇γ_a, J(2)–J(4), through sabre/sph_walls.h (closed form).
 * The lists are built with radius 2h + skin so that one build serves a whole predictor–corrector
 * step (and the pairs at both ends of the time-summation continuity, M 84 / J 10–11).
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

void sph_nbrs_gamma(struct sph_nbrs *nb, struct sph_system *s, const struct sph_kernel *k) {
  struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const struct sph_parts *seg = &s->part[SPH_KIND_SEGMENT];
  const struct sph_nlist *nl = &nb->list[SPH_KIND_SEGMENT];
  const double support = sph_kernel_support(k);
  long escaped = -1;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 64) reduction(max : escaped)
#endif
  for (size_t a = 0; a < f->n; a++) {
    double xa[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
    double sum_term = 0.0, g[3] = {0.0, 0.0, 0.0};
    /* Side test against the nearest element(s): outside when behind their summed normals. */
    double dmin = INFINITY, side = 0.0;
    for (size_t p = nl->offset[a]; p < nl->offset[a + 1]; p++) {
      size_t j = nl->index[p];
      struct sph_wall_element e;
      sph_segment_vertices(s, j, xa, e.x);
      for (int c = 0; c < 3; c++) e.normal[c] = seg->normal[c][j];
      double q[3];
      double dist = sph_element_distance(s->dim, (const double(*)[3])e.x, xa, q);
      double off = 0.0;
      for (int c = 0; c < 3; c++) off += (xa[c] - q[c]) * e.normal[c];
      if (dist < dmin * (1.0 - 1e-9)) {
        dmin = dist;
        side = off;
      } else if (dist <= dmin * (1.0 + 1e-9)) {
        side += off;
      }
      nb->dist_as[p] = off;
      double term = 0.0, gs[3] = {0.0, 0.0, 0.0};
      if (dist < support) sph_gamma_element(k, xa, &e, &term, gs);
      sum_term += term;
      for (int c = 0; c < 3; c++) {
        nb->grad_gamma_as[c][p] = gs[c];
        g[c] += gs[c];
      }
    }
    f->gamma[a] = 1.0 - sum_term;
    for (int c = 0; c < 3; c++) f->grad_gamma[c][a] = g[c];
    if (side < 0.0 && (long)a > escaped) escaped = (long)a;
  }
  nb->escaped = escaped;
}

void sph_nbrs_free(struct sph_nbrs *nb) {
  sph_cells_free(&nb->cells);
  for (int k = 0; k < SPH_NKINDS; k++) sph_nlist_free(&nb->list[k]);
  sph_nlist_free(&nb->vf);
  for (int c = 0; c < 3; c++) free(nb->grad_gamma_as[c]);
  free(nb->dist_as);
  memset(nb, 0, sizeof *nb);
}
