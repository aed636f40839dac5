/* Messages and exit codes (in child processes), checked allocation, strict CLI number parsing,
 * mkdir -p and progress lines. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sabre/common.h"
#include "testutil.h"

static void say_things(void) {
  cmn_message("reading %s", "case.yaml");
  cmn_set_program_name("./build/fv1d");
  cmn_warning("cfl = %g is large", 0.95);
  cmn_set_program_name(NULL);
  cmn_message("back to default");
  fflush(stderr);
  _exit(0);
}

static void input_error(void) {
  cmn_set_program_name("sph");
  cmn_input_error("--np: expected a positive integer, got '%s'", "x");
}

/* cmn_error() below sits three lines after this one. */
enum { RUN_ERROR_LINE = __LINE__ + 3 };
static void run_error(void) {
  cmn_set_program_name("fv1d");
  cmn_error("particle %d lost", 42);
}

static void test_messages(void **state) {
  (void)state;
  char out[1024], expected[1024];
  assert_int_equal(sabre_run_child(say_things, out, sizeof out), 0);
  assert_string_equal(out,
                      "sabre: reading case.yaml\nfv1d: warning: cfl = 0.95 is large\n"
                      "sabre: back to default\n");
  assert_int_equal(sabre_run_child(input_error, out, sizeof out), CMN_EXIT_INPUT);
  assert_string_equal(out, "sph: error: --np: expected a positive integer, got 'x'\n");
  assert_int_equal(sabre_run_child(run_error, out, sizeof out), CMN_EXIT_FAILURE);
  /* "fv1d: error: <path>/test_message.c:<line>: run_error(): particle 42 lost" */
  assert_true(strncmp(out, "fv1d: error: ", 13) == 0);
  snprintf(expected, sizeof expected, "test_message.c:%d: run_error(): particle 42 lost\n",
           RUN_ERROR_LINE);
  if (strstr(out, expected) == NULL) fail_msg("'%s' lacks '%s'", out, expected);
}

static void test_alloc(void **state) {
  (void)state;
  double *a = cmn_malloc(10 * sizeof *a);
  for (int i = 0; i < 10; ++i) a[i] = 2.385 * i;
  a = cmn_realloc(a, 1000 * sizeof *a);
  assert_rel(a[9], 2.385 * 9, 0.0);
  free(a);
  int *z = cmn_calloc(100, sizeof *z);
  for (int i = 0; i < 100; ++i) assert_int_equal(z[i], 0);
  free(z);
  /* Zero sizes still give a pointer that free() accepts. */
  free(cmn_malloc(0));
  free(cmn_calloc(0, 8));
  free(cmn_realloc(NULL, 0));
}

static void test_parse_double(void **state) {
  (void)state;
  sabre_fp_traps_on();
  double x = -7.0;
  const char *good[] = {"2.385", "-1e-3", "+4", "0", "1E5", ".5", "1e-310", "0x1p-2"};
  const double value[] = {2.385, -1e-3, 4.0, 0.0, 1e5, 0.5, 1e-310, 0.25};
  for (int i = 0; i < 8; ++i) {
    assert_int_equal(cmn_parse_double(good[i], &x), 0);
    assert_rel(x, value[i], 0.0);
  }
  x = -7.0;
  const char *bad[] = {"",    " 1",        "1 ",    "1,",  "abc", "1.5x", "nan",
                       "inf", "-Infinity", "1e400", "--1", "1e",  "\t2"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; ++i) {
    if (cmn_parse_double(bad[i], &x) != -1) fail_msg("'%s' accepted", bad[i]);
  }
  assert_int_equal(cmn_parse_double(NULL, &x), -1);
  assert_rel(x, -7.0, 0.0);
  sabre_fp_traps_off();
}

static void test_parse_doubles(void **state) {
  (void)state;
  sabre_fp_traps_on();
  double v[4] = {-1, -1, -1, -1};
  assert_int_equal(cmn_parse_doubles("1.5,-2.25, 3e2", v, 4), 3);
  assert_rel(v[0], 1.5, 0.0);
  assert_rel(v[1], -2.25, 0.0);
  assert_rel(v[2], 300.0, 0.0);
  assert_rel(v[3], -1.0, 0.0);
  assert_int_equal(cmn_parse_doubles("2.385", v, 1), 1);
  assert_rel(v[0], 2.385, 0.0);
  const char *bad[] = {"", "1,,2", "1,", ",1", "1,x", "1,2,3,4,5", "1;2", "1e999,1"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; ++i) {
    double w[4] = {9, 9, 9, 9};
    if (cmn_parse_doubles(bad[i], w, 4) != -1) fail_msg("'%s' accepted", bad[i]);
    /* Nothing written on failure. */
    for (int k = 0; k < 4; ++k) assert_rel(w[k], 9.0, 0.0);
  }
  assert_int_equal(cmn_parse_doubles("1", v, 0), -1);
  sabre_fp_traps_off();
}

static void test_parse_long(void **state) {
  (void)state;
  long n = -5;
  assert_int_equal(cmn_parse_long("40000", 1, 100000, &n), 0);
  assert_int_equal(n, 40000);
  assert_int_equal(cmn_parse_long("-3", -10, 10, &n), 0);
  assert_int_equal(n, -3);
  assert_int_equal(cmn_parse_long("10", 0, 10, &n), 0);
  const char *bad[] = {"",   " 1", "1 ", "1.0", "1e3", "x", "0x10", "99999999999999999999999",
                       "11", "-1"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; ++i) {
    if (cmn_parse_long(bad[i], 0, 10, &n) != -1) fail_msg("'%s' accepted", bad[i]);
  }
  assert_int_equal(cmn_parse_long(NULL, 0, 10, &n), -1);
  assert_int_equal(n, 10);
}

static void test_mkdir_p(void **state) {
  (void)state;
  char base[] = "/tmp/sabre_test_mkdir_XXXXXX";
  assert_non_null(mkdtemp(base));
  char path[512];
  struct stat st;
  snprintf(path, sizeof path, "%s/a/b//c/", base);
  assert_int_equal(cmn_mkdir_p(path), 0);
  snprintf(path, sizeof path, "%s/a/b/c", base);
  assert_int_equal(stat(path, &st), 0);
  assert_true(S_ISDIR(st.st_mode));
  /* Existing directories are fine. */
  assert_int_equal(cmn_mkdir_p(path), 0);
  /* A file in the way is not. */
  snprintf(path, sizeof path, "%s/a/file", base);
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fclose(f);
  assert_int_equal(cmn_mkdir_p(path), -1);
  assert_int_equal(errno, ENOTDIR);
  snprintf(path, sizeof path, "%s/a/file/sub", base);
  assert_int_equal(cmn_mkdir_p(path), -1);
  assert_int_equal(errno, ENOTDIR);
  assert_int_equal(cmn_mkdir_p(""), -1);
  assert_int_equal(errno, ENOENT);
  /* Relative paths work too. */
  char cwd[512];
  assert_non_null(getcwd(cwd, sizeof cwd));
  assert_int_equal(chdir(base), 0);
  assert_int_equal(cmn_mkdir_p("rel/x"), 0);
  assert_int_equal(stat("rel/x", &st), 0);
  assert_int_equal(chdir(cwd), 0);

  const char *cleanup[] = {"rel/x", "rel", "a/b/c", "a/b", "a/file", "a", ""};
  for (size_t i = 0; i < sizeof cleanup / sizeof *cleanup; ++i) {
    snprintf(path, sizeof path, "%s/%s", base, cleanup[i]);
    remove(path);
  }
  assert_int_equal(stat(base, &st), -1);
}

static void progress_lines(void) {
  struct cmn_progress p;
  cmn_progress_start(&p, 0.0, 1.0);
  /* Pretend that 10 s of wall time went into the first quarter of the run. */
  p.wall_start -= 10.0;
  cmn_progress_report(&p, 1200, 0.25, 1.2e-5, 40000, 1);
  /* Not forced and within the interval: silent. */
  p.interval = 1e9;
  cmn_progress_report(&p, 1201, 0.26, 1.2e-5, 40000, 0);
  /* At the start the ETA is unknown; a negative count omits N. */
  cmn_progress_start(&p, 2.0, 2.0);
  cmn_progress_report(&p, 0, 2.0, 1e-3, -1, 1);
  p.enabled = 0;
  cmn_progress_report(&p, 1, 2.5, 1e-3, 10, 1);
  /* A task counted in iterations: 5 s of wall time for 1000 of 4000. */
  cmn_progress_start(&p, 0.0, 4000.0);
  p.wall_start -= 5.0;
  cmn_progress_task(&p, 1000.0, 1, "repacking: step %d of %d", 1000, 4000);
  p.interval = 1e9;
  cmn_progress_task(&p, 2000.0, 0, "silent within the interval");
  p.enabled = 0;
  cmn_progress_task(&p, 3000.0, 1, "silent when disabled");
  fflush(stderr);
  _exit(0);
}

static void test_progress(void **state) {
  (void)state;
  double t0 = cmn_wall_time();
  double t1 = cmn_wall_time();
  assert_true(t1 >= t0);
  assert_true(t0 > 0.0);
  char out[1024];
  assert_int_equal(sabre_run_child(progress_lines, out, sizeof out), 0);
  assert_string_equal(out,
                      "step 1200  t = 0.25 s  dt = 1.2e-05 s  N = 40000  ETA 00:00:30\n"
                      "step 0  t = 2 s  dt = 0.001 s  ETA --:--:--\n"
                      "repacking: step 1000 of 4000  ETA 00:00:15\n");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_messages),     cmocka_unit_test(test_alloc),
      cmocka_unit_test(test_parse_double), cmocka_unit_test(test_parse_doubles),
      cmocka_unit_test(test_parse_long),   cmocka_unit_test(test_mkdir_p),
      cmocka_unit_test(test_progress),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
