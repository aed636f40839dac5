/* Case files: a valid file gives the documented defaults; every kind of bad input (missing key,
 * wrong type, unknown key, non-physical value, inconsistent keys) gives an error naming the key.
 * Also the expression language of the initial profiles. */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "helpers.h"

static const char base[] =
    "domain: {x_min: -0.5, x_max: 0.5, cells: 64}\n"
    "fluid: {rho0: 1000, c0: 20, xi: 7}\n"
    "initial:\n"
    "  rho: 1000\n"
    "  regions:\n"
    "    - {from: -1, to: 0, rho: 1010, u: 0.1}\n"
    "boundaries:\n"
    "  left: {type: wall}\n"
    "  right: {type: open, impose: pressure, signal: sinusoid, value: 10, amplitude: 5, "
    "frequency: 3}\n"
    "time: {end: 0.01}\n";

/* Parse base + overrides (each "path=value", "" ends), read; return 0 or -1 with the message. */
static int read_case(const char *const *sets, char *msg, size_t msglen, struct fv1d_params *p) {
  char err[512];
  struct cmn_case *c = cmn_case_parse(base, "test.yaml", err, sizeof err);
  assert_non_null(c);
  cmn_case_set_fatal(c, 0);
  for (int k = 0; sets && sets[k]; ++k) assert_int_equal(cmn_case_set(c, sets[k]), 0);
  int status = fv1d_case_read(c, NULL, p);
  snprintf(msg, msglen, "%s", cmn_case_error(c));
  cmn_case_free(c);
  return status;
}

static void test_valid_defaults(void **state) {
  (void)state;
  struct fv1d_params p;
  char msg[512];
  int status = read_case(NULL, msg, sizeof msg, &p);
  if (status != 0) print_error("%s\n", msg);
  assert_int_equal(status, 0);
  assert_int_equal(p.cells, 64);
  assert_true(p.flux == FV1D_FLUX_GODUNOV && p.recon == FV1D_RECON_MINMOD);
  assert_true(p.cfl == 0.5 && !p.adaptive && strcmp(p.method, "ssprk3") == 0);
  assert_true(p.noutput == 1 && p.output_times[0] == 0.01);
  assert_true(p.bc[0].type == FV1D_BC_WALL && p.bc[1].type == FV1D_BC_OPEN);
  assert_true(p.bc[1].signal.kind == FV1D_SIGNAL_SINUSOID && p.bc[1].signal.phase == 0.0);
  assert_true(p.initial.nregions == 1 && p.initial.regions[0].rho == 1010.0);
  fv1d_params_free(&p);
}

static void expect_error(const char *override, const char *key, const char *what);

static void test_expression_profiles(void **state) {
  (void)state;
  const char *sets[] = {"initial.rho=1000*(1 + 0.01*sin(2*pi*x))", "initial.u=-0.5*x^2", NULL};
  struct fv1d_params p;
  char msg[512];
  int status = read_case(sets, msg, sizeof msg, &p);
  if (status != 0) print_error("%s\n", msg);
  assert_int_equal(status, 0);
  assert_non_null(p.initial.rho_expr);
  const double x1 = 0.25, x2 = 0.3;
  assert_rel(cmn_expr_eval(p.initial.rho_expr, &x1), 1010.0, 1e-15);
  assert_rel(cmn_expr_eval(p.initial.u_expr, &x2), -0.045, 1e-15);
  fv1d_params_free(&p);
  /* The expression language itself: tests/common/test_expr.c. A name other than x is an error
   * naming the key. */
  expect_error("initial.u=y + 1", "initial.u", "unknown name 'y'");
}

/* One override must give an error whose message names `key` (and contains `what`, if given). */
static void expect_error(const char *override, const char *key, const char *what) {
  const char *sets[] = {override, NULL};
  struct fv1d_params p;
  char msg[512];
  int status = read_case(sets, msg, sizeof msg, &p);
  if (status == 0 || !strstr(msg, key) || (what && !strstr(msg, what)))
    print_error("override '%s': status %d, message '%s', expected the key '%s'%s%s\n", override,
                status, msg, key, what ? " and " : "", what ? what : "");
  assert_int_equal(status, -1);
  assert_non_null(strstr(msg, key));
  if (what) assert_non_null(strstr(msg, what));
  fv1d_params_free(&p);
}

static void test_missing_key(void **state) {
  (void)state;
  expect_error("domain={x_min: -0.5, x_max: 0.5}", "domain.cells", NULL);
  expect_error("fluid={rho0: 1000, xi: 7}", "fluid.c0", NULL);
  expect_error("time={cfl: 0.4}", "time.end", NULL);
  expect_error("boundaries.right={type: open, impose: pressure}", "boundaries.right.value", NULL);
  expect_error("boundaries.right={type: open, value: 3}", "boundaries.right.impose", NULL);
}

static void test_wrong_type(void **state) {
  (void)state;
  expect_error("domain.cells=abc", "domain.cells", NULL);
  expect_error("domain.cells=12.5", "domain.cells", NULL);
  expect_error("fluid.rho0=[1, 2]", "fluid.rho0", NULL);
  expect_error("time.adaptive=perhaps", "time.adaptive", NULL);
  expect_error("output.times=0.3", "output.times", NULL);
  expect_error("initial.u=1 +* 2", "initial.u", NULL);
}

static void test_unknown_key(void **state) {
  (void)state;
  expect_error("domain.celss=10", "domain.celss", NULL);
  expect_error("numerics.limiter=mc", "numerics.limiter", NULL);
  expect_error("boundaries.left.value=3", "boundaries.left.value", NULL); /* wall takes none */
}

static void test_bad_choice(void **state) {
  (void)state;
  expect_error("numerics.flux=roe", "numerics.flux", "godunov");
  expect_error("boundaries.left.type=hole", "boundaries.left.type", "periodic");
  expect_error("time.method=ARKODE_NOT_A_TABLE", "time.method", NULL);
  expect_error("time.method=rk4", "time.method", NULL);
  /* tables that SUNDIALS 6.4 mis-integrates (c_s = 1 without FSAL, LLNL/sundials #311) */
  expect_error("time.method=ARKODE_HEUN_EULER_2_1_2", "time.method", "#311");
  expect_error("time.method=ARKODE_ARK436L2SA_ERK_6_3_4", "time.method", "#311");
  expect_error("time={end: 0.01, method: ARKODE_KNOTH_WOLKE_3_3, adaptive: true}", "time.method",
               "embedding");
}

static void test_non_physical(void **state) {
  (void)state;
  expect_error("fluid.c0=-3", "fluid.c0", NULL);
  expect_error("fluid.rho0=0", "fluid.rho0", NULL);
  expect_error("fluid.xi=0.5", "fluid.xi", NULL);
  expect_error("domain.x_max=-1", "domain.x_max", NULL);
  expect_error("domain.cells=1", "domain.cells", NULL);
  expect_error("initial.rho=-5", "initial.rho", NULL);
  expect_error("initial.rho=1000*sin(2*pi*x)", "initial.rho", "non-physical");
  expect_error("initial.regions=[{from: 0, to: 0.2, rho: -1}]", "initial.regions[0].rho", NULL);
  expect_error("initial.regions=[{from: 0.3, to: 0.2, rho: 1}]", "initial.regions[0].to", NULL);
  expect_error("time.end=-0.1", "time.end", NULL);
  expect_error("time.cfl=0", "time.cfl", NULL);
  expect_error("output.times=[0.005, 0.002]", "output.times", NULL);
  expect_error("output.times=[0.02]", "output.times", NULL);
  /* an imposed pressure at or below the vacuum pressure −ρ0 c0²/ξ, a supersonic velocity */
  expect_error("boundaries.right.value=-60000", "boundaries.right", "vacuum");
  expect_error("boundaries.right={type: open, impose: velocity, value: 25}", "boundaries.right",
               "subsonic");
}

static void test_inconsistent(void **state) {
  (void)state;
  expect_error("boundaries.left.type=periodic", "boundaries.right.type", "both ends");
  expect_error("initial.p=100", "initial.p", "not both");
}

static void test_tables(void **state) {
  (void)state;
  const char *path = "fv1d_test_table.csv";
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fputs("t,value\n0,0\n0.5,100\n1.0,50\n", f);
  fclose(f);
  const char *sets[] = {
      "boundaries.right={type: open, impose: pressure, signal: table, "
      "table: fv1d_test_table.csv}",
      NULL};
  struct fv1d_params p;
  char msg[512];
  int status = read_case(sets, msg, sizeof msg, &p);
  if (status != 0) print_error("%s\n", msg);
  assert_int_equal(status, 0);
  assert_int_equal((int)p.bc[1].signal.ntable, 3);
  assert_rel(fv1d_signal_eval(&p.bc[1].signal, 0.75), 75.0, 1e-15);
  fv1d_params_free(&p);
  f = fopen(path, "w");
  fputs("time,value\n0,0\n", f);
  fclose(f);
  expect_error(sets[0], "boundaries.right.table", "header");
  remove(path);
  expect_error(sets[0], "boundaries.right.table", "cannot open");
}

/* An initial profile table (linear in x: cell averages equal the centre values) and a region
 * given by its pressure. */
static void test_initial_table(void **state) {
  (void)state;
  const char *path = "fv1d_test_profile.csv";
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fputs("x,rho,u\n-0.5,1000,0\n0.5,1010,0.3\n", f);
  fclose(f);
  const char *sets[] = {"initial={table: fv1d_test_profile.csv, regions: [{from: 0.25, p: 812.5}]}",
                        NULL};
  struct fv1d_params p;
  char msg[512];
  int status = read_case(sets, msg, sizeof msg, &p);
  if (status != 0) print_error("%s\n", msg);
  assert_int_equal(status, 0);
  struct fv1d_solver *s = fv1d_solver_create(&p);
  const double *y = fv1d_solver_state(s);
  for (long i = 0; i < fv1d_solver_cells(s); ++i) {
    double x = fv1d_solver_x(s, i);
    if (x >= 0.25) {
      assert_rel(y[2 * i], rmn_eos_density(&p.eos, 812.5), 1e-15);
      assert_true(y[2 * i + 1] == 0.0);
    } else {
      double rho = 1005.0 + 10.0 * x, u = 0.15 + 0.3 * x;
      assert_rel(y[2 * i], rho, 1e-14);
      /* ρu is quadratic in x: its cell average exceeds the centre product by dx²/12 ρ'u' */
      double dx = fv1d_solver_dx(s);
      assert_rel(y[2 * i + 1], rho * u + dx * dx / 12.0 * 10.0 * 0.3, 1e-12);
    }
  }
  fv1d_solver_destroy(s);
  fv1d_params_free(&p);
  remove(path);
  expect_error("initial={table: fv1d_test_profile.csv}", "initial.table", "cannot open");
  expect_error("initial={table: x.csv, u: 0}", "initial.table", "one or the other");
}

int main(void) {
  gsl_set_error_handler_off();
  sabre_fp_traps_on();
  cmn_set_program_name("test_case_file");
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_valid_defaults), cmocka_unit_test(test_expression_profiles),
      cmocka_unit_test(test_missing_key),    cmocka_unit_test(test_wrong_type),
      cmocka_unit_test(test_unknown_key),    cmocka_unit_test(test_bad_choice),
      cmocka_unit_test(test_non_physical),   cmocka_unit_test(test_inconsistent),
      cmocka_unit_test(test_tables),         cmocka_unit_test(test_initial_table),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
