/* Neighbour search cost per particle in 2D and 3D (cell build + fluid–fluid list), with all
 * threads and with one, on a jittered lattice at the papers' h/Δr (2D: 2, 3D: 1.3).
 *
 * It also measures the layout choice of the particle store: a density-like gather over the
 * list reading structure-of-arrays fields (as sph_parts stores them), in cell order and in random
 * order, against an array of structures holding the same fields (one 128-byte struct per particle).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph.h"
#ifdef _OPENMP
#include <omp.h>
#endif

struct aos_part { /* what a particle would be as one struct: the fields of the store */
  double x[3], v[3], mass, rho, gamma, grad_gamma[3], pad[2];
};

static double wendland(double q) { /* shape only: the cost is what matters */
  double t = 1 - 0.5 * q;
  return q < 2 ? t * t * t * t * (1 + 2 * q) : 0.0;
}

static void set_threads(int n) {
#ifdef _OPENMP
  omp_set_num_threads(n);
#else
  (void)n;
#endif
}

static int max_threads(void) {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

static uint64_t rng_state = 12345;
static double uniform(void) {
  rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(rng_state >> 11) * 0x1.0p-53;
}

/* Gather Σ_j m_j w(r_ij / h) for every particle from the list; returns ns per pair. */
static double gather_soa(const struct sph_system *s, const struct sph_nlist *nl, double h,
                         double *out) {
  const struct sph_parts *p = &s->part[SPH_KIND_FLUID];
  double t0 = cmn_wall_time();
#ifdef _OPENMP
#pragma omp parallel for schedule(static)
#endif
  for (size_t i = 0; i < p->n; i++) {
    double sum = 0;
    for (size_t k = nl->offset[i]; k < nl->offset[i + 1]; k++) {
      size_t j = nl->index[k];
      double dx = p->x[0][j] - p->x[0][i], dy = p->x[1][j] - p->x[1][i],
             dz = p->x[2][j] - p->x[2][i];
      sum += p->mass[j] * wendland(sqrt(dx * dx + dy * dy + dz * dz) / h);
    }
    out[i] = sum;
  }
  return (cmn_wall_time() - t0) * 1e9 / (double)nl->offset[p->n];
}

static double gather_aos(const struct aos_part *a, size_t n, const struct sph_nlist *nl, double h,
                         double *out) {
  double t0 = cmn_wall_time();
#ifdef _OPENMP
#pragma omp parallel for schedule(static)
#endif
  for (size_t i = 0; i < n; i++) {
    double sum = 0;
    for (size_t k = nl->offset[i]; k < nl->offset[i + 1]; k++) {
      const struct aos_part *b = &a[nl->index[k]];
      double dx = b->x[0] - a[i].x[0], dy = b->x[1] - a[i].x[1], dz = b->x[2] - a[i].x[2];
      sum += b->mass * wendland(sqrt(dx * dx + dy * dy + dz * dz) / h);
    }
    out[i] = sum;
  }
  return (cmn_wall_time() - t0) * 1e9 / (double)nl->offset[n];
}

static void bench(int dim, long side, double h_over_dr) {
  struct sph_system s;
  sph_system_init(&s, dim);
  double dr = 1.0 / (double)side;
  s.dr = dr;
  s.h = h_over_dr * dr;
  size_t n = 1;
  for (int a = 0; a < dim; a++) {
    n *= (size_t)side;
    s.domain.lo[a] = 0;
    s.domain.hi[a] = 1;
    s.domain.periodic[a] = 1;
  }
  struct sph_parts *p = &s.part[SPH_KIND_FLUID];
  sph_system_append(&s, SPH_KIND_FLUID, n);
  /* Random order in memory, as particles end up after a while without sorting. */
  size_t *perm = cmn_malloc(n * sizeof *perm);
  for (size_t i = 0; i < n; i++) perm[i] = i;
  for (size_t i = n - 1; i > 0; i--) {
    size_t j = (size_t)(uniform() * (double)(i + 1)), t = perm[i];
    perm[i] = perm[j];
    perm[j] = t;
  }
  for (size_t i = 0; i < n; i++) {
    size_t rest = perm[i];
    for (int a = 0; a < dim; a++) {
      double x = ((double)(rest % (size_t)side) + 0.5 + 0.2 * (uniform() - 0.5)) * dr;
      p->x[a][i] = x;
      rest /= (size_t)side;
    }
    p->mass[i] = 1.0;
  }
  double support = 2 * s.h;
  struct sph_cells cells = {0};
  struct sph_nlist nl = {0};
  int threads[2] = {max_threads(), 1};
  double per_particle[2] = {0, 0};
  for (int t = 0; t < (threads[0] > 1 ? 2 : 1); t++) {
    set_threads(threads[t]);
    double best_cells = INFINITY, best_list = INFINITY;
    for (int rep = 0; rep < 3; rep++) {
      double t0 = cmn_wall_time();
      sph_cells_build(&cells, &s, support);
      double t1 = cmn_wall_time();
      sph_nlist_build(&nl, &cells, &s, SPH_KIND_FLUID, SPH_KIND_FLUID, support);
      double t2 = cmn_wall_time();
      best_cells = fmin(best_cells, t1 - t0);
      best_list = fmin(best_list, t2 - t1);
    }
    per_particle[t] = (best_cells + best_list) * 1e9 / (double)n;
    printf(
        "bench-neighbours: %dD, %zu particles, h/dr = %.1f, %.1f neighbours/particle, "
        "%d thread%s: cells %.1f ms + list %.1f ms = %.0f ns/particle\n",
        dim, n, h_over_dr, (double)nl.offset[n] / (double)n, threads[t], threads[t] > 1 ? "s" : "",
        best_cells * 1e3, best_list * 1e3, per_particle[t]);
  }
  set_threads(threads[0]);

  /* Layout: gather over the list, SoA in random order, SoA sorted by cell, AoS sorted by cell. */
  double *out = cmn_malloc(n * sizeof *out);
  double soa_random = gather_soa(&s, &nl, s.h, out);
  sph_parts_permute(p, cells.index[SPH_KIND_FLUID]); /* cell order */
  sph_cells_build(&cells, &s, support);
  sph_nlist_build(&nl, &cells, &s, SPH_KIND_FLUID, SPH_KIND_FLUID, support);
  double soa_sorted = INFINITY, aos_sorted = INFINITY;
  struct aos_part *aos = cmn_calloc(n, sizeof *aos);
  for (size_t i = 0; i < n; i++) {
    for (int a = 0; a < 3; a++) aos[i].x[a] = p->x[a][i];
    aos[i].mass = p->mass[i];
  }
  for (int rep = 0; rep < 3; rep++) {
    soa_sorted = fmin(soa_sorted, gather_soa(&s, &nl, s.h, out));
    aos_sorted = fmin(aos_sorted, gather_aos(aos, n, &nl, s.h, out));
  }
  printf(
      "bench-neighbours: %dD gather over the list (%d threads): SoA random order %.2f ns/pair, "
      "SoA cell order %.2f ns/pair, AoS cell order %.2f ns/pair\n",
      dim, threads[0], soa_random, soa_sorted, aos_sorted);
  free(aos);
  free(out);
  free(perm);
  sph_nlist_free(&nl);
  sph_cells_free(&cells);
  sph_system_free(&s);
}

int main(void) {
  bench(2, 320, 2.0); /* 102400 particles */
  bench(3, 47, 1.3);  /* 103823 particles */
  return 0;
}
