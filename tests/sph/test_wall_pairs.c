/* The fluid–segment pair data of sph_nbrs_gamma in 3D (one frame per pair, the edge integrals of
 * a meshed face shared between the coplanar triangles across each edge, docs/sph-gamma.md §10)
 * against the reference path, pair by pair: sph_gamma_element, sph_element_distance and, per
 * particle, sph_gamma_eval over all the segments; and the same bits with 1 and 2 threads. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/sph_walls.h"
#include "solver_fixture.h"
#include "sph_testfiles.h"
#ifdef _OPENMP
#include <omp.h>
#endif

/* A closed tank (faces meshed into many triangles, edges, corners) and a box of fluid a row from
 * its walls, moved off the lattice by up to 0.45 Δr. */
static const char tank[] =
    "geometry:\n"
    "  dimension: 3\n"
    "  dr: 0.025\n"
    "  h_over_dr: 2\n"
    "  first_row: 1\n"
    "  walls: [{type: box, lo: [0, 0, 0], hi: [0.3, 0.25, 0.2]}]\n"
    "  fluid: [{type: box, lo: [0, 0, 0], hi: [0.3, 0.25, 0.2]}]\n";

static void gamma_pass(struct sph_system *s, const struct sph_kernel *k, int threads,
                       struct sph_nbrs *nb) {
#ifdef _OPENMP
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  memset(nb, 0, sizeof *nb);
  sph_nbrs_build(nb, s, 0.2 * s->h);
  sph_nbrs_gamma(nb, s, k);
}

/* The system of a case text with its fluid moved off the lattice by up to `spread` Δr (seeded),
 * and its kernel. */
static void jittered_tank(struct sph_system *s, struct sph_kernel *k, const char *text,
                          uint64_t seed, double spread) {
  fixture_system_from_yaml(s, text);
  struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  struct sabre_rng rng;
  sabre_rng_seed(&rng, seed);
  for (size_t a = 0; a < f->n; a++)
    for (int c = 0; c < 3; c++) f->x[c][a] += sabre_rng_uniform(&rng, -spread, spread) * s->dr;
  sph_kernel_init(k, 3, s->h);
}

static void test_pairs_against_reference(void **state) {
  (void)state;
  struct sph_system s;
  struct sph_kernel k;
  jittered_tank(&s, &k, tank, 5, 0.45);
  struct sph_parts *f = &s.part[SPH_KIND_FLUID];
  const struct sph_parts *sg = &s.part[SPH_KIND_SEGMENT];
  struct sph_nbrs nb1, nb2;
  gamma_pass(&s, &k, 1, &nb1);
  const double *gamma1 = f->gamma;
  double *g1 = malloc(f->n * sizeof *g1);
  memcpy(g1, gamma1, f->n * sizeof *g1);
  gamma_pass(&s, &k, 2, &nb2);

  const struct sph_nlist *nl = &nb1.list[SPH_KIND_SEGMENT];
  const size_t np = nl->offset[f->n];
  size_t in_support = 0;
  double worst_term = 0.0, worst_grad = 0.0, worst_off = 0.0, worst_gamma = 0.0;
  struct sph_wall_element *all = malloc(sg->n * sizeof *all);
  for (size_t a = 0; a < f->n; a++) {
    const double xa[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
    for (size_t p = nl->offset[a]; p < nl->offset[a + 1]; p++) {
      const size_t j = nl->index[p];
      struct sph_wall_element e;
      sph_segment_vertices(&s, j, xa, e.x);
      for (int c = 0; c < 3; c++) e.normal[c] = sg->normal[c][j];
      double term, grad[3], q[3];
      sph_gamma_element(&k, xa, &e, &term, grad);
      const double dist = sph_element_distance(3, (const double(*)[3])e.x, xa, q);
      double off = 0.0;
      for (int c = 0; c < 3; c++) off += (xa[c] - q[c]) * e.normal[c];
      if (dist < 2.0 * s.h) in_support++;
      worst_term = fmax(worst_term, fabs(nb1.term_as[p] - term));
      for (int c = 0; c < 3; c++)
        worst_grad = fmax(worst_grad, s.h * fabs(nb1.grad_gamma_as[c][p] - grad[c]));
      worst_off = fmax(worst_off, fabs(nb1.dist_as[p] - off) / s.h);
    }
    /* γ_a from every element of the tank through the library's own evaluation */
    for (size_t j = 0; j < sg->n; j++) {
      sph_segment_vertices(&s, j, xa, all[j].x);
      for (int c = 0; c < 3; c++) all[j].normal[c] = sg->normal[c][j];
    }
    double gamma, grad[3];
    assert_int_equal(sph_gamma_eval(&k, xa, sg->n, all, &gamma, grad), 0);
    worst_gamma = fmax(worst_gamma, fabs(g1[a] - gamma));
  }
  printf(
      "%zu fluid particles, %zu segments, %zu pairs (%zu within the support), %zu edge "
      "integrals shared; largest differences: term %.1e, h grad %.1e, plane distance/h %.1e, "
      "gamma %.1e\n",
      f->n, sg->n, np, in_support, nb1.edges_shared, worst_term, worst_grad, worst_off,
      worst_gamma);
  /* the sharing is exercised: most triangles of a meshed face take edges from a neighbour */
  assert_true(nb1.edges_shared > in_support / 2);
  assert_true(worst_term <= 1e-13);
  assert_true(worst_grad <= 1e-13);
  assert_true(worst_off <= 1e-13);
  assert_true(worst_gamma <= 1e-13);
  /* two threads: the same rows, the same bits */
  assert_int_equal(nb2.edges_shared, nb1.edges_shared);
  assert_memory_equal(nb2.term_as, nb1.term_as, np * sizeof(double));
  for (int c = 0; c < 3; c++)
    assert_memory_equal(nb2.grad_gamma_as[c], nb1.grad_gamma_as[c], np * sizeof(double));
  assert_memory_equal(f->gamma, g1, f->n * sizeof(double));
  free(all);
  free(g1);
  sph_nbrs_free(&nb1);
  sph_nbrs_free(&nb2);
  sph_system_free(&s);
}

/* The side test of sph_nbrs_gamma (which measures the distance only to the elements that may be
 * the nearest, docs/sph-gamma.md §10) against the same test with the reference distance of every
 * pair of the row, for the system s with its fluid moved off the lattice. Returns the number of
 * rows where the element of largest |∇γ_as| (the one the solver measures first) alone would give
 * the wrong side: the rows where the measuring and pruning of the other candidates decide. */
static size_t check_side(struct sph_system *s, const struct sph_kernel *k, size_t *behind_out) {
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT];
  struct sph_nbrs nb;
  gamma_pass(s, k, 1, &nb);
  const struct sph_nlist *nl = &nb.list[SPH_KIND_SEGMENT];
  const double support = 2.0 * s->h;
  size_t behind = 0, agree = 0, decided = 0;
  for (size_t a = 0; a < f->n; a++) {
    const double xa[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
    double dmin = INFINITY, side = 0.0, gmax = 0.0, side_first = 0.0;
    for (size_t p = nl->offset[a]; p < nl->offset[a + 1]; p++) {
      const size_t j = nl->index[p];
      struct sph_wall_element e;
      sph_segment_vertices(s, j, xa, e.x);
      double q[3];
      const double d = sph_element_distance(3, (const double(*)[3])e.x, xa, q);
      double off = 0.0, g2 = 0.0;
      for (int c = 0; c < 3; c++) {
        off += (xa[c] - q[c]) * sg->normal[c][j];
        g2 += nb.grad_gamma_as[c][p] * nb.grad_gamma_as[c][p];
      }
      if (g2 > gmax) {
        gmax = g2;
        side_first = off;
      }
      if (d >= support) continue;
      if (d < dmin * (1.0 - 1e-9)) {
        dmin = d;
        side = off;
      } else if (d <= dmin * (1.0 + 1e-9)) {
        side += off;
      }
    }
    const int ref = side < 0.0;
    behind += (size_t)ref;
    agree += (size_t)(ref == nb.behind[a]);
    decided += (size_t)(ref != (side_first < 0.0));
  }
  printf(
      "side test: %zu of %zu particles behind the walls by the reference distances, the "
      "solver agrees on %zu; in %zu rows the element of largest |grad gamma_as| alone would "
      "give the other side\n",
      behind, f->n, agree, decided);
  assert_int_equal(agree, f->n);
  assert_int_equal(nb.nescaped, behind);
  *behind_out = behind;
  sph_nbrs_free(&nb);
  return decided;
}

/* Particles moved by up to 1.5 Δr, many of them through the walls, edges and corners of the
 * tank. */
static void test_side_against_reference(void **state) {
  (void)state;
  struct sph_system s;
  struct sph_kernel k;
  jittered_tank(&s, &k, tank, 11, 1.5);
  size_t behind;
  check_side(&s, &k, &behind);
  assert_true(behind > 50);
  sph_system_free(&s);
}

/* One facet of a box: the square (c0, c1, c2, c3), counter-clockwise seen from outside, as two
 * triangles. */
static void stl_quad(char **at, const double c[4][3]) {
  const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (int t = 0; t < 2; t++) {
    *at += sprintf(*at, "facet normal 0 0 0\nouter loop\n");
    for (int i = 0; i < 3; i++) {
      const double *v = c[tri[t][i]];
      *at += sprintf(*at, "vertex %.17g %.17g %.17g\n", v[0], v[1], v[2]);
    }
    *at += sprintf(*at, "endloop\nendfacet\n");
  }
}

/* The same tank read from an STL file whose faces are two triangles each: the mesher bisects them
 * into triangles of several sizes and shapes, not aligned with the lattice, so that in many rows
 * the element of largest |∇γ_as| is not the nearest and the side test rests on the pruning of the
 * other candidates (by plane distance, then by the bounding-circle bound) decides the side in
 * some of them. On the box generator's grid of triangles it never does: the nearest element
 * there lies on the same face as the one of largest |∇γ_as|. */
static void test_side_mixed_triangles(void **state) {
  (void)state;
  const double L[3] = {0.3, 0.25, 0.2};
  /* each face of the box [0, L]: its four corners, counter-clockwise seen from outside */
  static const int face[6][4][3] = {
      {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  char stl[8192], *at = stl;
  at += sprintf(at, "solid tank\n");
  for (int q = 0; q < 6; q++) {
    double c[4][3];
    for (int i = 0; i < 4; i++)
      for (int d = 0; d < 3; d++) c[i][d] = face[q][i][d] * L[d];
    stl_quad(&at, (const double(*)[3])c);
  }
  sprintf(at, "endsolid tank\n");
  const char *path = test_write("tank.stl", stl);
  char yaml[1024];
  snprintf(yaml, sizeof yaml,
           "geometry:\n"
           "  dimension: 3\n"
           "  dr: 0.025\n"
           "  h_over_dr: 2\n"
           "  first_row: 1\n"
           "  walls: [{type: stl, file: '%s', fluid: inside}]\n"
           "  fluid: [{type: box, lo: [0, 0, 0], hi: [0.3, 0.25, 0.2]}]\n",
           path);
  struct sph_system s;
  struct sph_kernel k;
  jittered_tank(&s, &k, yaml, 13, 1.5);
  size_t behind;
  const size_t decided = check_side(&s, &k, &behind);
  assert_true(behind > 50);
  assert_true(decided >= 5);
  sph_system_free(&s);
}

int main(void) {
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_pairs_against_reference),
                                     cmocka_unit_test(test_side_against_reference),
                                     cmocka_unit_test(test_side_mixed_triangles)};
  return cmocka_run_group_tests(tests, test_dir_setup, test_dir_teardown);
}
