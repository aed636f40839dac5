/*
 * `sabre-sph scalar` (sph_cmd_scalar): a short Robin-wave run writes its files with the reference
 * and errors; bad cases stop with exit code 2 and a message naming the key.
 */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_scalar.h"
#include "testutil.h"
/* after testutil.h */
#include "sph_testfiles.h"

static const char *const wave_case =
    "geometry:\n"
    "  dimension: 1\n"
    "  dr: 0.02\n"
    "  h_over_dr: 2\n"
    "  walls:\n"
    "    - {type: interval, lo: [0], hi: [1]}\n"
    "  fluid:\n"
    "    - {type: box, lo: [0.01], hi: [0.99]}\n"
    "scalar:\n"
    "  initial:\n"
    "    u_t: {type: sin, wavelength: 1}\n"
    "  boundaries:\n"
    "    - {type: robin, mu: [-1, 1, 0], order: 2}\n"
    "  reference: {type: robin_wave, terms: 200}\n"
    "time:\n"
    "  end: 0.25\n"
    "  dt: 0.002\n"
    "output:\n"
    "  profile_times: [0.1, 0.22]\n";

struct run_args {
  const char *case_path, *out;
  const char *sets[4];
};

static int run_cmd(void *arg) {
  const struct run_args *r = arg;
  char *argv[16];
  int argc = 0;
  argv[argc++] = "scalar";
  argv[argc++] = (char *)r->case_path;
  argv[argc++] = "--output";
  argv[argc++] = (char *)r->out;
  for (int i = 0; i < 4 && r->sets[i]; i++) {
    argv[argc++] = "--set";
    argv[argc++] = (char *)r->sets[i];
  }
  return sph_cmd_scalar(argc, argv);
}

static int count_lines(const char *text) {
  int n = 0;
  for (const char *p = text; *p; p++) n += *p == '\n';
  return n;
}

static void test_run(void **state) {
  (void)state;
  char path[256], out[256], log[8192];
  snprintf(path, sizeof path, "%s", test_write("wave.yaml", wave_case));
  snprintf(out, sizeof out, "%s", test_path("run"));
  struct run_args a = {path, out, {NULL}};
  int rc = test_capture(run_cmd, &a, log, sizeof log);
  printf("%s", log);
  assert_int_equal(rc, 0);
  assert_non_null(strstr(log, "vertex layer 0.5 dr"));
  assert_non_null(strstr(log, "boundary error |u_v - u_ref|"));
  static char buf[1 << 20];
  test_read("run/series.csv", buf, sizeof buf);
  const char *header = "time,u_v0,u_v1,ref_v0,ref_v1,err_v0,err_v1,err_mean,err_max\n";
  assert_int_equal(strncmp(buf, header, strlen(header)), 0);
  assert_int_equal(count_lines(buf), 1 + 1 + 125); /* header, t = 0, 125 steps of 0.002 */
  test_read("run/profiles.csv", buf, sizeof buf);
  /* 4 times (0, 0.1, 0.22, 0.25) × (49 fluid + 2 vertices) */
  assert_int_equal(count_lines(buf), 1 + 4 * 51);
  test_read("run/vertices.csv", buf, sizeof buf);
  assert_non_null(strstr(buf, "0,0,0,0,1,0,0,0,0.01"));
  test_read("run/used_case.yaml", buf, sizeof buf);
  assert_non_null(strstr(buf, "vertex_layer: \"auto\"")); /* defaults are written quoted */
  assert_non_null(strstr(buf, "cfl: 0.5"));
}

static void expect_input_error(const char *text, const char *set, const char *what) {
  char path[256], out[256], log[8192];
  snprintf(path, sizeof path, "%s", test_write("bad.yaml", text));
  snprintf(out, sizeof out, "%s", test_path("bad"));
  struct run_args a = {path, out, {set, NULL}};
  int rc = test_capture(run_cmd, &a, log, sizeof log);
  if (rc != CMN_EXIT_INPUT || !strstr(log, what))
    fail_msg("--set %s: exit %d, expected %d with '%s' in:\n%s", set ? set : "(none)", rc,
             CMN_EXIT_INPUT, what, log);
}

static void test_errors(void **state) {
  (void)state;
  expect_input_error(wave_case, "scalar.speed=2", "unknown key 'scalar.speed'");
  expect_input_error(wave_case, "scalar.boundaries[0].mu=[1, 0, 0]", "mu2 must not be 0");
  expect_input_error(wave_case, "scalar.boundaries[0].type=diriclet", "expected one of");
  expect_input_error(wave_case, "scalar.initial.u_t.wavelength=0.5",
                     "the initial data differ from the reference's");
  expect_input_error(wave_case, "scalar.c=2", "robin_wave is the series M(78) for d = 1 and c = 1");
  expect_input_error(wave_case, "time.dt=0.05", "exceeds the stability limit");
  expect_input_error(wave_case, "scalar.boundaries[0].wall=1", "scalar.boundaries[0].wall");
  expect_input_error(wave_case,
                     "scalar.boundaries[0]={type: robin, mu: [-1, 1, 0], wall: 0, edges: [1]}",
                     "no entry covers element 2 of geometry.walls[0]");
  expect_input_error(wave_case, "scalar.vertex_layer=thick", "expected 'auto' or a number");
  expect_input_error(wave_case, "output.profile_times=[0.2, 0.1]", "must increase strictly");
  expect_input_error(wave_case, "scalar.boundaries[0].order=6",
                     "fewer than m distinct fluid distances");
}

int main(void) {
  gsl_set_error_handler_off();
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_run),
      cmocka_unit_test(test_errors),
  };
  return cmocka_run_group_tests(tests, test_dir_setup, test_dir_teardown);
}
