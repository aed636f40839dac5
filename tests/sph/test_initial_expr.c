/*
 * Initial profiles as expressions of the coordinates (docs/sph-case-file.md, `initial`):
 * velocity components, pressure and density reach every fluid particle exactly as the expression
 * gives them (density through the Tait EOS for a pressure), masses follow; bad expressions and
 * inconsistent keys fail naming the key (non-fatal mode).
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

/* Read base + extra into a solver (fatal mode off for the solver sections). Returns the rc of
 * sph_config_read() with its message in msg; the solver is set up only on success. */
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
  snprintf(msg, len, "%s", cmn_case_error(c));
  if (rc == 0) {
    struct sph_system s;
    sph_system_from_geometry(&s, &g);
    sph_solver_init(sv, &cfg, &s, NULL, NULL);
    sph_system_free(&s);
  }
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
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_initial_expressions),
                                     cmocka_unit_test(test_initial_errors)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
