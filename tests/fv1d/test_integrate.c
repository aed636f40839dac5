/* The integrator: ARKODE adaptivity and named ERK tables reach the accuracy of the default fixed
 * CFL step; failures (vacuum at an open end, step limit) stop the run with a message naming the
 * cause; the output writer produces every file with the documented columns. */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "helpers.h"

/* Smooth periodic acoustic field; returns the L1 distance to the state of a reference run. */
static void smooth_params(struct fv1d_params *p, double *tout) {
  th_params(p, 0.0, 1.0, 100, 1000.0, 20.0, 7.0);
  p->bc[0].type = p->bc[1].type = FV1D_BC_PERIODIC;
  p->recon = FV1D_RECON_MC;
  p->flux = FV1D_FLUX_HLL;
  p->t_end = *tout;
  p->output_times = tout, p->noutput = 1;
}

static void set_smooth(struct fv1d_solver *s) {
  double *y = fv1d_solver_state(s);
  for (long i = 0; i < fv1d_solver_cells(s); ++i) {
    double x = fv1d_solver_x(s, i), rho = 1000.0 * (1.0 + 2e-3 * sin(FV1D_TEST_TWO_PI * x));
    y[2 * i] = rho, y[2 * i + 1] = rho * 0.04 * sin(FV1D_TEST_TWO_PI * x);
  }
}

static double run_and_diff(const char *method, int adaptive, const double *ref, double *mass_err,
                           long *steps) {
  double tout = 0.03;
  struct fv1d_params p;
  smooth_params(&p, &tout);
  snprintf(p.method, sizeof p.method, "%s", method);
  p.adaptive = adaptive;
  p.rtol = 1e-8, p.atol = 1e-10;
  struct fv1d_solver *s = fv1d_solver_create(&p);
  set_smooth(s);
  double tot0[3], tot1[3];
  fv1d_totals(s, fv1d_solver_state(s), tot0);
  struct fv1d_stats stats;
  th_run(s, &p, tout, &stats);
  fv1d_totals(s, fv1d_solver_state(s), tot1);
  *mass_err = fabs(tot1[0] - tot0[0]) / tot0[0];
  *steps = stats.steps;
  double diff = 0.0;
  const double *y = fv1d_solver_state(s);
  for (long i = 0; i < 100; ++i) diff += fabs(y[2 * i] - (ref ? ref[i] : 0.0)) * 0.01;
  fv1d_solver_destroy(s);
  return diff;
}

static void test_adaptive_and_tables(void **state) {
  (void)state;
  /* reference: ssprk3 at a quarter of the default Courant number */
  double tout = 0.03;
  struct fv1d_params p;
  smooth_params(&p, &tout);
  p.cfl = 0.05;
  struct fv1d_solver *s = fv1d_solver_create(&p);
  set_smooth(s);
  struct fv1d_stats stats;
  th_run(s, &p, tout, &stats);
  double ref[100];
  for (long i = 0; i < 100; ++i) ref[i] = fv1d_solver_state(s)[2 * i];
  fv1d_solver_destroy(s);

  double mass_err, d;
  long steps, steps_fixed;
  double d_fixed = run_and_diff("ssprk3", 0, ref, &mass_err, &steps_fixed);
  assert_true(mass_err < 1e-14);
  const char *methods[] = {"ssprk3", "ARKODE_BOGACKI_SHAMPINE_4_2_3",
                           "ARKODE_DORMAND_PRINCE_7_4_5"};
  for (int k = 0; k < 3; ++k) {
    d = run_and_diff(methods[k], 1, ref, &mass_err, &steps);
    printf("adaptive %-30s steps %4ld  L1 difference %.3e (fixed ssprk3: %ld steps, %.3e)\n",
           methods[k], steps, d, steps_fixed, d_fixed);
    assert_true(mass_err < 1e-14);
    assert_true(d < 10.0 * d_fixed + 1e-9);
  }
  d = run_and_diff("ARKODE_BOGACKI_SHAMPINE_4_2_3", 0, ref, &mass_err, &steps);
  assert_true(steps == steps_fixed && d < 2.0 * d_fixed + 1e-12);
}

/* The default SSP-RK3 table is third order in time: on a fixed mesh, the distance to a run with a
 * tiny step falls as cfl³. */
static void test_time_order(void **state) {
  (void)state;
  const double cfl[4] = {0.8, 0.4, 0.2, 0.0125};
  double rho[4][100];
  for (int k = 0; k < 4; ++k) {
    double tout = 0.03;
    struct fv1d_params p;
    smooth_params(&p, &tout);
    p.recon = FV1D_RECON_NONE; /* smooth in time: no limiter switching between runs */
    p.cfl = cfl[k];
    struct fv1d_solver *s = fv1d_solver_create(&p);
    set_smooth(s);
    struct fv1d_stats stats;
    th_run(s, &p, tout, &stats);
    for (long i = 0; i < 100; ++i) rho[k][i] = fv1d_solver_state(s)[2 * i];
    fv1d_solver_destroy(s);
  }
  double err[3];
  for (int k = 0; k < 3; ++k) {
    err[k] = 0.0;
    for (long i = 0; i < 100; ++i) err[k] += fabs(rho[k][i] - rho[3][i]) * 0.01;
  }
  double order1 = log(err[0] / err[1]) / log(2.0), order2 = log(err[1] / err[2]) / log(2.0);
  printf("ssprk3 in time: differences %.3e %.3e %.3e, orders %.2f %.2f\n", err[0], err[1], err[2],
         order1, order2);
  assert_true(order1 > 2.7 && order2 > 2.7);
}

static void test_failures(void **state) {
  (void)state;
  /* an outflow at 0.9 c0 through the left end expands the fluid beyond vacuum (ξ = 7:
   * ψ(ρ0) = c0/3 < 0.9 c0) */
  double tout = 0.01;
  struct fv1d_params p;
  th_params(&p, 0.0, 1.0, 20, 1000.0, 20.0, 7.0);
  p.bc[0].type = FV1D_BC_OPEN, p.bc[0].imposed = RMN_IMPOSE_VELOCITY;
  p.bc[0].signal.kind = FV1D_SIGNAL_CONSTANT, p.bc[0].signal.value = -18.0;
  p.bc[1].type = FV1D_BC_WALL;
  p.t_end = tout, p.output_times = &tout, p.noutput = 1;
  struct fv1d_solver *s = fv1d_solver_create(&p);
  struct fv1d_stats stats;
  assert_int_equal(fv1d_integrate(s, NULL, NULL, &stats), -1);
  const char *msg = fv1d_solver_error(s);
  printf("expected failure: %s\n", msg);
  assert_non_null(strstr(msg, "left end"));
  assert_non_null(strstr(msg, "RMN_ECAVITATION"));
  assert_non_null(strstr(msg, "integrate.c"));
  assert_non_null(strstr(msg, "ERKStepEvolve"));
  fv1d_solver_destroy(s);

  /* the step limit */
  p.bc[0].type = FV1D_BC_WALL;
  p.max_steps = 3;
  s = fv1d_solver_create(&p);
  /* the step limit stops the run (status 1: not a failure, not complete either) */
  assert_int_equal(fv1d_integrate(s, NULL, NULL, &stats), 1);
  assert_non_null(strstr(fv1d_solver_error(s), "max_steps"));
  assert_int_equal(stats.steps, 3);
  fv1d_solver_destroy(s);
}

static void test_outputs(void **state) {
  (void)state;
  double times[2] = {0.004, 0.01};
  struct fv1d_params p;
  th_params(&p, 0.0, 1.0, 30, 1000.0, 20.0, 7.0);
  p.bc[0].type = FV1D_BC_OPEN, p.bc[0].imposed = RMN_IMPOSE_PRESSURE;
  p.bc[0].signal.kind = FV1D_SIGNAL_CONSTANT, p.bc[0].signal.value = 1234.5;
  p.bc[1].type = FV1D_BC_WALL;
  p.t_end = 0.01, p.output_times = times, p.noutput = 2;
  p.series_every = 5;
  const char *dir = "fv1d_test_outputs";
  struct fv1d_solver *s = fv1d_solver_create(&p);
  struct fv1d_output *out = fv1d_output_open(dir, s);
  assert_non_null(out);
  struct fv1d_stats stats;
  assert_int_equal(fv1d_integrate(s, fv1d_output_observer, out, &stats), 0);
  assert_int_equal(fv1d_output_close(out, &stats, 0), 0);
  fv1d_solver_destroy(s);
  char line[1024];
  const char *files[] = {"profile_0000.csv", "profile_0001.csv", "profile_0002.csv"};
  for (int k = 0; k < 3; ++k) {
    snprintf(line, sizeof line, "%s/%s", dir, files[k]);
    FILE *f = fopen(line, "r");
    assert_non_null(f);
    assert_non_null(fgets(line, sizeof line, f));
    assert_string_equal(line, "x,rho,u,p\n");
    int rows = 0;
    while (fgets(line, sizeof line, f)) ++rows;
    assert_int_equal(rows, 30);
    fclose(f);
  }
  snprintf(line, sizeof line, "%s/series.csv", dir);
  FILE *f = fopen(line, "r");
  assert_non_null(f);
  assert_non_null(fgets(line, sizeof line, f));
  assert_non_null(strstr(line, "t,mass,momentum,energy,flux_mass_left"));
  assert_non_null(strstr(line, "mass_balance,momentum_balance,energy_dissipated"));
  double last_balance = 1.0;
  int rows = 0;
  while (fgets(line, sizeof line, f)) { /* mass_balance is column 17 */
    char *save = NULL, *tok = strtok_r(line, ",", &save);
    for (int c = 1; c < 17; ++c) tok = strtok_r(NULL, ",", &save);
    last_balance = strtod(tok, NULL);
    ++rows;
  }
  fclose(f);
  assert_true(rows >= 3);
  assert_true(fabs(last_balance) < 1e-12 * 1000.0);
  snprintf(line, sizeof line, "%s/summary.yaml", dir);
  f = fopen(line, "r");
  assert_non_null(f);
  int success = 0;
  while (fgets(line, sizeof line, f)) success |= strcmp(line, "status: success\n") == 0;
  fclose(f);
  assert_true(success);
}

int main(void) {
  gsl_set_error_handler_off();
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_adaptive_and_tables),
      cmocka_unit_test(test_time_order),
      cmocka_unit_test(test_failures),
      cmocka_unit_test(test_outputs),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
