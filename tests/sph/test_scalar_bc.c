/*
 * Scalar mode: the boundary values behind the wall term of M(18) (sabre/sph_scalar.h).
 *
 * - Robin/Neumann vertex values are those of sph_robin_vertex_value() (M 64–74) on the vertex's
 *   fluid neighbours, and exact for a polynomial of degree ≤ m satisfying the condition;
 *   the segment flux is ∂u/∂n|_s = (μ3 − μ1 u_s)/μ2, M(65), passed as 2 ∂u/∂n to the Laplacian.
 * - Dirichlet: u_v = g and ∂u/∂n from the one-sided fit, exact for degree ≤ m.
 * - Every failure comes back with the vertex: too few distances (ETOOFEW), bad parameters
 *   (EINVAL), and a step stops with a message naming the vertex.
 * - 2D box: vertex values of a linear field with Neumann data per wall, and its Laplacian.
 */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_scalar.h"
#include "solver_fixture.h"
#include "testutil.h"

/* [0, 1] with walls at both ends, fluid at lo + (i + 1/2) Δr in [off Δr, 1 − off Δr]. */
static void make_1d(struct sph_system *s, double dr, double h_over_dr, double off) {
  char text[1024];
  snprintf(text, sizeof text,
           "geometry:\n  dimension: 1\n  dr: %.17g\n  h_over_dr: %.17g\n"
           "  walls:\n    - {type: interval, lo: [0], hi: [1]}\n"
           "  fluid:\n    - {type: box, lo: [%.17g], hi: [%.17g]}\n",
           dr, h_over_dr, off * dr, 1.0 - off * dr);
  fixture_system_from_yaml(s, text);
}

static void setup_1d(struct sph_scalar *sc, double dr, double h_over_dr, double off,
                     const struct sph_scalar_bc bc[2]) {
  struct sph_system s;
  make_1d(&s, dr, h_over_dr, off);
  const int seg_bc[2] = {0, 1};
  sph_scalar_init(sc, &s, 1.0, -1.0, 2, bc, seg_bc);
  sph_system_free(&s);
}

static struct sph_scalar_bc robin(double mu1, double mu2, double mu3, int m) {
  struct sph_scalar_bc bc;
  sph_scalar_bc_init(&bc);
  bc.robin.mu1 = mu1;
  bc.robin.mu2 = mu2;
  bc.robin.mu3 = mu3;
  bc.robin.m = m;
  return bc;
}

/* Left: A(1 + x) + D x² (du/dn = u at x = 0); right, y = 1 − x: E(1 + y) + G y² (du/dn = u). */
static double field(double x, double A, double D, double E, double G) {
  if (x < 0.5) return A * (1 + x) + D * x * x;
  const double y = 1.0 - x;
  return E * (1 + y) + G * y * y;
}

static void set_field(struct sph_scalar *sc, double A, double D, double E, double G) {
  const struct sph_parts *f = &sc->sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < f->n; a++) sc->u[SPH_KIND_FLUID][a] = field(f->x[0][a], A, D, E, G);
}

/* The values equal sph_robin_vertex_value() over the fluid within 2h, and are exact. */
static void test_robin_values(void **state) {
  (void)state;
  const double A = 2.385, D = -1.7, E = -0.93, G = 3.1;
  for (int off2 = 0; off2 < 2; off2++)
    for (int m = 1; m <= 3; m++) {
      const struct sph_scalar_bc bc[2] = {robin(-1.0, 1.0, 0.0, m), robin(-1.0, 1.0, 0.0, m)};
      struct sph_scalar sc;
      setup_1d(&sc, 0.01, 2.0, 0.5 * off2, bc);
      set_field(&sc, A, m >= 2 ? D : 0.0, E, m >= 2 ? G : 0.0);
      long bad = 99;
      assert_int_equal(sph_scalar_boundary_values(&sc, &bad), SPH_ROBIN_SUCCESS);
      assert_int_equal(bad, -1);
      const struct sph_parts *f = &sc.sys.part[SPH_KIND_FLUID], *v = &sc.sys.part[SPH_KIND_VERTEX];
      for (size_t i = 0; i < 2; i++) {
        /* brute-force neighbours */
        size_t n = 0;
        double(*x)[3] = calloc(f->n, sizeof *x);
        double *fv = calloc(f->n, sizeof *fv), *vol = calloc(f->n, sizeof *vol),
               *w = calloc(f->n, sizeof *w);
        for (size_t a = 0; a < f->n; a++) {
          const double r = fabs(f->x[0][a] - v->x[0][i]);
          if (r >= 2.0 * sc.sys.h) continue;
          x[n][0] = f->x[0][a];
          fv[n] = sc.u[SPH_KIND_FLUID][a];
          vol[n] = f->mass[a] / f->rho[a];
          w[n++] = sph_kernel_w(&sc.kernel, r);
        }
        const double xv[3] = {v->x[0][i], 0.0, 0.0}, nv[3] = {v->normal[0][i], 0.0, 0.0};
        struct sph_robin_ws ws;
        double ref;
        assert_int_equal(sph_robin_vertex_value(&sc.bc[i].robin, 1, xv, nv, n,
                                                (const double(*)[3])x, fv, vol, w, NULL, &ws, &ref),
                         SPH_ROBIN_SUCCESS);
        free(x);
        free(fv);
        free(vol);
        free(w);
        assert_rel(sc.u[SPH_KIND_VERTEX][i], ref, 1e-13);
        assert_rel(sc.u[SPH_KIND_VERTEX][i], i == 0 ? A : E, 1e-11); /* exact */
        /* Robin flux, M(65): du/dn = u at the segment */
        assert_rel(sc.dudn[SPH_KIND_SEGMENT][i], sc.u[SPH_KIND_SEGMENT][i], 1e-15);
        assert_rel(sc.u[SPH_KIND_SEGMENT][i], sc.u[SPH_KIND_VERTEX][i], 1e-15);
      }
      /* the wall term handed to sph_op_lap: 2 du/dn of the segment, per fluid–segment pair */
      const struct sph_nlist *fs = &sc.nb.list[SPH_KIND_SEGMENT];
      size_t pairs = 0;
      for (size_t a = 0; a < fs->n; a++)
        for (size_t q = fs->offset[a]; q < fs->offset[a + 1]; q++, pairs++)
          assert_rel(sc.flux[q], 2.0 * sc.u[SPH_KIND_SEGMENT][fs->index[q]], 1e-15);
      assert_true(pairs >= 4);
      /* m = 1 is not exact for a quadratic: the difference the paper's Fig. 7 is about */
      if (m == 1) {
        set_field(&sc, A, D, E, G);
        assert_int_equal(sph_scalar_boundary_values(&sc, NULL), SPH_ROBIN_SUCCESS);
        assert_true(fabs(sc.u[SPH_KIND_VERTEX][0] - A) > 1e-5);
      }
      sph_scalar_free(&sc);
    }
}

/* Dirichlet: value imposed, ∂u/∂n exact for degree ≤ m; Laplacian of a linear field near it. */
static void test_dirichlet(void **state) {
  (void)state;
  for (int m = 1; m <= 2; m++) {
    struct sph_scalar_bc bc[2];
    sph_scalar_bc_init(&bc[0]);
    sph_scalar_bc_init(&bc[1]);
    bc[0].type = bc[1].type = SPH_SCALAR_DIRICHLET;
    bc[0].order = bc[1].order = m;
    bc[0].value = 0.7;
    bc[1].value = 0.7 + 1.3 + (m == 2 ? 0.9 : 0.0);
    struct sph_scalar sc;
    setup_1d(&sc, 0.01, 2.0, 0.5, bc);
    const struct sph_parts *f = &sc.sys.part[SPH_KIND_FLUID];
    for (size_t a = 0; a < f->n; a++) {
      const double x = f->x[0][a];
      sc.u[SPH_KIND_FLUID][a] = 0.7 + 1.3 * x + (m == 2 ? 0.9 * x * x : 0.0);
    }
    assert_int_equal(sph_scalar_laplacian(&sc, NULL), SPH_ROBIN_SUCCESS);
    assert_rel(sc.u[SPH_KIND_VERTEX][0], 0.7, 1e-15);
    assert_rel(sc.u[SPH_KIND_VERTEX][1], bc[1].value, 1e-15);
    assert_rel(sc.dudn[SPH_KIND_VERTEX][0], 1.3, 1e-11);
    assert_rel(sc.dudn[SPH_KIND_VERTEX][1], -(1.3 + (m == 2 ? 1.8 : 0.0)), 1e-11);
    assert_rel(sc.dudn[SPH_KIND_SEGMENT][0], 1.3, 1e-11);
    if (m == 1) { /* linear: the Laplacian error next to the wall is the quadrature error */
      double emax = 0.0;
      for (size_t a = 0; a < f->n; a++) emax = fmax(emax, fabs(sc.lap[a]) * sc.sys.h / 1.3);
      printf("Dirichlet, linear field: max |Lap| h/|u'| = %.3e\n", emax);
      assert_true(emax < 0.05);
    }
    sph_scalar_free(&sc);
  }
}

/* Every failure names its vertex. */
static void test_errors(void **state) {
  (void)state;
  /* h = 1.3 Δr, fluid from Δr: two distances within 2h = 2.6 Δr, so m = 3 is undetermined */
  struct sph_scalar_bc bc[2] = {robin(0.0, 1.0, 0.0, 1), robin(-1.0, 1.0, 0.0, 3)};
  struct sph_scalar sc;
  setup_1d(&sc, 0.01, 1.3, 0.5, bc);
  long bad = -7;
  assert_int_equal(sph_scalar_laplacian(&sc, &bad), SPH_ROBIN_ETOOFEW);
  assert_int_equal(bad, 1);
  char msg[512];
  assert_int_equal(sph_scalar_step(&sc, 1e-3, msg, sizeof msg), -1);
  printf("%s\n", msg);
  assert_non_null(strstr(msg, "vertex 1 at (1, 0, 0), boundary group 1"));
  assert_non_null(strstr(msg, "SPH_ROBIN_ETOOFEW"));
  sc.bc[1].robin.m = 2; /* two distances: fine */
  assert_int_equal(sph_scalar_laplacian(&sc, &bad), SPH_ROBIN_SUCCESS);
  assert_int_equal(bad, -1);
  sc.bc[1].robin.mu2 = 0.0; /* Dirichlet is not a Robin condition */
  assert_int_equal(sph_scalar_boundary_values(&sc, &bad), SPH_ROBIN_EINVAL);
  assert_int_equal(bad, 1);
  sc.bc[1].robin.mu2 = 1.0;
  sc.bc[0].type = SPH_SCALAR_DIRICHLET;
  sc.bc[0].order = 3;
  assert_int_equal(sph_scalar_boundary_values(&sc, &bad), SPH_ROBIN_ETOOFEW);
  assert_int_equal(bad, 0);
  sc.bc[0].order = 2;
  assert_int_equal(sph_scalar_boundary_values(&sc, &bad), SPH_ROBIN_SUCCESS);
  /* a non-finite u stops the step */
  sabre_fp_traps_off();
  sc.lap[5] = INFINITY;
  assert_int_equal(sph_scalar_step(&sc, 1e-3, msg, sizeof msg), -1);
  printf("%s\n", msg);
  assert_non_null(strstr(msg, "u_t = inf at fluid particle"));
  sabre_fp_traps_on();
  sph_scalar_free(&sc);
}

/* 2D box [0, 1]², Δr = 0.05, h = 2Δr, u = 1.3 + 0.4x + 0.7y with the Neumann data of each wall
 * (elements 1 bottom, 2 right, 3 top, 4 left: ∂u/∂n = 0.7, −0.4, −0.7, 0.4). Vertex values are
 * exact where the neighbourhood is symmetric along the wall (≥ 2h from the corners: the fit is
 * one-dimensional along the normal, M §6.1, and the tangential slope cancels); the Laplacian
 * vanishes to round-off in the interior and within the quadrature error next to the walls. */
static void test_box_2d(void **state) {
  (void)state;
  const char *text =
      "geometry:\n  dimension: 2\n  dr: 0.05\n  h_over_dr: 2\n"
      "  walls:\n    - {type: box, lo: [0, 0], hi: [1, 1]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0], hi: [1, 1]}\n";
  char err[512];
  struct cmn_case *c = cmn_case_parse(text, "test.yaml", err, sizeof err);
  assert_non_null(c);
  struct sph_geometry g;
  sph_geometry_read(&g, c);
  struct sph_system s;
  sph_system_from_geometry(&s, &g);
  int *seg_bc = malloc(g.walls.nelem * sizeof *seg_bc);
  for (size_t e = 0; e < g.walls.nelem; e++) seg_bc[e] = (int)g.walls.source_index[e] - 1;
  const double grad[4] = {0.7, -0.4, -0.7, 0.4};
  struct sph_scalar_bc bc[4];
  for (int k = 0; k < 4; k++) bc[k] = robin(0.0, 1.0, grad[k], 1);
  struct sph_scalar sc;
  sph_scalar_init(&sc, &s, 1.0, -1.0, 4, bc, seg_bc);
  free(seg_bc);
  sph_system_free(&s);
  sph_geometry_free(&g);
  cmn_case_free(c);
  assert_abs(sc.phi, 0.0, 1e-9);
  const struct sph_parts *f = &sc.sys.part[SPH_KIND_FLUID], *v = &sc.sys.part[SPH_KIND_VERTEX];
  for (size_t a = 0; a < f->n; a++)
    sc.u[SPH_KIND_FLUID][a] = 1.3 + 0.4 * f->x[0][a] + 0.7 * f->x[1][a];
  assert_int_equal(sph_scalar_laplacian(&sc, NULL), SPH_ROBIN_SUCCESS);
  size_t checked = 0;
  double e_edge = 0.0;
  for (size_t i = 0; i < v->n; i++) {
    const double x = v->x[0][i], y = v->x[1][i];
    const double along = (x == 0.0 || x == 1.0) ? y : x; /* position along its wall */
    const double exact = 1.3 + 0.4 * x + 0.7 * y;
    if (along < 0.2 - 1e-9 || along > 0.8 + 1e-9) {
      /* the neighbourhood is lopsided along the wall: the 1D fit sees the tangential slope */
      e_edge = fmax(e_edge, fabs(sc.u[SPH_KIND_VERTEX][i] - exact));
      continue;
    }
    assert_rel(sc.u[SPH_KIND_VERTEX][i], exact, 1e-12);
    checked++;
  }
  assert_int_equal(checked, 4 * 13);
  printf("2D box: vertex values within 2h of a corner off by up to %.3e (|grad u| h = %.3e)\n",
         e_edge, hypot(0.4, 0.7) * sc.sys.h);
  assert_true(e_edge < 0.5 * hypot(0.4, 0.7) * sc.sys.h);
  const double h = sc.sys.h, gnorm = hypot(0.4, 0.7);
  double e_in = 0.0, e_wall = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    const double x = f->x[0][a], y = f->x[1][a];
    const double dx = fmin(x, 1 - x), dy = fmin(y, 1 - y);
    const double e = fabs(sc.lap[a]) * h / gnorm;
    if (dx > 2 * h && dy > 2 * h)
      e_in = fmax(e_in, e);
    else if (dx > 2 * h || dy > 2 * h) /* next to one wall, away from the corners */
      e_wall = fmax(e_wall, e);
  }
  printf("2D box, linear field: max |Lap| h/|grad u|: interior %.3e, next to one wall %.3e\n", e_in,
         e_wall);
  assert_true(e_in < 1e-10);
  assert_true(e_wall < 0.05);
  /* the same with the naive O(N²) neighbour search (the lists are in another order) */
  double *lap = malloc(f->n * sizeof *lap);
  memcpy(lap, sc.lap, f->n * sizeof *lap);
  sph_nbrs_build_naive(&sc.nb, &sc.sys, 0.0);
  sph_nbrs_gamma(&sc.nb, &sc.sys, &sc.kernel);
  assert_int_equal(sph_scalar_laplacian(&sc, NULL), SPH_ROBIN_SUCCESS);
  for (size_t a = 0; a < f->n; a++) assert_abs(sc.lap[a], lap[a], 1e-12 * gnorm / h);
  free(lap);
  sph_scalar_free(&sc);
}

int main(void) {
  gsl_set_error_handler_off();
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_robin_values),
      cmocka_unit_test(test_dirichlet),
      cmocka_unit_test(test_errors),
      cmocka_unit_test(test_box_2d),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
