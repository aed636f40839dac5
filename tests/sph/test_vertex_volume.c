/*
 * Geometric vertex volumes (sph_walls_vertex_volumes, docs/sph-solver.md §6): the wall layer of
 * thickness t nearest to each vertex. Exact values for walls meshed at Δr: Δr^(d−1) t on a flat
 * wall; in a right-angled box with t = Δr/2 the layer cells are cubes cut by the bisecting planes:
 * 2D corner t²·(1/2)·2 = Δr²/4 (1/2 of a face vertex), 3D edge Δr³/4 (1/2), 3D corner Δr³/8
 * (1/4). The sum over the vertices is the layer's volume: perimeter (area) × t minus the overlaps
 * at concave corners (edges), which the per-element cut removes.
 */
#include <math.h>
#include <stdlib.h>

#include "sabre/sph_walls.h"
#include "solver_fixture.h"

/* Relative tolerance of the sampled volumes: exact in 2D (the midpoint samples, 8 per Δr, do not
 * straddle a vertex's Voronoi boundary and the depth is found by bisection); in 3D the sub-triangle
 * centroids (12 per hypotenuse) resolve the in-triangle Voronoi cells to about 1 % at corners. */
#define TOL_2D 1e-9
#define TOL_3D 1e-2

/* Number of distinct normal directions among the segments at each vertex (1 face, 2 edge or 2D
 * corner, 3 corner). */
static void planes_per_vertex(const struct sph_system *s, int *np) {
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT];
  const size_t nv = s->part[SPH_KIND_VERTEX].n;
  double(*seen)[3][3] = calloc(nv, sizeof *seen);
  for (size_t i = 0; i < nv; i++) np[i] = 0;
  for (size_t j = 0; j < sg->n; j++)
    for (int k = 0; k < s->dim; k++) {
      size_t iv = sg->vertex[k][j];
      int found = 0;
      for (int q = 0; q < np[iv]; q++)
        found |= sg->normal[0][j] * seen[iv][q][0] + sg->normal[1][j] * seen[iv][q][1] +
                     sg->normal[2][j] * seen[iv][q][2] >
                 0.999;
      if (!found && np[iv] < 3) {
        for (int c = 0; c < 3; c++) seen[iv][np[iv]][c] = sg->normal[c][j];
        np[iv]++;
      }
    }
  free(seen);
}

static void check_box(const char *yaml, double dr, double t, double total) {
  struct sph_system s;
  fixture_system_from_yaml(&s, yaml);
  const size_t nv = s.part[SPH_KIND_VERTEX].n;
  double *vol = calloc(nv, sizeof *vol);
  int *np = calloc(nv, sizeof *np);
  assert_int_equal(sph_walls_vertex_volumes(&s, t, vol), 0);
  planes_per_vertex(&s, np);
  const double face = pow(dr, s.dim - 1) * t;
  double sum = 0.0;
  int count[4] = {0, 0, 0, 0};
  for (size_t i = 0; i < nv; i++) {
    sum += vol[i];
    count[np[i]]++;
    /* face 1, edge / 2D corner 1/2, 3D corner 1/4 */
    const double expect = np[i] == 1 ? face : np[i] == 2 ? face / 2 : face / 4;
    if (fabs(vol[i] / expect - 1.0) > (s.dim == 2 ? TOL_2D : TOL_3D))
      fail_msg("vertex %zu at (%g, %g, %g), %d planes: volume %.6g, expected %.6g", i,
               s.part[SPH_KIND_VERTEX].x[0][i], s.part[SPH_KIND_VERTEX].x[1][i],
               s.part[SPH_KIND_VERTEX].x[2][i], np[i], vol[i], expect);
  }
  assert_true(count[1] > 0 && count[2] > 0);
  assert_rel(sum, total, 1e-3);
  free(np);
  free(vol);
  sph_system_free(&s);
}

/* 2D box 1 × 0.75 m, Δr = 0.05: perimeter 3.5 m, t = Δr/2 → 3.5 t − 4 t². */
static void test_box_2d(void **state) {
  (void)state;
  const double dr = 0.05, t = 0.5 * dr;
  check_box(
      "geometry:\n  dimension: 2\n  dr: 0.05\n  h_over_dr: 2\n  walls:\n"
      "    - type: box\n      lo: [0, 0]\n      hi: [1, 0.75]\n",
      dr, t, 3.5 * t - 4.0 * t * t);
}

/* 3D box 0.2 × 0.25 × 0.3 m, Δr = 0.05: area 2(0.05 + 0.06 + 0.075) = 0.37 m²; each of the 12
 * edges loses t² of its length L (the two slabs overlap in a t × t square) and the 8 corners
 * give back t³ (the three overlaps meet in a t cube, removed three times, counted once):
 * 0.37 t − t² Σ L + 8 t³, Σ L = 4 (0.2 + 0.25 + 0.3). */
static void test_box_3d(void **state) {
  (void)state;
  const double dr = 0.05, t = 0.5 * dr;
  check_box(
      "geometry:\n  dimension: 3\n  dr: 0.05\n  h_over_dr: 2\n  walls:\n"
      "    - type: box\n      lo: [0, 0, 0]\n      hi: [0.2, 0.25, 0.3]\n",
      dr, t, 0.37 * t - t * t * 4.0 * (0.2 + 0.25 + 0.3) + 8.0 * t * t * t);
}

/* A thicker layer on a flat wall (2D channel periodic in x): every vertex Δr t. */
static void test_channel(void **state) {
  (void)state;
  struct sph_system s;
  fixture_system_from_yaml(&s,
                           "geometry:\n  dimension: 2\n  dr: 0.1\n  h_over_dr: 2\n"
                           "  periodic: [x]\n  walls:\n    - type: channel\n"
                           "      lo: [0, 0]\n      hi: [1, 0.5]\n");
  const size_t nv = s.part[SPH_KIND_VERTEX].n;
  double *vol = calloc(nv, sizeof *vol);
  assert_int_equal(sph_walls_vertex_volumes(&s, 0.07, vol), 0);
  for (size_t i = 0; i < nv; i++) assert_rel(vol[i], 0.1 * 0.07, 1e-12);
  assert_int_equal(sph_walls_vertex_volumes(&s, -1.0, vol), -1);
  free(vol);
  sph_system_free(&s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_box_2d),
      cmocka_unit_test(test_box_3d),
      cmocka_unit_test(test_channel),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
