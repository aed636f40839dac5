/* Cell-list neighbour lists against the naive O(N^2) search on random sets: 1D/2D/3D, periodic
 * or not in each direction, fluid–fluid, fluid–vertex, fluid–segment (and vertex–fluid,
 * segment–fluid), several thread counts; rows must be the same sets, and the same sequences
 * whatever the thread count. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/sph.h"
#include "testutil.h"
#ifdef _OPENMP
#include <omp.h>
#endif

static int cmp_size(const void *a, const void *b) {
  size_t x = *(const size_t *)a, y = *(const size_t *)b;
  return (x > y) - (x < y);
}

/* Random fluid and vertex points in [lo, hi) and segments made of nearby vertices (their
 * vertices may lie across a periodic boundary, wrapped into the box). */
static void random_system(struct sph_system *s, int dim, unsigned periodic, uint64_t seed,
                          size_t nf, size_t nseg, double seg_size) {
  struct sabre_rng rng;
  sabre_rng_seed(&rng, seed);
  sph_system_init(s, dim);
  const double lo[3] = {-0.37, 0.21, 1.13}, hi[3] = {0.61, 1.05, 1.98};
  for (int a = 0; a < dim; a++) {
    s->domain.lo[a] = lo[a];
    s->domain.hi[a] = hi[a];
    s->domain.periodic[a] = (periodic >> a) & 1u;
  }
  size_t f0 = sph_system_append(s, SPH_KIND_FLUID, nf);
  for (size_t i = f0; i < f0 + nf; i++)
    for (int a = 0; a < dim; a++) {
      /* Across a periodic boundary, some particles have moved out of the box since their last
       * wrap (by up to 3 % of the period). */
      double out = s->domain.periodic[a] ? 0.03 * (hi[a] - lo[a]) : 0.0;
      s->part[SPH_KIND_FLUID].x[a][i] = sabre_rng_uniform(&rng, lo[a] - out, hi[a] + out);
    }
  /* A few extra vertices not attached to any segment, then dim vertices per segment. */
  size_t nv_free = nseg / 2;
  size_t v0 = sph_system_append(s, SPH_KIND_VERTEX, nv_free + nseg * (size_t)dim);
  struct sph_parts *pv = &s->part[SPH_KIND_VERTEX];
  for (size_t i = v0; i < v0 + nv_free; i++)
    for (int a = 0; a < dim; a++) pv->x[a][i] = sabre_rng_uniform(&rng, lo[a], hi[a]);
  size_t s0 = sph_system_append(s, SPH_KIND_SEGMENT, nseg);
  struct sph_parts *ps = &s->part[SPH_KIND_SEGMENT];
  for (size_t j = 0; j < nseg; j++) {
    double c[3] = {0, 0, 0};
    for (int a = 0; a < dim; a++) c[a] = sabre_rng_uniform(&rng, lo[a], hi[a]);
    double mean[3] = {0, 0, 0};
    for (int k = 0; k < dim; k++) {
      size_t iv = v0 + nv_free + j * (size_t)dim + (size_t)k;
      ps->vertex[k][s0 + j] = iv;
      for (int a = 0; a < dim; a++) {
        double x = c[a] + sabre_rng_uniform(&rng, -seg_size, seg_size);
        mean[a] += x / dim;
        if (s->domain.periodic[a]) {
          double len = hi[a] - lo[a];
          if (x >= hi[a]) x -= len;
          if (x < lo[a]) x += len;
        }
        pv->x[a][iv] = x;
      }
    }
    for (int a = 0; a < dim; a++) {
      double x = mean[a];
      if (s->domain.periodic[a]) {
        double len = hi[a] - lo[a];
        if (x >= hi[a]) x -= len;
        if (x < lo[a]) x += len;
      }
      ps->x[a][s0 + j] = x;
    }
  }
}

/* The cell search's rows are the naive search's, entry for entry: both sorted by index. */
static size_t compare_lists(const struct sph_nlist *cell, const struct sph_nlist *naive) {
  assert_int_equal(cell->n, naive->n);
  size_t total = 0;
  for (size_t i = 0; i < cell->n; i++) {
    size_t len = cell->offset[i + 1] - cell->offset[i];
    assert_int_equal(len, naive->offset[i + 1] - naive->offset[i]);
    size_t *row = malloc((len ? len : 1) * sizeof *row);
    for (size_t k = 0; k < len; k++) row[k] = cell->index[cell->offset[i] + k];
    qsort(row, len, sizeof *row, cmp_size);
    for (size_t k = 0; k < len; k++) {
      assert_int_equal(row[k], naive->index[naive->offset[i] + k]);
      assert_int_equal(cell->index[cell->offset[i] + k], row[k]);
    }
    free(row);
    total += len;
  }
  return total;
}

static void set_threads(int n) {
#ifdef _OPENMP
  omp_set_num_threads(n);
#else
  (void)n;
#endif
}

static void check_dim(int dim, size_t nf, double radius) {
  static const enum sph_kind pairs[][2] = {{SPH_KIND_FLUID, SPH_KIND_FLUID},
                                           {SPH_KIND_FLUID, SPH_KIND_VERTEX},
                                           {SPH_KIND_FLUID, SPH_KIND_SEGMENT},
                                           {SPH_KIND_VERTEX, SPH_KIND_FLUID},
                                           {SPH_KIND_SEGMENT, SPH_KIND_FLUID}};
  for (unsigned periodic = 0; periodic < (1u << dim); periodic++) {
    struct sph_system s;
    random_system(&s, dim, periodic, 1234 + periodic * 7 + (uint64_t)dim, nf, nf / 4, 0.4 * radius);
    for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++) {
      struct sph_nlist naive = {0}, first = {0};
      sph_nlist_build_naive(&naive, &s, pairs[p][0], pairs[p][1], radius);
      for (int threads = 1; threads <= 3; threads++) {
        set_threads(threads);
        struct sph_cells cells = {0};
        struct sph_nlist nl = {0};
        sph_cells_build(&cells, &s, radius);
        sph_nlist_build(&nl, &cells, &s, pairs[p][0], pairs[p][1], radius);
        size_t total = compare_lists(&nl, &naive);
        assert_true(total > nl.n); /* a test with empty lists could not fail */
        if (threads == 1) {
          first = nl;
        } else {
          assert_memory_equal(nl.offset, first.offset, (nl.n + 1) * sizeof(size_t));
          assert_memory_equal(nl.index, first.index, nl.offset[nl.n] * sizeof *nl.index);
          sph_nlist_free(&nl);
        }
        sph_cells_free(&cells);
      }
      sph_nlist_free(&first);
      sph_nlist_free(&naive);
    }
    sph_system_free(&s);
  }
  set_threads(1);
}

static void test_neighbours_1d(void **state) {
  (void)state;
  check_dim(1, 300, 0.0284);
}

static void test_neighbours_2d(void **state) {
  (void)state;
  check_dim(2, 400, 0.123);
}

static void test_neighbours_3d(void **state) {
  (void)state;
  check_dim(3, 450, 0.218);
}

/* A wide radius spans several cells of a periodic direction: every pair is still found once. */
static void test_neighbours_wide_radius(void **state) {
  (void)state;
  struct sph_system s;
  random_system(&s, 2, 3u, 99, 300, 60, 0.05);
  struct sph_cells cells = {0};
  struct sph_nlist nl = {0}, naive = {0};
  sph_cells_build(&cells, &s, 0.1);
  sph_nlist_build(&nl, &cells, &s, SPH_KIND_FLUID, SPH_KIND_FLUID, 0.39);
  sph_nlist_build_naive(&naive, &s, SPH_KIND_FLUID, SPH_KIND_FLUID, 0.39);
  compare_lists(&nl, &naive);
  sph_nlist_build(&nl, &cells, &s, SPH_KIND_FLUID, SPH_KIND_SEGMENT, 0.3);
  sph_nlist_build_naive(&naive, &s, SPH_KIND_FLUID, SPH_KIND_SEGMENT, 0.3);
  compare_lists(&nl, &naive);
  sph_nlist_free(&nl);
  sph_nlist_free(&naive);
  sph_cells_free(&cells);
  sph_system_free(&s);
}

/* Kinds with no particles, and lists with no pairs at all (sanitizers watch the empty paths). */
static void test_neighbours_empty(void **state) {
  (void)state;
  struct sph_system s;
  sph_system_init(&s, 2);
  s.domain.hi[0] = s.domain.hi[1] = 1;
  s.domain.periodic[0] = 1;
  assert_int_equal(sph_system_append(&s, SPH_KIND_VERTEX, 0), 0);
  size_t f0 = sph_system_append(&s, SPH_KIND_FLUID, 3);
  for (size_t i = f0; i < 3; i++) s.part[SPH_KIND_FLUID].x[0][i] = 0.3 * (double)i;
  struct sph_cells cells = {0};
  struct sph_nlist nl = {0};
  sph_cells_build(&cells, &s, 0.1);
  for (int k = 0; k < SPH_NKINDS; k++) {
    sph_nlist_build(&nl, &cells, &s, SPH_KIND_FLUID, (enum sph_kind)k, 0.1);
    assert_int_equal(nl.n, 3);
    assert_int_equal(nl.offset[3], 0);
  }
  sph_nlist_build(&nl, &cells, &s, SPH_KIND_SEGMENT, SPH_KIND_FLUID, 0.1);
  assert_int_equal(nl.n, 0);
  sph_nlist_free(&nl);
  sph_cells_free(&cells);
  sph_system_free(&s);
}

/* Threads that find no pair at all, next to threads that do: one vertex in a corner of a lattice
 * of fluid particles over 12 × 12 cells, and no vertex at all; 1 to 4 threads. The row buffers of
 * the idle threads must not be read as NULL (UBSan in the sanitizer build). */
static void test_neighbours_idle_threads(void **state) {
  (void)state;
  struct sph_system s;
  sph_system_init(&s, 2);
  s.domain.hi[0] = s.domain.hi[1] = 1.2;
  const int side = 24;
  size_t f0 = sph_system_append(&s, SPH_KIND_FLUID, (size_t)(side * side));
  for (int i = 0; i < side * side; i++) {
    s.part[SPH_KIND_FLUID].x[0][f0 + (size_t)i] = 0.05 * (i % side) + 0.0213;
    s.part[SPH_KIND_FLUID].x[1][f0 + (size_t)i] = 0.05 * (i / side) + 0.0187;
  }
  for (int nv = 0; nv <= 1; nv++) {
    if (nv) {
      size_t v0 = sph_system_append(&s, SPH_KIND_VERTEX, 1);
      s.part[SPH_KIND_VERTEX].x[0][v0] = 0.031;
      s.part[SPH_KIND_VERTEX].x[1][v0] = 0.047;
    }
    struct sph_nlist naive = {0};
    sph_nlist_build_naive(&naive, &s, SPH_KIND_FLUID, SPH_KIND_VERTEX, 0.1);
    const size_t pairs = naive.offset[naive.n];
    assert_true(nv ? pairs > 0 && pairs < 20 : pairs == 0);
    for (int threads = 1; threads <= 4; threads++) {
      set_threads(threads);
      struct sph_cells cells = {0};
      struct sph_nlist nl = {0};
      sph_cells_build(&cells, &s, 0.1);
      assert_true(cells.ncells >= 100);
      sph_nlist_build(&nl, &cells, &s, SPH_KIND_FLUID, SPH_KIND_VERTEX, 0.1);
      assert_int_equal(compare_lists(&nl, &naive), pairs);
      sph_nlist_free(&nl);
      sph_cells_free(&cells);
    }
    sph_nlist_free(&naive);
  }
  set_threads(1);
  sph_system_free(&s);
}

/* More query particles than one slice of sph_nlist_build (32768): three slices. Fluid–segment rows
 * against the naive search, every 101st fluid–fluid row against a direct scan of all particles
 * (the naive fluid–fluid search would take too long), and the same bits with 1 and 2 threads. */
static void test_neighbours_slices(void **state) {
  (void)state;
  struct sph_system s;
  const size_t nf = 80000;
  const double radius = 0.04;
  random_system(&s, 3, 1u, 4321, nf, 150, 0.02);
  const struct sph_parts *f = &s.part[SPH_KIND_FLUID];
  struct sph_nlist first = {0}, naive = {0};
  sph_nlist_build_naive(&naive, &s, SPH_KIND_FLUID, SPH_KIND_SEGMENT, radius);
  for (int threads = 1; threads <= 2; threads++) {
    set_threads(threads);
    struct sph_cells cells = {0};
    struct sph_nlist nl = {0};
    sph_cells_build(&cells, &s, radius);
    sph_nlist_build(&nl, &cells, &s, SPH_KIND_FLUID, SPH_KIND_SEGMENT, radius);
    assert_true(compare_lists(&nl, &naive) > nf / 100);
    sph_nlist_build(&nl, &cells, &s, SPH_KIND_FLUID, SPH_KIND_FLUID, radius);
    size_t checked = 0;
    for (size_t i = 0; i < nf; i += 101) {
      size_t q = nl.offset[i];
      for (size_t j = 0; j < nf; j++) {
        const double xi[3] = {f->x[0][i], f->x[1][i], f->x[2][i]};
        const double xj[3] = {f->x[0][j], f->x[1][j], f->x[2][j]};
        double d[3];
        sph_domain_delta(&s.domain, xi, xj, d);
        if (j == i || d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= radius * radius) continue;
        assert_true(q < nl.offset[i + 1]);
        assert_int_equal(nl.index[q++], j);
        checked++;
      }
      assert_int_equal(q, nl.offset[i + 1]);
    }
    assert_true(checked > 10 * (nf / 101)); /* rows of about 30 neighbours */
    if (threads == 1) {
      first = nl;
    } else {
      assert_memory_equal(nl.offset, first.offset, (nf + 1) * sizeof(size_t));
      assert_memory_equal(nl.index, first.index, nl.offset[nf] * sizeof *nl.index);
      sph_nlist_free(&nl);
    }
    sph_cells_free(&cells);
  }
  set_threads(1);
  sph_nlist_free(&naive);
  sph_nlist_free(&first);
  sph_system_free(&s);
}

/* Point-to-element distance against hand-computed cases (face, edge and vertex regions). */
static void test_element_distance(void **state) {
  (void)state;
  double q[3];
  double seg[3][3] = {{0.3, 0.2, 0}, {1.3, 0.2, 0}, {0, 0, 0}};
  assert_rel(sph_element_distance(2, seg, (double[]){0.7, 0.95, 0}, q), 0.75, 1e-15);
  assert_rel(sph_element_distance(2, seg, (double[]){1.6, 0.6, 0}, q), 0.5, 1e-15);
  double tri[3][3] = {{0, 0, 0.5}, {2, 0, 0.5}, {0, 2, 0.5}};
  assert_rel(sph_element_distance(3, tri, (double[]){0.4, 0.3, 1.7}, q), 1.2, 1e-15);
  assert_rel(sph_element_distance(3, tri, (double[]){-0.3, -0.4, 0.5}, q), 0.5, 1e-15);
  assert_rel(sph_element_distance(3, tri, (double[]){1.5, 1.5, 0.5}, q), sqrt(0.5), 1e-15);
  assert_rel(q[0], 1.0, 1e-15);
  assert_rel(q[1], 1.0, 1e-15);
  double pt[3][3] = {{0.25, 0, 0}};
  assert_rel(sph_element_distance(1, pt, (double[]){-0.5, 0, 0}, q), 0.75, 1e-15);
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_element_distance),        cmocka_unit_test(test_neighbours_1d),
      cmocka_unit_test(test_neighbours_2d),           cmocka_unit_test(test_neighbours_3d),
      cmocka_unit_test(test_neighbours_wide_radius),  cmocka_unit_test(test_neighbours_empty),
      cmocka_unit_test(test_neighbours_idle_threads), cmocka_unit_test(test_neighbours_slices)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
