/*
 * Initial profiles as expressions of the coordinates (docs/sph-case-file.md, `initial`):
 * velocity components, pressure and density reach every fluid particle exactly as the expression
 * gives them (density through the Tait EOS for a pressure), masses follow; a wave (initial.wave)
 * keeps the fluid below its surface with its velocity and pressure; bad expressions and
 * inconsistent keys fail naming the key (non-fatal mode); so do probes and gauges outside the
 * case's domain (sph_config_check_probes).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_solver.h"
#include "testutil.h"

#define PI 3.14159265358979323846

static const char base[] =
    "geometry:\n"
    "  dimension: 2\n"
    "  dr: 0.05\n"
    "  first_row: 1\n"
    "  walls: [{type: box, lo: [0, 0], hi: [0.5, 0.6]}]\n"
    "  fluid: [{type: box, lo: [0, 0], hi: [0.5, 0.4]}]\n"
    "fluid: {rho0: 1000, c0: 20}\n"
    "time: {end: 1}\n";

/* Read base + extra (fatal mode off for the solver sections) into a solver, or with sv NULL
 * check its probes (sph_config_check_probes). Returns the rc of sph_config_read(), then of the
 * probe check, with the message in msg; the solver is set up only on success. */
static int setup(const char *extra, struct sph_solver *sv, char *msg, size_t len) {
  char text[4096], err[512];
  snprintf(text, sizeof text, "%s%s", base, extra);
  struct cmn_case *c = cmn_case_parse(text, "case.yaml", err, sizeof err);
  assert_non_null(c);
  struct sph_geometry g;
  sph_geometry_read(&g, c);
  cmn_case_set_fatal(c, 0);
  struct sph_config cfg;
  int rc = sph_config_read(&cfg, c, g.dim);
  if (rc == 0) rc = cmn_case_check_unused(c);
  if (rc == 0) {
    struct sph_system s;
    sph_system_from_geometry(&s, &g);
    if (sv)
      sph_solver_init(sv, &cfg, &s, NULL, NULL);
    else
      rc = sph_config_check_probes(&cfg, c, &s);
    sph_system_free(&s);
  }
  snprintf(msg, len, "%s", cmn_case_error(c));
  sph_geometry_free(&g);
  cmn_case_free(c);
  return rc;
}

static void test_initial_expressions(void **state) {
  (void)state;
  struct sph_solver sv;
  char msg[512];
  int rc = setup(
      "initial:\n"
      "  velocity: [0.125, 2*sin(4*pi*y) - x]\n"
      "  pressure: 300*(0.4 - y) + 20*cos(pi*x)\n",
      &sv, msg, sizeof msg);
  if (rc) print_error("%s\n", msg);
  assert_int_equal(rc, 0);
  const struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
  assert_int_equal(f->n, 9 * 8);
  for (size_t a = 0; a < f->n; a++) {
    const double x = f->x[0][a], y = f->x[1][a];
    const double p = 300 * (0.4 - y) + 20 * cos(PI * x);
    assert_rel(f->v[0][a], 0.125, 1e-15);
    assert_true(fabs(f->v[1][a] - (2 * sin(4 * PI * y) - x)) <= 1e-15);
    assert_rel(f->rho[a], rmn_eos_density(&sv.eos, p), 1e-15);
    assert_rel(f->p[a], p, 1e-9);
    assert_rel(f->mass[a], f->rho[a] * 0.05 * 0.05, 1e-15);
  }
  sph_solver_free(&sv);
  /* A density profile instead of the pressure; a constant pressure as a plain number. */
  assert_int_equal(setup("initial: {density: 1000 + 3.5*y}\n", &sv, msg, sizeof msg), 0);
  for (size_t a = 0; a < sv.sys.part[SPH_KIND_FLUID].n; a++)
    assert_rel(sv.sys.part[SPH_KIND_FLUID].rho[a], 1000 + 3.5 * sv.sys.part[SPH_KIND_FLUID].x[1][a],
               1e-15);
  sph_solver_free(&sv);
  assert_int_equal(setup("initial: {pressure: 250}\n", &sv, msg, sizeof msg), 0);
  assert_rel(sv.sys.part[SPH_KIND_FLUID].rho[0], rmn_eos_density(&sv.eos, 250.0), 1e-15);
  sph_solver_free(&sv);
}

/* initial.wave: the fluid below Fenton's surface at t = 0 (a lattice point is kept when it lies
 * below η at its x), with the wave's velocity and pressure. */
static void test_initial_wave(void **state) {
  (void)state;
  struct sph_solver sv;
  char msg[512];
  int rc = setup(
      "gravity: [0, -9.81]\n"
      "initial:\n"
      "  wave:\n"
      "    stokes5: {depth: 0.3, amplitude: 0.03, length: 1.0, x0: 0.2}\n",
      &sv, msg, sizeof msg);
  if (rc) print_error("%s\n", msg);
  assert_int_equal(rc, 0);
  struct sph_stokes5_params wp;
  sph_stokes5_params_init(&wp);
  wp.depth = 0.3;
  wp.height = 0.06;
  wp.length = 1.0;
  wp.g = 9.81;
  wp.rho0 = 1000.0;
  struct sph_stokes5 w;
  assert_int_equal(sph_stokes5_init(&w, &wp, NULL, 0), SPH_WAVE_SUCCESS);
  /* the lattice of the fluid box: columns 0.05 ... 0.45, rows 0.05 ... 0.40 */
  size_t expected = 0;
  int crest_row = 0;
  for (int i = 1; i <= 9; i++)
    for (int j = 1; j <= 8; j++) {
      struct sph_wave_point pt;
      sph_stokes5_eval(&w, 0.05 * i - 0.2, 0.05 * j, 0.0, &pt);
      expected += 0.05 * j < pt.eta;
      crest_row |= j == 6 && 0.05 * j < pt.eta;
    }
  assert_true(crest_row);        /* the wave's crest keeps part of the row at 0.30 m */
  assert_true(expected < 9 * 6); /* and its trough removes the rest */
  const struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
  assert_int_equal(f->n, expected);
  for (size_t a = 0; a < f->n; a++) {
    struct sph_wave_point pt;
    assert_int_equal(sph_stokes5_eval(&w, f->x[0][a] - 0.2, f->x[1][a], 0.0, &pt),
                     SPH_WAVE_SUCCESS);
    assert_true(f->x[1][a] < pt.eta);
    assert_true(fabs(f->v[0][a] - pt.u) <= 1e-15);
    assert_true(fabs(f->v[1][a] - pt.w) <= 1e-15);
    assert_true(pt.p > 0.0);
    assert_rel(f->rho[a], rmn_eos_density(&sv.eos, pt.p), 1e-15);
    assert_rel(f->mass[a], f->rho[a] * 0.05 * 0.05, 1e-15);
  }
  sph_solver_free(&sv);
}

static void expect_error(const char *extra, const char *want) {
  struct sph_solver sv;
  char msg[512];
  int rc = setup(extra, &sv, msg, sizeof msg);
  if (rc == 0 || !strstr(msg, want)) print_error("rc %d, '%s'; wanted '%s'\n", rc, msg, want);
  assert_int_equal(rc, -1);
  assert_non_null(strstr(msg, want));
}

static void test_initial_errors(void **state) {
  (void)state;
  expect_error("initial: {velocity: [0, 2*sin(4*pi*z)]}\n",
               "case.yaml:9:25: initial.velocity[1]: expected a number or an expression: "
               "expression '2*sin(4*pi*z)': unknown name 'z' (variables: x, y, pi;");
  expect_error("initial: {velocity: [0, 1, 2]}\n",
               "initial.velocity: expected 2 numbers or expressions, got 3");
  expect_error("initial: {pressure: hydrostatc}\n", "initial.pressure: expected a number or an");
  expect_error("initial: {pressure: 1 +}\n", "unexpected end at column 4");
  expect_error("initial: {pressure: hydrostatic, density: 1000}\ngravity: [0, -9.81]\n",
               "initial.density: give initial.pressure or initial.density, not both");
  expect_error(
      "gravity: [0, -9.81]\ninitial:\n  velocity: [0, 0]\n"
      "  wave: {stokes5: {depth: 0.3, amplitude: 0.03, length: 1}}\n",
      "initial.velocity: initial.wave gives the free surface, velocity and pressure");
  expect_error(
      "gravity: [0, -9.81]\ninitial:\n  wave:\n"
      "    stokes5: {depth: 0.3, amplitude: 0.03, length: 1}\n"
      "    solitary: {depth: 0.3, amplitude: 0.1}\n",
      "initial.wave: give exactly one of 'stokes5' and 'solitary'");
  expect_error("initial:\n  wave: {solitary: {depth: 0.3, amplitude: 0.1}}\n",
               "initial.wave: a wave needs a non-zero gravity");
  expect_error("gravity: [0, -9.81]\ninitial:\n  wave: {stokes5: {depth: 0.3, length: 1}}\n",
               "initial.wave.stokes5: give exactly one of 'height' (H, m) and 'amplitude'");
}

static void expect_probes(const char *extra, const char *want) {
  char msg[1024];
  const int rc = setup(extra, NULL, msg, sizeof msg);
  if (want == NULL) {
    if (rc != 0) print_error("rc %d, '%s'; wanted no error\n", rc, msg);
    assert_int_equal(rc, 0);
    return;
  }
  if (rc == 0 || !strstr(msg, want)) print_error("rc %d, '%s'; wanted '%s'\n", rc, msg, want);
  assert_int_equal(rc, -1);
  assert_non_null(strstr(msg, want));
}

/* The walls span 0 ... 0.5 × 0 ... 0.6 m and h = 2 dr = 0.1 m (the default h_over_dr). */
static void test_probe_errors(void **state) {
  (void)state;
  /* inside, on a wall, within h outside it, and gauges above the water or below the floor */
  expect_probes(
      "probes: {pressure: [[0.25, 0.1], [0, 0.3], [-0.09, 0.3]],\n"
      "         gauges: [[0.25, 0], [0.1, 5], [0.4, -3]]}\n"
      "gravity: [0, -9.81]\n",
      NULL);
  expect_probes("probes: {pressure: [[0.25, 0.1], [0.25, 0.75]]}\n",
                "case.yaml:9:34: probes.pressure[1]: the point y = 0.75 m is outside the case's "
                "domain: the fluid and the walls (widened by h = 0.1 m) span x -0.1 ... 0.6 m, "
                "y -0.1 ... 0.7 m");
  expect_probes("probes: {gauges: [[0.25, 0], [0.9, 0]]}\ngravity: [0, -9.81]\n",
                "probes.gauges[1]: the vertical line through (0.9, 0, 0) m (along -g) misses the "
                "case's domain");
  /* without gravity the line is along y; with gravity along x, along x */
  expect_probes("probes: {gauges: [[-0.15, 0.3]]}\n", "probes.gauges[0]: the vertical line");
  expect_probes("probes: {gauges: [[-3, 0.3]]}\ngravity: [-9.81, 0]\n", NULL);
  expect_probes("probes: {gauges: [[-3, 0.75]]}\ngravity: [-9.81, 0]\n",
                "probes.gauges[0]: the vertical line");
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_initial_expressions), cmocka_unit_test(test_initial_wave),
      cmocka_unit_test(test_initial_errors), cmocka_unit_test(test_probe_errors)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
