/*
 * Least-squares vertex values M(64–74) through the solver (docs/sph-robin.md §5):
 * - m = 1 equals the Shepard path M(16–17): Neumann without gravity against Shepard without
 *   correction (M 82), and with gravity and M(83) (no gravity flux) against Shepard with the
 *   tangential correction, on a perturbed tank, to round-off — vertex pressures and accelerations;
 * - a hydrostatic tank: M(83) with ∂p/∂n = ρ g·n gives the exact wall pressure for m = 1, 2, 3,
 *   (to 2e-5 ρ0 g H: the Tait column is not quite linear), including the vertex at the free-surface
 *   corner, where M(82) is off by 5 % of ρ0 g H (M Fig. 9);
 * - too few distinct distances for the order stops the step with the vertex's id and position;
 *   too_few = lower lowers the order instead;
 * - wall groups: vertices take the group of their first segment;
 * - the case-file section vertex_values and imposed_flux, with errors.
 */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_robin.h"
#include "solver_fixture.h"
#include "testutil.h"

enum { NX = 19, NY = 10 };
static const double DR = 0.01, H = 0.105; /* rows at y = dr ... 0.1, surface dr/2 above */

/* fixture_tank (0.2 m × 0.2 m, NX × NY fluid particles) with its segments' edge numbers. */
static void tank(struct sph_solver *sv, const struct sph_config *cfg) {
  struct sph_system s;
  fixture_tank(&s, 0.2, 0.2, DR, NX, NY);
  const struct sph_parts *sg = &s.part[SPH_KIND_SEGMENT];
  int *wall = calloc(sg->n + 1, sizeof *wall);
  long *edge = calloc(sg->n + 1, sizeof *edge);
  for (size_t j = 0; j < sg->n; j++) {
    const double nx = sg->normal[0][j], ny = sg->normal[1][j];
    edge[j] = ny > 0.5 ? 1 : nx < -0.5 ? 2 : ny < -0.5 ? 3 : 4;
  }
  sph_solver_init(sv, cfg, &s, wall, edge);
  free(wall);
  free(edge);
  sph_system_free(&s);
}

static void tank_config(struct sph_config *cfg, int gravity) {
  fixture_config(cfg);
  if (gravity) {
    cfg->gravity[1] = -9.81;
    cfg->hydrostatic = 1;
    cfg->free_surface = H;
  }
  cfg->vertex_bc.method = SPH_VVALUES_SHEPARD;
  cfg->vertex_bc.order = 1;
  cfg->vertex_bc.mu[1] = 1.0;
  cfg->vertex_bc.gravity_flux = 1;
  cfg->vertex_bc.tangential = 1;
  cfg->vertex_bc.wall = -1;
}

/* Random but reproducible departure from rest: positions ±0.1 Δr, densities ±0.5 %. */
static void perturb(struct sph_solver *sv, uint64_t seed) {
  struct sabre_rng rng;
  sabre_rng_seed(&rng, seed);
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < f->n; a++) {
    for (int c = 0; c < 2; c++) f->x[c][a] += sabre_rng_uniform(&rng, -0.1, 0.1) * DR;
    f->rho[a] *= 1.0 + sabre_rng_uniform(&rng, -5e-3, 5e-3);
  }
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
}

/* Largest difference of vertex pressures and of accelerations, relative to their scales. */
static void compare(const struct sph_solver *a, const struct sph_solver *b, double *dp,
                    double *dacc) {
  const struct sph_parts *va = &a->sys.part[SPH_KIND_VERTEX], *vb = &b->sys.part[SPH_KIND_VERTEX];
  double pmax = 0.0, amax = 0.0;
  *dp = *dacc = 0.0;
  for (size_t i = 0; i < va->n; i++) {
    pmax = fmax(pmax, fabs(va->p[i]));
    *dp = fmax(*dp, fabs(va->p[i] - vb->p[i]));
  }
  for (size_t i = 0; i < a->sys.part[SPH_KIND_FLUID].n; i++)
    for (int c = 0; c < 2; c++) {
      amax = fmax(amax, fabs(a->acc[c][i]));
      *dacc = fmax(*dacc, fabs(a->acc[c][i] - b->acc[c][i]));
    }
  *dp /= pmax;
  *dacc /= amax;
}

static void test_m1_is_shepard(void **state) {
  (void)state;
  sabre_fp_traps_on();
  for (int gravity = 0; gravity <= 1; gravity++) {
    struct sph_config cs, cr;
    tank_config(&cs, gravity);
    tank_config(&cr, gravity);
    /* without gravity: Shepard without correction = Neumann m = 1, M(82);
     * with gravity: Shepard with the tangential correction = m = 1, M(83), μ3 = 0 */
    cs.vertex_hydro = gravity ? SPH_VHYDRO_TANGENTIAL : SPH_VHYDRO_NONE;
    cr.vertex_bc.method = SPH_VVALUES_ROBIN;
    cr.vertex_bc.tangential = gravity;
    cr.vertex_bc.gravity_flux = 0;
    struct sph_solver a, b;
    tank(&a, &cs);
    tank(&b, &cr);
    assert_rel(a.vertex_phi, b.vertex_phi, 1e-12);
    perturb(&a, 71 + (uint64_t)gravity);
    perturb(&b, 71 + (uint64_t)gravity);
    assert_true(a.vertex_fail < 0 && b.vertex_fail < 0);
    double dp, dacc;
    compare(&a, &b, &dp, &dacc);
    print_message("m = 1 vs Shepard (%s): vertex p %.2e, acceleration %.2e (relative)\n",
                  gravity ? "gravity, M(83)" : "no gravity, M(82)", dp, dacc);
    assert_true(dp < 1e-12 && dacc < 1e-11);
    sph_solver_free(&a);
    sph_solver_free(&b);
  }
}

/* Exact Tait hydrostatic pressure at depth d (as the solver's initial state). */
static double p_exact(const struct sph_solver *sv, double d) {
  const struct rmn_eos *e = &sv->eos;
  const double c2 = e->c0 * e->c0;
  return e->b * expm1(e->xi / (e->xi - 1.0) * log1p((e->xi - 1.0) * 9.81 * d / c2));
}

/* Worst wall-pressure error over the wetted wall vertices (y ≤ H) and at the free-surface corner,
 * relative to ρ0 g H. */
static void wall_error(const struct sph_solver *sv, double *worst, double *corner) {
  const struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  *worst = *corner = 0.0;
  const double scale = 1000.0 * 9.81 * H;
  for (size_t i = 0; i < v->n; i++) {
    const double x = v->x[0][i], y = v->x[1][i];
    if (y > H) continue;
    const double err = fabs(v->p[i] - p_exact(sv, H - y)) / scale;
    *worst = fmax(*worst, err);
    if (fabs(y - NY * DR) < 1e-9 && (x < 1e-9 || x > 0.2 - 1e-9)) *corner = fmax(*corner, err);
  }
}

static void test_hydrostatic_tank(void **state) {
  (void)state;
  sabre_fp_traps_on();
  double corner82 = 0.0;
  for (int m = 1; m <= 3; m++)
    for (int tangential = 1; tangential >= 0; tangential--) {
      struct sph_config cfg;
      tank_config(&cfg, 1);
      cfg.vertex_bc.method = SPH_VVALUES_ROBIN;
      cfg.vertex_bc.order = m;
      cfg.vertex_bc.tangential = tangential;
      /* vertices above the surface see only 2 distinct distances within 2h */
      cfg.vertex_bc.too_few = m > 2 ? SPH_VTOOFEW_LOWER : SPH_VTOOFEW_ERROR;
      struct sph_solver sv;
      tank(&sv, &cfg);
      assert_true(sv.vertex_fail < 0);
      double worst, corner;
      wall_error(&sv, &worst, &corner);
      print_message(
          "hydrostatic tank, m = %d, %s: worst wall error %.2e rho0 g H, free-surface "
          "corner %.2e\n",
          m, tangential ? "M(83)" : "M(82)", worst, corner);
      if (tangential)
        assert_true(worst < 2e-4);
      else
        corner82 = fmax(corner82, corner);
      if (!tangential) assert_true(corner > 0.03);
      sph_solver_free(&sv);
    }
  assert_true(corner82 > 0.03);
}

static void test_too_few(void **state) {
  (void)state;
  sabre_fp_traps_on();
  for (int lower = 0; lower <= 1; lower++) {
    struct sph_config cfg;
    tank_config(&cfg, 1);
    cfg.vertex_bc.method = SPH_VVALUES_ROBIN;
    cfg.vertex_bc.order = 4; /* rows and columns within 2h: three distinct distances */
    cfg.vertex_bc.too_few = lower ? SPH_VTOOFEW_LOWER : SPH_VTOOFEW_ERROR;
    struct sph_solver sv;
    tank(&sv, &cfg);
    char msg[1024];
    const int rc = sph_solver_step(&sv, INFINITY, msg, sizeof msg);
    if (lower) {
      assert_int_equal(rc, 0);
      assert_true(sv.vertex_fail < 0);
    } else {
      print_message("%s\n", msg);
      assert_int_equal(rc, -1);
      assert_int_equal(sv.vertex_fail_status, SPH_ROBIN_ETOOFEW);
      assert_non_null(strstr(msg, "step 1"));
      assert_non_null(strstr(msg, "vertex id "));
      assert_non_null(strstr(msg, ") at ("));
      assert_non_null(strstr(msg, "SPH_ROBIN_ETOOFEW"));
      assert_non_null(strstr(msg, "3 distinct"));
    }
    sph_solver_free(&sv);
  }
}

static void test_groups(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_config cfg;
  tank_config(&cfg, 1);
  cfg.nvertex_groups = 1;
  cfg.vertex_groups[0] = cfg.vertex_bc;
  cfg.vertex_groups[0].method = SPH_VVALUES_ROBIN;
  cfg.vertex_groups[0].order = 2;
  cfg.vertex_groups[0].wall = 0;
  cfg.vertex_groups[0].nedges = 2;
  cfg.vertex_groups[0].edges[0] = 2;
  cfg.vertex_groups[0].edges[1] = 4;
  struct sph_solver sv;
  tank(&sv, &cfg);
  const struct sph_parts *v = &sv.sys.part[SPH_KIND_VERTEX];
  int side = 0, floor = 0;
  for (size_t i = 0; i < v->n; i++) {
    const double x = v->x[0][i], y = v->x[1][i];
    const int on_side = (x < 1e-9 || x > 0.2 - 1e-9) && y > 1e-9 && y < 0.2 - 1e-9;
    const int on_floor = y < 1e-9 && x > 1e-9 && x < 0.2 - 1e-9;
    if (on_side) assert_int_equal(sv.vert_bc[i], 0), side++;
    if (on_floor) assert_int_equal(sv.vert_bc[i], -1), floor++;
  }
  assert_int_equal(side, 2 * 19);
  assert_int_equal(floor, 19);
  double worst, corner;
  wall_error(&sv, &worst, &corner);
  assert_true(worst < 2e-3);
  sph_solver_free(&sv);
}

/* ------------------------------------------------------------------------------------------- */

static const char base[] =
    "geometry:\n"
    "  dr: 0.01\n"
    "  walls: [{type: box, lo: [0, 0], hi: [1, 1]}, {type: box, lo: [2, 0], hi: [3, 1]}]\n"
    "fluid: {rho0: 1000, c0: 20}\n"
    "time: {end: 2.5}\n";

static int read_case(const char *extra, struct sph_config *cfg, char *msg, size_t len) {
  return fixture_read_case(base, extra, cfg, msg, len);
}

static void test_case_keys(void **state) {
  (void)state;
  struct sph_config cfg;
  char msg[512];
  assert_int_equal(read_case("", &cfg, msg, sizeof msg), 0);
  assert_int_equal(cfg.vertex_bc.method, SPH_VVALUES_SHEPARD);
  assert_true(cfg.vertex_bc.order == 1 && cfg.vertex_bc.mu[0] == 0.0 &&
              cfg.vertex_bc.mu[1] == 1.0 && cfg.vertex_bc.mu[2] == 0.0);
  assert_true(cfg.vertex_bc.gravity_flux && cfg.vertex_bc.tangential);
  assert_int_equal(cfg.vertex_bc.too_few, SPH_VTOOFEW_ERROR);
  assert_int_equal(cfg.nvertex_groups, 0);
  assert_int_equal(cfg.flux_method, SPH_FLUXSEL_OFF);
  assert_int_equal(
      read_case("vertex_values:\n"
                "  method: least_squares\n"
                "  order: 2\n"
                "  constraint: M82\n"
                "  groups:\n"
                "    - {wall: 1, edges: [2, 4], order: 3, mu: [-1, 2, 0.5], too_few: lower}\n"
                "    - {wall: 0, method: shepard, gravity_flux: false}\n"
                "imposed_flux: {velocity: 0.0125, area: 0.2, point: [0.5, 0.1]}\n",
                &cfg, msg, sizeof msg),
      0);
  assert_true(cfg.vertex_bc.method == SPH_VVALUES_ROBIN && cfg.vertex_bc.order == 2);
  assert_int_equal(cfg.vertex_bc.tangential, 0);
  assert_int_equal(cfg.nvertex_groups, 2);
  const struct sph_vertex_bc *g0 = &cfg.vertex_groups[0], *g1 = &cfg.vertex_groups[1];
  assert_true(g0->wall == 1 && g0->nedges == 2 && g0->edges[1] == 4 && g0->order == 3);
  assert_true(g0->mu[0] == -1.0 && g0->mu[1] == 2.0 && g0->mu[2] == 0.5);
  assert_true(g0->too_few == SPH_VTOOFEW_LOWER && g0->tangential == 0 && g0->gravity_flux);
  assert_true(g1->wall == 0 && g1->nedges == 0 && g1->method == SPH_VVALUES_SHEPARD);
  assert_true(g1->order == 2 && g1->gravity_flux == 0);
  assert_int_equal(cfg.flux_method, SPH_FLUXSEL_M63);
  assert_true(cfg.flux_velocity == 0.0125 && cfg.flux_area == 0.2 && cfg.flux_width == 0.02);
  assert_true(cfg.flux_normal[0] == 1.0 && cfg.flux_normal[1] == 0.0);
  assert_true(cfg.flux_point[0] == 0.5 && cfg.flux_point[1] == 0.1 && cfg.flux_force0 == 0.0);
  assert_int_equal(read_case("imposed_flux: {method: M58, flux: 0.01, area: 0.5, width: 0.03, "
                             "direction: [0, 2], force0: 0.1}\n",
                             &cfg, msg, sizeof msg),
                   0);
  assert_int_equal(cfg.flux_method, SPH_FLUXSEL_M58);
  assert_true(cfg.flux_velocity == 0.02 && cfg.flux_width == 0.03 && cfg.flux_force0 == 0.1);
  assert_true(cfg.flux_normal[0] == 0.0 && cfg.flux_normal[1] == 1.0);

  static const struct {
    const char *yaml, *expect;
  } bad[] = {
      {"vertex_values: {order: 7}\n", "vertex_values.order"},
      {"vertex_values: {mu: [1, 0, 0]}\n", "mu2 != 0"},
      {"vertex_values: {method: robin}\n", "vertex_values.method"},
      {"vertex_values: {constraint: M84}\n", "vertex_values.constraint"},
      {"vertex_values: {ordr: 2}\n", "vertex_values.ordr"},
      {"vertex_values: {groups: [{order: 2}]}\n", "groups[0].wall"},
      {"vertex_values: {groups: [{wall: 2}]}\n", "groups[0].wall"},
      {"imposed_flux: {area: 1}\n", "exactly one"},
      {"imposed_flux: {velocity: 1, flux: 1, area: 1}\n", "exactly one"},
      {"imposed_flux: {velocity: 1}\n", "imposed_flux.area"},
      {"imposed_flux: {velocity: 1, area: 1, method: M62}\n", "imposed_flux.method"},
      {"imposed_flux: {velocity: 1, area: 1, direction: [0, 0]}\n", "non-zero"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    assert_int_equal(read_case(bad[i].yaml, &cfg, msg, sizeof msg), -1);
    if (!strstr(msg, bad[i].expect)) print_message("'%s' -> '%s'\n", bad[i].yaml, msg);
    assert_non_null(strstr(msg, bad[i].expect));
  }
}

int main(void) {
  gsl_set_error_handler_off();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_m1_is_shepard), cmocka_unit_test(test_hydrostatic_tank),
      cmocka_unit_test(test_too_few),       cmocka_unit_test(test_groups),
      cmocka_unit_test(test_case_keys),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
