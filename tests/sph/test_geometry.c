/* Geometry from case files: generators, periodic joining, walls to particles, fluid filling
 * against an independent brute-force count (point in polygon by ray crossings, distances to every
 * wall edge), 1D/2D/3D, STL obstacle. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sabre/common.h"
#include "sabre/sph.h"
#include "testutil.h"
/* testutil.h first */
#include "sph_testfiles.h"

static void build(const char *yaml, struct sph_geometry *g, struct sph_system *s) {
  char name[256], err[512];
  snprintf(name, sizeof name, "%s", test_path("case.yaml"));
  struct cmn_case *c = cmn_case_parse(yaml, name, err, sizeof err);
  if (!c) print_error("%s\n", err);
  assert_non_null(c);
  sph_geometry_read(g, c);
  assert_int_equal(cmn_case_check_unused(c), 0);
  sph_system_from_geometry(s, g);
  cmn_case_free(c);
}

static double seg_dist(const double *p, const double *a, const double *b) {
  double dx = b[0] - a[0], dy = b[1] - a[1];
  double t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy);
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  return hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

static int inside(size_t n, const double (*q)[2], const double *p) {
  int in = 0;
  for (size_t i = 0, j = n - 1; i < n; j = i++)
    if ((q[i][1] > p[1]) != (q[j][1] > p[1]) &&
        p[0] < q[j][0] + (p[1] - q[j][1]) * (q[i][0] - q[j][0]) / (q[i][1] - q[j][1]))
      in = !in;
  return in;
}

static double poly_dist(size_t n, const double (*q)[2], const double *p) {
  double d = INFINITY;
  for (size_t i = 0; i < n; i++) d = fmin(d, seg_dist(p, q[i], q[(i + 1) % n]));
  return d;
}

static void test_box_2d(void **state) {
  (void)state;
  struct sph_geometry g;
  struct sph_system s;
  build(
      "geometry:\n  dimension: 2\n  dr: 0.1\n  walls:\n"
      "    - {type: box, lo: [0, 0], hi: [1.2, 0.7], open: [x+]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0], hi: [1.2, 0.5]}\n",
      &g, &s);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 12 * 5);
  assert_int_equal(s.part[SPH_KIND_SEGMENT].n, 2 * (12 + 7));
  assert_int_equal(s.part[SPH_KIND_VERTEX].n, 2 * (12 + 7));
  assert_rel(s.h, 0.2, 1e-15); /* default h_over_dr = 2 */
  assert_rel(g.min_wall_distance, 0.05, 1e-15);
  const struct sph_parts *ps = &s.part[SPH_KIND_SEGMENT], *pv = &s.part[SPH_KIND_VERTEX];
  int nopen = 0, ncorner = 0;
  for (size_t j = 0; j < ps->n; j++) {
    assert_rel(ps->measure[j], 0.1, 1e-12);
    if (ps->flags[j] & SPH_FLAG_OPEN) {
      nopen++;
      assert_rel(ps->x[0][j], 1.2, 1e-15);
      assert_rel(ps->normal[0][j], -1, 1e-15);
    }
  }
  for (size_t i = 0; i < pv->n; i++) ncorner += (pv->flags[i] & SPH_FLAG_CORNER) != 0;
  assert_int_equal(nopen, 7);
  assert_int_equal(ncorner, 2);
  /* A vertex at a corner has the 45° mean normal. */
  for (size_t i = 0; i < pv->n; i++)
    if (pv->x[0][i] == 0 && pv->x[1][i] == 0) {
      assert_rel(pv->normal[0][i], sqrt(0.5), 1e-15);
      assert_rel(pv->normal[1][i], sqrt(0.5), 1e-15);
    }
  sph_system_free(&s);
  sph_geometry_free(&g);
}

/* Sloping tank, obstacle with the fluid outside, fluid box overlapping the walls. */
static void test_fill_2d_polygons(void **state) {
  (void)state;
  const double tank[5][2] = {{0, 0}, {2.1, 0}, {3, 1.13}, {3, 1.5}, {0, 1.5}};
  const double obst[3][2] = {{0.61, 0.3}, {1.07, 0.33}, {0.8, 0.57}};
  struct sph_geometry g;
  struct sph_system s;
  build(
      "geometry:\n  dimension: 2\n  dr: 0.0371\n  h_over_dr: 1.7\n"
      "  min_wall_distance: 0.02\n  walls:\n"
      "    - {type: polygon, points: [[0, 0], [2.1, 0], [3, 1.13], [3, 1.5], [0, 1.5]]}\n"
      "    - type: polygon\n      points: [[0.61, 0.3], [1.07, 0.33], [0.8, 0.57]]\n"
      "      fluid: outside\n"
      "  fluid:\n    - {type: box, lo: [-0.2, -0.1], hi: [3.3, 0.8]}\n",
      &g, &s);
  const struct sph_parts *pf = &s.part[SPH_KIND_FLUID];
  /* Brute force on the same lattice. */
  double dr = 0.0371;
  size_t expected = 0;
  long nx = (long)floor(3.5 / dr + 1e-9), ny = (long)floor(0.9 / dr + 1e-9);
  for (long j = 0; j < ny; j++)
    for (long i = 0; i < nx; i++) {
      double p[2] = {-0.2 + (i + 0.5) * dr, -0.1 + (j + 0.5) * dr};
      if (inside(5, tank, p) && !inside(3, obst, p) && poly_dist(5, tank, p) >= 0.02 &&
          poly_dist(3, obst, p) >= 0.02)
        expected++;
    }
  assert_true(expected > 1000);
  assert_int_equal(pf->n, expected);
  for (size_t i = 0; i < pf->n; i++) {
    double p[2] = {pf->x[0][i], pf->x[1][i]};
    assert_true(inside(5, tank, p) && !inside(3, obst, p));
  }
  sph_system_free(&s);
  sph_geometry_free(&g);
}

/* Count of the brute-force fill of a box region [lo, hi] clipped by a closed polygon. */
static size_t brute_fill(size_t n, const double (*poly)[2], const double *lo, const double *hi,
                         double dr, double mwd) {
  size_t count = 0;
  long nx = (long)floor((hi[0] - lo[0]) / dr + 1e-9), ny = (long)floor((hi[1] - lo[1]) / dr + 1e-9);
  for (long j = 0; j < ny; j++)
    for (long i = 0; i < nx; i++) {
      double p[2] = {lo[0] + (i + 0.5) * dr, lo[1] + (j + 0.5) * dr};
      if (inside(n, poly, p) && poly_dist(n, poly, p) >= mwd - 1e-9 * dr) count++;
    }
  return count;
}

/* Backward-facing step and wedge generators: their polygons, open faces, fill. */
static void test_step_wedge(void **state) {
  (void)state;
  struct sph_geometry g;
  struct sph_system s;
  build(
      "geometry:\n  dimension: 2\n  dr: 0.05\n  walls:\n"
      "    - {type: step, lo: [0, 0], hi: [2, 0.5], step_length: 0.6, step_height: 0.15,"
      " open: [x-, x+]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0], hi: [2, 0.4]}\n",
      &g, &s);
  const double step[6][2] = {{0, 0.15}, {0.6, 0.15}, {0.6, 0}, {2, 0}, {2, 0.5}, {0, 0.5}};
  assert_int_equal(s.part[SPH_KIND_FLUID].n,
                   brute_fill(6, step, (double[]){0, 0}, (double[]){2, 0.4}, 0.05, 0.025));
  /* Perimeter 2 + 0.5 + 2 + 0.5 in segments of 0.05; open: x- (0.35 m) and x+ (0.5 m). */
  const struct sph_parts *ps = &s.part[SPH_KIND_SEGMENT];
  assert_int_equal(ps->n, 100);
  size_t nopen = 0;
  for (size_t j = 0; j < ps->n; j++) nopen += ps->flags[j] & SPH_FLAG_OPEN;
  assert_int_equal(nopen, 7 + 10);
  sph_system_free(&s);
  sph_geometry_free(&g);

  build(
      "geometry:\n  dimension: 2\n  dr: 0.02\n  walls:\n"
      "    - {type: wedge, apex: [0.5, 0.1], angle: 70, length: 0.8, direction: 80, lid: open}\n"
      "  fluid:\n    - {type: box, lo: [0, 0], hi: [1.2, 1.0]}\n",
      &g, &s);
  const double pi = 3.14159265358979323846, a1 = (80 - 35) * pi / 180, a2 = (80 + 35) * pi / 180;
  const double wedge[3][2] = {{0.5, 0.1},
                              {0.5 + 0.8 * cos(a1), 0.1 + 0.8 * sin(a1)},
                              {0.5 + 0.8 * cos(a2), 0.1 + 0.8 * sin(a2)}};
  size_t expected = brute_fill(3, wedge, (double[]){0, 0}, (double[]){1.2, 1.0}, 0.02, 0.01);
  assert_true(expected > 500);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, expected);
  /* Lid open, arms walls: 40 + 40 wall segments of 0.02 m. */
  ps = &s.part[SPH_KIND_SEGMENT];
  nopen = 0;
  for (size_t j = 0; j < ps->n; j++) nopen += ps->flags[j] & SPH_FLAG_OPEN;
  assert_int_equal(ps->n - nopen, 80);
  assert_true(nopen > 20);
  sph_system_free(&s);
  sph_geometry_free(&g);
}

/* Lattice points midway between two walls (equally near both, within the search reach) are kept:
 * a box three layers high and a cube three layers wide, filled completely. */
static void test_fill_midway(void **state) {
  (void)state;
  struct sph_geometry g;
  struct sph_system s;
  build(
      "geometry:\n  dimension: 2\n  dr: 0.1\n  walls:\n"
      "    - {type: box, lo: [0, 0], hi: [1, 0.3]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0], hi: [1, 0.3]}\n",
      &g, &s);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 30);
  sph_system_free(&s);
  sph_geometry_free(&g);
  build(
      "geometry:\n  dimension: 3\n  dr: 0.1\n  walls:\n"
      "    - {type: box, lo: [0, 0, 0], hi: [0.3, 0.3, 0.3]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0, 0], hi: [0.3, 0.3, 0.3]}\n",
      &g, &s);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 27);
  sph_system_free(&s);
  sph_geometry_free(&g);
}

/* Regions that never come near a wall: one far inside the tank is filled, one far outside is not
 * (their side comes from the nearest of all the walls). */
static void test_fill_far_regions(void **state) {
  (void)state;
  struct sph_geometry g;
  struct sph_system s;
  build(
      "geometry:\n  dimension: 2\n  dr: 0.1\n  walls:\n"
      "    - {type: wedge, apex: [0, 0], angle: 90, length: 10, direction: 90}\n"
      "  fluid:\n    - {type: box, lo: [-0.5, 4], hi: [0.5, 5]}\n"
      "    - {type: box, lo: [5, 1], hi: [6, 2]}\n",
      &g, &s);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 100);
  for (size_t i = 0; i < s.part[SPH_KIND_FLUID].n; i++)
    assert_true(s.part[SPH_KIND_FLUID].x[1][i] > 4);
  sph_system_free(&s);
  sph_geometry_free(&g);
}

/* Periodic channel: the walls close across x, the seam vertices exist once. */
static void test_channel_periodic(void **state) {
  (void)state;
  struct sph_geometry g;
  struct sph_system s;
  build(
      "geometry:\n  dimension: 2\n  dr: 0.1\n  periodic: [x]\n  walls:\n"
      "    - {type: channel, lo: [0, 0], hi: [1, 0.4]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0], hi: [1, 0.4]}\n",
      &g, &s);
  assert_int_equal(s.part[SPH_KIND_SEGMENT].n, 20);
  assert_int_equal(s.part[SPH_KIND_VERTEX].n, 20);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 40);
  assert_true(s.domain.periodic[0] && !s.domain.periodic[1]);
  /* Every segment has length dr through the seam. */
  for (size_t j = 0; j < s.part[SPH_KIND_SEGMENT].n; j++)
    assert_rel(s.part[SPH_KIND_SEGMENT].measure[j], 0.1, 1e-12);
  sph_system_free(&s);
  sph_geometry_free(&g);
}

/* 3D channel periodic in x and y: an infinite layer, floor and lid only (no y faces), closed
 * across both seams; every seam vertex exists once and every triangle has area dr²/2. */
static void test_layer_periodic_xy(void **state) {
  (void)state;
  struct sph_geometry g;
  struct sph_system s;
  build(
      "geometry:\n  dimension: 3\n  dr: 0.1\n  periodic: [x, y]\n  walls:\n"
      "    - {type: channel, lo: [0, 0, 0], hi: [1, 0.7, 0.4]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0, 0], hi: [1, 0.7, 0.4]}\n",
      &g, &s);
  const struct sph_parts *sg = &s.part[SPH_KIND_SEGMENT];
  assert_int_equal(sg->n, 2 * 2 * 10 * 7);
  assert_int_equal(s.part[SPH_KIND_VERTEX].n, 2 * 10 * 7);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 10 * 7 * 4);
  assert_true(s.domain.periodic[0] && s.domain.periodic[1] && !s.domain.periodic[2]);
  size_t up = 0;
  for (size_t j = 0; j < sg->n; j++) {
    assert_rel(sg->measure[j], 0.005, 1e-12);
    assert_rel(fabs(sg->normal[2][j]), 1, 1e-12); /* floor (+z) or lid (−z): no side walls */
    up += sg->normal[2][j] > 0;
  }
  assert_int_equal(up, sg->n / 2);
  sph_system_free(&s);
  sph_geometry_free(&g);
}

static void test_interval_1d(void **state) {
  (void)state;
  struct sph_geometry g;
  struct sph_system s;
  build(
      "geometry:\n  dimension: 1\n  dr: 0.05\n  walls:\n"
      "    - {type: interval, lo: [0.25], hi: [1.25], open: [x+]}\n"
      "  fluid:\n    - {type: box, lo: [0.25], hi: [1.0]}\n",
      &g, &s);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 15);
  assert_int_equal(s.part[SPH_KIND_SEGMENT].n, 2);
  assert_rel(s.part[SPH_KIND_SEGMENT].normal[0][1], -1, 0);
  assert_int_equal(s.part[SPH_KIND_SEGMENT].flags[1], SPH_FLAG_OPEN);
  sph_system_free(&s);
  sph_geometry_free(&g);
}

/* 3D box tank with an STL cube obstacle (fluid outside). */
static void test_fill_3d_stl(void **state) {
  (void)state;
  struct sph_mesh cube;
  sph_mesh_init(&cube, 3);
  int src = sph_mesh_add_source(&cube, "cube");
  sph_mesh_box(&cube, (double[]){0.3, 0.3, 0.1}, (double[]){0.6, 0.7, 0.45}, 0.15, 0, 0, src);
  char path[256];
  snprintf(path, sizeof path, "%s", test_path("cube.stl"));
  assert_int_equal(sph_mesh_write_stl(&cube, path, 0), 0); /* ASCII: exact doubles */
  sph_mesh_free(&cube);
  struct sph_geometry g;
  struct sph_system s;
  build(
      "geometry:\n  dimension: 3\n  dr: 0.05\n  h_over_dr: 1.3\n  walls:\n"
      "    - {type: box, lo: [0, 0, 0], hi: [1, 1, 1]}\n"
      "    - {type: stl, file: cube.stl, fluid: outside, scale: 1.0}\n"
      "  fluid:\n    - {type: box, lo: [0, 0, 0], hi: [1, 1, 0.5]}\n",
      &g, &s);
  size_t expected = 0;
  for (int k = 0; k < 10; k++)
    for (int j = 0; j < 20; j++)
      for (int i = 0; i < 20; i++) {
        double p[3] = {(i + 0.5) * 0.05, (j + 0.5) * 0.05, (k + 0.5) * 0.05};
        /* distance to the cube [0.3, 0.6] x [0.3, 0.7] x [0.1, 0.45] from outside */
        double lo[3] = {0.3, 0.3, 0.1}, hi[3] = {0.6, 0.7, 0.45}, d2 = 0;
        int in = 1;
        for (int a = 0; a < 3; a++) {
          double e = fmax(lo[a] - p[a], p[a] - hi[a]);
          if (e > 0) d2 += e * e;
          in &= e < 0;
        }
        if (!in && d2 >= 0.025 * 0.025 * (1 - 1e-9)) expected++;
      }
  assert_int_equal(s.part[SPH_KIND_FLUID].n, expected);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 4000 - 6 * 8 * 7);
  /* Box faces and cube faces meshed at ≈ dr: all triangles closed and small. */
  char msg[512];
  assert_int_equal(sph_mesh_check(&g.walls, &g.domain, msg, sizeof msg), 0);
  sph_system_free(&s);
  sph_geometry_free(&g);
}

/* An STL tank (fluid inside) filled from a region much larger than it: lattice points far outside
 * the walls take their side from their neighbours and are dropped. */
static void test_fill_3d_stl_tank(void **state) {
  (void)state;
  struct sph_mesh tank;
  sph_mesh_init(&tank, 3);
  sph_mesh_box(&tank, (double[]){0, 0, 0}, (double[]){0.6, 0.5, 0.4}, 0.6, 0, 0,
               sph_mesh_add_source(&tank, "tank"));
  char path[256];
  snprintf(path, sizeof path, "%s", test_path("tank.stl"));
  assert_int_equal(sph_mesh_write_stl(&tank, path, 0), 0);
  sph_mesh_free(&tank);
  struct sph_geometry g;
  struct sph_system s;
  build(
      "geometry:\n  dimension: 3\n  dr: 0.05\n  walls:\n"
      "    - {type: stl, file: tank.stl}\n"
      "  fluid:\n    - {type: box, lo: [-0.4, -0.4, -0.4], hi: [1.0, 1.0, 1.0]}\n",
      &g, &s);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 12 * 10 * 8);
  for (size_t i = 0; i < s.part[SPH_KIND_FLUID].n; i++)
    for (int a = 0; a < 3; a++) {
      double x = s.part[SPH_KIND_FLUID].x[a][i];
      assert_true(x > 0 && x < 0.6);
    }
  sph_system_free(&s);
  sph_geometry_free(&g);
}

/* geometry.first_row: the lattice lo + (i + first_row) dr. With 1 the first row lies dr from
 * walls on a region's faces at both ends (the point on the hi face is dropped, being on the
 * wall), and a periodic direction keeps n evenly spaced columns. 2D tank, 2D channel, 3D tank. */
static void check_first_row(const struct sph_system *s, int dim, const double *lo_wall,
                            const double *hi_wall, const int *walled, double dr) {
  const struct sph_parts *pf = &s->part[SPH_KIND_FLUID];
  for (int a = 0; a < dim; a++) {
    double mn = INFINITY, mx = -INFINITY;
    for (size_t i = 0; i < pf->n; i++) {
      mn = fmin(mn, pf->x[a][i]);
      mx = fmax(mx, pf->x[a][i]);
    }
    assert_rel(mn - lo_wall[a], dr, 1e-9);
    if (walled[a]) assert_rel(hi_wall[a] - mx, dr, 1e-9);
  }
}

static void test_fill_first_row(void **state) {
  (void)state;
  struct sph_geometry g;
  struct sph_system s;
  /* 2D tank: x in [0, 1.2] (walls at both ends), y from the floor to the region's top 0.5. */
  build(
      "geometry:\n  dimension: 2\n  dr: 0.1\n  first_row: 1\n  walls:\n"
      "    - {type: box, lo: [0, 0], hi: [1.2, 0.7]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0], hi: [1.2, 0.5]}\n",
      &g, &s);
  assert_rel(g.first_row, 1.0, 1e-15);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 11 * 5);
  const double lo2[3] = {0, 0, 0}, hi2[3] = {1.2, 0.7, 0};
  check_first_row(&s, 2, lo2, hi2, (const int[]){1, 0, 0}, 0.1);
  double ymax = 0;
  for (size_t i = 0; i < s.part[SPH_KIND_FLUID].n; i++)
    ymax = fmax(ymax, s.part[SPH_KIND_FLUID].x[1][i]);
  assert_rel(ymax, 0.5, 1e-12); /* the top row on the region's (wall-free) hi face */
  sph_system_free(&s);
  sph_geometry_free(&g);
  /* The default is the midpoint lattice, dr/2 from the walls. */
  build(
      "geometry:\n  dimension: 2\n  dr: 0.1\n  walls:\n"
      "    - {type: box, lo: [0, 0], hi: [1.2, 0.7]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0], hi: [1.2, 0.5]}\n",
      &g, &s);
  assert_rel(g.first_row, 0.5, 1e-15);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 12 * 5);
  check_first_row(&s, 2, lo2, hi2, (const int[]){0, 0, 0}, 0.05);
  sph_system_free(&s);
  sph_geometry_free(&g);
  /* Channel periodic in x over 1.3 = 13 dr: 13 evenly spaced columns, the last on the period. */
  build(
      "geometry:\n  dimension: 2\n  dr: 0.1\n  first_row: 1\n  periodic: [x]\n  walls:\n"
      "    - {type: channel, lo: [0, 0], hi: [1.3, 0.6]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0], hi: [1.3, 0.6]}\n",
      &g, &s);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 13 * 5);
  const double hic[3] = {1.3, 0.6, 0};
  check_first_row(&s, 2, lo2, hic, (const int[]){0, 1, 0}, 0.1);
  sph_system_free(&s);
  sph_geometry_free(&g);
  /* 3D tank 0.5 × 0.4 × 0.6 at dr = 0.05, fluid up to z = 0.3. */
  build(
      "geometry:\n  dimension: 3\n  dr: 0.05\n  h_over_dr: 1.3\n  first_row: 1\n  walls:\n"
      "    - {type: box, lo: [0, 0, 0], hi: [0.5, 0.4, 0.6]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0, 0], hi: [0.5, 0.4, 0.3]}\n",
      &g, &s);
  assert_int_equal(s.part[SPH_KIND_FLUID].n, 9 * 7 * 6);
  const double hi3[3] = {0.5, 0.4, 0.6};
  check_first_row(&s, 3, lo2, hi3, (const int[]){1, 1, 0}, 0.05);
  sph_system_free(&s);
  sph_geometry_free(&g);
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_box_2d),           cmocka_unit_test(test_fill_2d_polygons),
      cmocka_unit_test(test_channel_periodic), cmocka_unit_test(test_layer_periodic_xy),
      cmocka_unit_test(test_step_wedge),       cmocka_unit_test(test_fill_far_regions),
      cmocka_unit_test(test_fill_midway),      cmocka_unit_test(test_interval_1d),
      cmocka_unit_test(test_fill_3d_stl),      cmocka_unit_test(test_fill_3d_stl_tank),
      cmocka_unit_test(test_fill_first_row)};
  return cmocka_run_group_tests(tests, test_dir_setup, test_dir_teardown);
}
