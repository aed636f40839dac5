/*
 * Neighbour lists kept over several steps (numerics.list_rebuild, docs/sph-solver.md §1): N steps
 * with the lists rebuilt only when some particle has moved more than skin/2 since their build,
 * and the same N steps with the lists rebuilt at every step, give bitwise equal positions,
 * velocities, densities and masses (vertex masses too with open boundaries): rows are sorted by
 * neighbour index and every loop over a row leaves out the pairs beyond the support. Cases: a 2D
 * dam break in a closed box (gravity, viscous walls, wall impedance), a 3D dam break in a tank, a
 * channel periodic in x whose particles wrap (dynamic γ), and the through-flow of
 * test_open_mass.c (particles created and deleted). Each run keeps some lists and rebuilds others
 * (1 < builds < N). The second run also forms the continuity's sums at the start of every step
 * again, where the first carries them over from the previous corrector (docs/sph-solver.md §3):
 * the same bits too. Also: a bad value of numerics.list_rebuild is an error naming the key.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_solver.h"
#include "solver_fixture.h"
#include "testutil.h"

/* The case text with `numerics: {list_rebuild: <mode>, <numerics>}` appended. */
static struct sph_solver *solver(const char *text, const char *numerics, const char *mode) {
  char full[4096];
  snprintf(full, sizeof full, "%snumerics: {list_rebuild: %s%s%s}\n", text, mode,
           numerics[0] ? ", " : "", numerics);
  struct sph_solver *sv = fixture_solver_from_case(full);
  assert_int_equal(sv->cfg.list_rebuild,
                   strcmp(mode, "every_step") == 0 ? SPH_LISTS_EVERY_STEP : SPH_LISTS_WHEN_NEEDED);
  sv->list_builds = 0;
  return sv;
}

/* With fresh_sums, the continuity's sums at the start of each step are formed again in the
 * predictor instead of carried over from the previous corrector (docs/sph-solver.md §3). */
static void run(struct sph_solver *sv, long steps, int fresh_sums) {
  char msg[1024];
  for (long n = 0; n < steps; n++) {
    if (fresh_sums) sv->sum_w_valid = 0;
    if (sph_solver_step(sv, INFINITY, msg, sizeof msg) != 0) fail_msg("%s", msg);
  }
}

/* Run `steps` steps both ways and compare the stores bit for bit. */
static void check(const char *name, const char *text, const char *numerics, long steps) {
  sabre_fp_traps_on();
  struct sph_solver *a = solver(text, numerics, "when_needed");
  struct sph_solver *b = solver(text, numerics, "every_step");
  const double t0 = cmn_wall_time();
  run(a, steps, 0);
  const double t1 = cmn_wall_time();
  run(b, steps, 1);
  const double t2 = cmn_wall_time();
  const struct sph_parts *fa = &a->sys.part[SPH_KIND_FLUID], *fb = &b->sys.part[SPH_KIND_FLUID];
  const struct sph_parts *va = &a->sys.part[SPH_KIND_VERTEX], *vb = &b->sys.part[SPH_KIND_VERTEX];
  double vmax = 0.0;
  for (size_t i = 0; i < fa->n; i++) {
    double v2 = 0.0;
    for (int c = 0; c < 3; c++) v2 += fa->v[c][i] * fa->v[c][i];
    vmax = fmax(vmax, sqrt(v2));
  }
  print_message(
      "%s: %zu fluid particles, %ld steps to t = %.4g s (max speed %.3g m/s, skin/2 = %.3g m): "
      "%ld builds when needed (%.2f s), %ld at every step (%.2f s)\n",
      name, fa->n, steps, a->time, vmax, 0.5 * a->cfg.skin_over_h * a->sys.h, a->list_builds,
      t1 - t0, b->list_builds, t2 - t1);
  assert_int_equal(b->list_builds, steps);
  assert_true(a->list_builds > 1 && a->list_builds < steps);
  assert_true(a->time == b->time && a->step == b->step);
  assert_int_equal(fa->n, fb->n);
  assert_memory_equal(fa->id, fb->id, fa->n * sizeof *fa->id);
  assert_memory_equal(fa->rho, fb->rho, fa->n * sizeof(double));
  assert_memory_equal(fa->mass, fb->mass, fa->n * sizeof(double));
  assert_memory_equal(fa->gamma, fb->gamma, fa->n * sizeof(double));
  for (int c = 0; c < a->sys.dim; c++) {
    assert_memory_equal(fa->x[c], fb->x[c], fa->n * sizeof(double));
    assert_memory_equal(fa->v[c], fb->v[c], fa->n * sizeof(double));
  }
  assert_memory_equal(va->mass, vb->mass, va->n * sizeof(double));
  assert_memory_equal(va->rho, vb->rho, va->n * sizeof(double));
  fixture_solver_destroy(a);
  fixture_solver_destroy(b);
}

/* A water column collapsing in a closed box: gravity, viscous walls, the wall impedance. */
static void test_box_2d(void **state) {
  (void)state;
  check("2D dam break in a box",
        "geometry:\n"
        "  dimension: 2\n"
        "  dr: 0.02\n"
        "  walls: [{type: box, lo: [0, 0], hi: [0.6, 0.4]}]\n"
        "  fluid: [{type: box, lo: [0, 0], hi: [0.2, 0.3]}]\n"
        "fluid: {rho0: 1000, c0: 20, nu: 1.0e-4}\n"
        "gravity: [0, -9.81]\n"
        "initial: {pressure: hydrostatic}\n"
        "time: {end: 1}\n",
        "wall_impedance: acoustic", 300);
}

/* A 3D dam break in a tank (triangle walls, edges and corners). */
static void test_tank_3d(void **state) {
  (void)state;
  check("3D dam break in a tank",
        "geometry:\n"
        "  dimension: 3\n"
        "  dr: 0.025\n"
        "  first_row: 1\n"
        "  walls: [{type: box, lo: [0, 0, 0], hi: [0.3, 0.15, 0.2]}]\n"
        "  fluid: [{type: box, lo: [0, 0, 0], hi: [0.1, 0.15, 0.15]}]\n"
        "fluid: {rho0: 1000, c0: 15, nu: 1.0e-5}\n"
        "gravity: [0, 0, -9.81]\n"
        "initial: {pressure: hydrostatic}\n"
        "time: {end: 1}\n",
        "", 120);
}

/* A sheared flow along a channel periodic in x: particles wrap around the period. */
static void test_periodic(void **state) {
  (void)state;
  check("periodic channel",
        "geometry:\n"
        "  dimension: 2\n"
        "  dr: 0.025\n"
        "  first_row: 1\n"
        "  periodic: [x]\n"
        "  walls: [{type: channel, lo: [0, 0], hi: [0.4, 0.3]}]\n"
        "  fluid: [{type: box, lo: [0, 0], hi: [0.4, 0.3]}]\n"
        "fluid: {rho0: 1000, c0: 20, nu: 1.0e-3}\n"
        "gravity: [0.5, -9.81]\n"
        "initial: {pressure: hydrostatic, velocity: [1.5 + 0.5*sin(2*pi*y/0.3), 0]}\n"
        "time: {end: 1}\n",
        "gamma: dynamic", 300);
}

/* The through-flow of test_open_mass.c: particles created at the inlet and deleted at the
 * outlet (each creation or deletion drops the lists), vertex masses varying. */
static void test_open_through(void **state) {
  (void)state;
  check("open through-flow", FIXTURE_THROUGH_CASE, "", 400);
}

static void test_option_error(void **state) {
  (void)state;
  static const char base[] =
      "geometry:\n"
      "  walls: [{type: box, lo: [0, 0], hi: [1, 1]}]\n"
      "fluid: {rho0: 1000, c0: 20}\n"
      "time: {end: 2.5}\n";
  struct sph_config cfg;
  char msg[512];
  assert_int_equal(fixture_read_case(base, "", &cfg, msg, sizeof msg), 0);
  assert_int_equal(cfg.list_rebuild, SPH_LISTS_WHEN_NEEDED);
  assert_int_equal(
      fixture_read_case(base, "numerics: {list_rebuild: every_step}\n", &cfg, msg, sizeof msg), 0);
  assert_int_equal(cfg.list_rebuild, SPH_LISTS_EVERY_STEP);
  assert_int_equal(
      fixture_read_case(base, "numerics: {list_rebuild: sometimes}\n", &cfg, msg, sizeof msg), -1);
  print_message("%s\n", msg);
  if (!strstr(msg, "case.yaml") || !strstr(msg, "numerics.list_rebuild") ||
      !strstr(msg, "when_needed"))
    fail_msg("'%s' does not name the file, the key and the choices", msg);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_option_error), cmocka_unit_test(test_box_2d),
      cmocka_unit_test(test_tank_3d),      cmocka_unit_test(test_periodic),
      cmocka_unit_test(test_open_through),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
