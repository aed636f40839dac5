/* γ and ∇γ do not depend on how a flat wall is cut into segments: the same wall meshed by the
 * generators at several Δr, and cut at random points (2D) or by random conforming bisections
 * (3D), gives the same values at points near it, on it (at cut points and between them) and in
 * its corners, to round-off. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/sph.h"
#include "sabre/sph_walls.h"
#include "testutil.h"

static struct sph_wall_element *elements(const struct sph_mesh *m) {
  struct sph_wall_element *e = calloc(m->nelem + 1, sizeof *e);
  for (size_t i = 0; i < m->nelem; i++) {
    for (int k = 0; k < m->dim; k++) memcpy(e[i].x[k], m->vert[m->elem[i][k]], sizeof e[i].x[k]);
    memcpy(e[i].normal, m->normal[i], sizeof e[i].normal);
  }
  return e;
}

static void eval(const struct sph_kernel *k, const struct sph_mesh *m, const double *a, double *g,
                 double *grad) {
  struct sph_wall_element *e = elements(m);
  assert_int_equal(sph_gamma_eval(k, a, m->nelem, e, g, grad), 0);
  free(e);
}

/* 2D: the floor and walls of a tank [0, 2.3] x [0, 1.7] meshed as (a) the generator's polygon
 * refined at several dr, (b) the floor cut at random abscissae. */
static void test_cut_2d(void **state) {
  (void)state;
  struct sph_kernel k;
  assert_int_equal(sph_kernel_init(&k, 2, 0.173), 0);
  const double lo[2] = {0, 0}, hi[2] = {2.3, 1.7};
  struct sph_mesh ref;
  sph_mesh_init(&ref, 2);
  sph_mesh_box(&ref, lo, hi, 0, 0, 0, sph_mesh_add_source(&ref, "box")); /* 4 segments */
  struct sph_mesh cuts[4];
  const double drs[3] = {0.05, 0.0913, 0.31};
  for (int c = 0; c < 3; c++) {
    sph_mesh_init(&cuts[c], 2);
    sph_mesh_box(&cuts[c], lo, hi, 0, 0, 0, sph_mesh_add_source(&cuts[c], "box"));
    sph_mesh_refine(&cuts[c], drs[c]);
  }
  /* Random cuts of the floor; the other three sides as single segments. */
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 17);
  struct sph_mesh *r = &cuts[3];
  sph_mesh_init(r, 2);
  int src = sph_mesh_add_source(r, "random");
  double xs[40];
  xs[0] = 0;
  for (int i = 1; i < 39; i++) xs[i] = xs[i - 1] + sabre_rng_uniform(&rng, 0.01, 0.1);
  for (int i = 1; i < 39; i++) xs[i] *= 2.3 / (xs[38] + 0.05);
  xs[39] = 2.3;
  size_t prev = sph_mesh_add_vertex(r, (double[]){0, 0, 0}), first = prev;
  for (int i = 1; i < 40; i++) {
    size_t v = sph_mesh_add_vertex(r, (double[]){xs[i], 0, 0});
    sph_mesh_add_element(r, (size_t[]){prev, v, 0}, 0, 0, src, i);
    prev = v;
  }
  size_t c1 = sph_mesh_add_vertex(r, (double[]){2.3, 1.7, 0});
  size_t c2 = sph_mesh_add_vertex(r, (double[]){0, 1.7, 0});
  sph_mesh_add_element(r, (size_t[]){prev, c1, 0}, 0, 0, src, 40);
  sph_mesh_add_element(r, (size_t[]){c1, c2, 0}, 0, 0, src, 41);
  sph_mesh_add_element(r, (size_t[]){c2, first, 0}, 0, 0, src, 42);
  char msg[256];
  assert_int_equal(sph_mesh_check(r, NULL, msg, sizeof msg), 0);

  double pts[][2] = {{1.137, 0.0412}, {0.8, 0.2},    {1.5, 0.3001}, {0.1, 0.07}, {0.05, 0.0},
                     {xs[7], 0.0},    {xs[21], 0.0}, {0.0, 0.0},    {2.3, 0.11}, {1.3, 1.6321}};
  int nonflat = 0;
  for (size_t p = 0; p < sizeof pts / sizeof pts[0]; p++) {
    double a[3] = {pts[p][0], pts[p][1], 0}, g0, grad0[3];
    eval(&k, &ref, a, &g0, grad0);
    nonflat += g0 < 1 - 1e-9;
    for (int c = 0; c < 4; c++) {
      double g, grad[3];
      eval(&k, &cuts[c], a, &g, grad);
      assert_abs(g, g0, 1e-13);
      assert_abs(grad[0], grad0[0], 1e-12);
      assert_abs(grad[1], grad0[1], 1e-12);
    }
  }
  assert_int_equal(nonflat, 10); /* every point is within the support of a wall */
  for (int c = 0; c < 4; c++) sph_mesh_free(&cuts[c]);
  sph_mesh_free(&ref);
}

/* 3D: a box [0, 1.1] x [0, 0.9] x [0, 0.7] meshed at several dr and refined by bisection. */
static void check_cut_3d(size_t npts, const double (*pts)[3]) {
  struct sph_kernel k;
  assert_int_equal(sph_kernel_init(&k, 3, 0.117), 0);
  const double lo[3] = {0, 0, 0}, hi[3] = {1.1, 0.9, 0.7};
  struct sph_mesh m[4];
  const double drs[4] = {5.0, 0.3, 0.137, 0.0611};
  for (int c = 0; c < 4; c++) {
    sph_mesh_init(&m[c], 3);
    sph_mesh_box(&m[c], lo, hi, drs[c], 0, 0, sph_mesh_add_source(&m[c], "box"));
    if (c == 3) sph_mesh_refine(&m[c], 0.043); /* bisection on top of the grid */
  }
  assert_int_equal(m[0].nelem, 12);
  assert_true(m[3].nelem > 4 * m[2].nelem);
  for (size_t p = 0; p < npts; p++) {
    double g0, grad0[3];
    eval(&k, &m[0], pts[p], &g0, grad0);
    for (int c = 1; c < 4; c++) {
      double g, grad[3];
      eval(&k, &m[c], pts[p], &g, grad);
      if (fabs(g - g0) > 1e-12) print_error("point %zu, mesh %d\n", p, c);
      assert_abs(g, g0, 1e-12);
      for (int a = 0; a < 3; a++) assert_abs(grad[a], grad0[a], 1e-10);
    }
  }
  for (int c = 0; c < 4; c++) sph_mesh_free(&m[c]);
}

static void test_cut_3d(void **state) {
  (void)state;
  const double pts[][3] = {{0.55, 0.4123, 0.0731}, {0.123, 0.2, 0.1},  {0.5, 0.05, 0.03},
                           {0.31, 0.4, 0.0},       {0.0, 0.0, 0.0},    {1.1, 0.45, 0.2},
                           {0.55, 0.9, 0.7},       {0.6, 0.6, 0.6517}, {0.3, 0.3, 0.3}};
  check_cut_3d(sizeof pts / sizeof pts[0], pts);
}

/* The foot of the point on the floor lies on the diagonal of the coarsest mesh's floor. */
static void test_cut_3d_foot_on_edge(void **state) {
  (void)state;
  const double pts[][3] = {{0.55, 0.45, 0.0731}};
  check_cut_3d(1, pts);
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_cut_2d), cmocka_unit_test(test_cut_3d),
                                     cmocka_unit_test(test_cut_3d_foot_on_edge)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
