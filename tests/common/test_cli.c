/* The command line of the case-file programs (cmn_cli_*): options in any order, program options
 * with and without a value, --help, loading with --set overrides, used_case.yaml; and every error,
 * in a child process, with its exact message and exit code. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sabre/common.h"
#include "testutil.h"

static const char usage[] = "usage: sabre-test run CASE.yaml [--threads N] [--quiet]\n";

/* The options of the command under test; the values land in these. */
static const char *threads, *restart, *quiet;
static const struct cmn_cli_option options[] = {
    {"--threads", &threads, 0}, {"--restart", &restart, 0}, {"--quiet", &quiet, 1}};

/* A scratch directory with a case file in it. */
static char base[] = "/tmp/sabre_test_cli_XXXXXX";
static char case_path[256];

static void make_case(void) {
  if (case_path[0] != '\0') return;
  assert_non_null(mkdtemp(base));
  snprintf(case_path, sizeof case_path, "%s/case.yaml", base);
  FILE *f = fopen(case_path, "w");
  assert_non_null(f);
  fputs("fluid:\n  c0: 12.75\n  rho0: 1000\n", f);
  assert_int_equal(fclose(f), 0);
}

static int argc_of(char **argv) {
  int n = 0;
  while (argv[n] != NULL) n++;
  return n;
}

static void test_parse(void **state) {
  (void)state;
  threads = restart = quiet = NULL;
  char *argv[] = {"run",     "--set", "a=1",        "case.yaml", "--threads", "4",
                  "--quiet", "--set", "b.c=[1, 2]", "--output",  "o2",        NULL};
  struct cmn_cli cli;
  assert_int_equal(cmn_cli_parse(&cli, argc_of(argv), argv, "run", usage, "def", options, 3), 0);
  assert_string_equal(cli.command, "run");
  assert_string_equal(cli.case_path, "case.yaml");
  assert_string_equal(cli.output, "o2");
  assert_int_equal(cli.nsets, 2);
  assert_string_equal(cli.sets[0], "a=1");
  assert_string_equal(cli.sets[1], "b.c=[1, 2]");
  assert_string_equal(threads, "4");
  assert_ptr_equal(quiet, options[2].name); /* a flag receives its name */
  assert_null(restart);                     /* absent: left alone */
  free(cli.sets);

  /* The default output, no program options, nothing else. */
  char *plain[] = {"sabre-test", "case.yaml", NULL};
  assert_int_equal(cmn_cli_parse(&cli, 2, plain, NULL, usage, "def", NULL, 0), 0);
  assert_null(cli.command);
  assert_string_equal(cli.case_path, "case.yaml");
  assert_string_equal(cli.output, "def");
  assert_int_equal(cli.nsets, 0);
  free(cli.sets);
}

/* --help and -h print the usage on stdout (captured here with stderr) wherever they stand. */
static char **help_argv;
static void help_body(void) {
  dup2(2, 1);
  struct cmn_cli cli;
  int rc = cmn_cli_parse(&cli, argc_of(help_argv), help_argv, "run", usage, "def", options, 3);
  fflush(stdout);
  _exit(rc == 1 && cli.sets == NULL ? 0 : 3);
}

static void test_help(void **state) {
  (void)state;
  char *first[] = {"run", "--help", NULL};
  char *last[] = {"run", "case.yaml", "--set", "a=1", "--threads", "2", "-h", NULL};
  char *both[] = {"run", "-h", "--frobnicate", NULL};
  char **cases[] = {first, last, both};
  char out[1024];
  for (int i = 0; i < 3; i++) {
    help_argv = cases[i];
    assert_int_equal(sabre_run_child(help_body, out, sizeof out), 0);
    assert_string_equal(out, usage);
  }
}

/* Errors: each runs in a child that must exit with CMN_EXIT_INPUT and this message. */
static char **child_argv;
static const char *child_command;
static void parse_body(void) {
  cmn_set_program_name("sabre-test");
  struct cmn_cli cli;
  cmn_cli_parse(&cli, argc_of(child_argv), child_argv, child_command, usage, "def", options, 3);
  _exit(0);
}

static void test_parse_errors(void **state) {
  (void)state;
  static struct {
    const char *command;
    char *argv[8];
    const char *want;
  } bad[] = {
      {"run", {"run", "c.yaml", "--set"}, "run: --set: missing value (see --help)"},
      {NULL, {"fv1d", "c.yaml", "--output"}, "--output: missing value (see --help)"},
      {"run", {"run", "--threads"}, "run: --threads: missing value (see --help)"},
      {"run",
       {"run", "c.yaml", "--frobnicate", "1"},
       "run: unknown option '--frobnicate' (see --help)"},
      {NULL, {"fv1d", "c.yaml", "-"}, "unknown option '-' (see --help)"},
      {"run", {"run", "--x", "--help"}, "run: unknown option '--x' (see --help)"},
      {"run",
       {"run", "a.yaml", "--quiet", "b.yaml"},
       "run: one case file only ('a.yaml' and 'b.yaml')"},
      {"run", {"run"}, "run: missing case file (see --help)"},
      {NULL, {"fv1d", "--quiet", "--set", "a=1"}, "missing case file (see --help)"},
      /* each option once (--set may repeat): no silent override */
      {"run",
       {"run", "c.yaml", "--output", "o1", "--output", "o2"},
       "run: --output given twice: give each option once"},
      {"run",
       {"run", "c.yaml", "--threads", "1", "--threads", "2"},
       "run: --threads given twice: give each option once"},
      {NULL,
       {"fv1d", "c.yaml", "--quiet", "--quiet"},
       "--quiet given twice: give each option once"},
      /* an option's value is not the case file */
      {"run", {"run", "--threads", "c.yaml"}, "run: missing case file (see --help)"},
  };
  char out[1024], want[1024];
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    child_argv = bad[i].argv;
    child_command = bad[i].command;
    snprintf(want, sizeof want, "sabre-test: error: %s\n", bad[i].want);
    int rc = sabre_run_child(parse_body, out, sizeof out);
    if (rc != CMN_EXIT_INPUT || strcmp(out, want) != 0)
      fail_msg("case %zu: exit %d, '%s' instead of '%s'", i, rc, out, want);
  }
}

static void test_load_and_write(void **state) {
  (void)state;
  make_case();
  char *argv[] = {"run", case_path, "--set", "fluid.c0=2.385", "--set", "fluid.mu=[1, 2.5]", NULL};
  struct cmn_cli cli;
  assert_int_equal(cmn_cli_parse(&cli, 6, argv, "run", usage, "def", options, 3), 0);
  struct cmn_case *c = cmn_cli_load(&cli);
  assert_null(cli.sets);
  assert_int_equal(cli.nsets, 0);
  assert_string_equal(cmn_case_name(c), case_path);
  double c0, rho0, mu[2], cfl;
  assert_int_equal(cmn_case_get_double(c, "fluid.c0", 0.0, 1e9, &c0), 0);
  assert_rel(c0, 2.385, 0.0);
  assert_int_equal(cmn_case_get_double(c, "fluid.rho0", 0.0, 1e9, &rho0), 0);
  assert_rel(rho0, 1000.0, 0.0);
  assert_int_equal(cmn_case_get_doubles(c, "fluid.mu", 2, 2, mu, NULL), 0);
  assert_rel(mu[1], 2.5, 0.0);
  assert_int_equal(cmn_case_opt_double(c, "time.cfl", 0.4, 0.0, 1.0, &cfl), 0);

  /* used_case.yaml in a new nested directory: overrides and defaults included. */
  char dir[512], path[600];
  snprintf(dir, sizeof dir, "%s/out/run", base);
  cmn_cli_write_used(c, dir);
  cmn_case_free(c);
  snprintf(path, sizeof path, "%s/used_case.yaml", dir);
  char err[512];
  struct cmn_case *u = cmn_case_load(path, err, sizeof err);
  if (u == NULL) fail_msg("%s", err);
  assert_int_equal(cmn_case_get_double(u, "fluid.c0", 0.0, 1e9, &c0), 0);
  assert_rel(c0, 2.385, 0.0);
  assert_int_equal(cmn_case_get_double(u, "time.cfl", 0.0, 1.0, &cfl), 0);
  assert_rel(cfl, 0.4, 0.0);
  assert_int_equal(cmn_case_get_doubles(u, "fluid.mu", 2, 2, mu, NULL), 0);
  assert_rel(mu[0], 1.0, 0.0);
  cmn_case_free(u);
  /* Writing again into the existing directory replaces the file. */
  c = cmn_case_load(case_path, err, sizeof err);
  assert_non_null(c);
  cmn_cli_write_used(c, dir);
  cmn_case_free(c);
  u = cmn_case_load(path, err, sizeof err);
  assert_non_null(u);
  assert_int_equal(cmn_case_get_double(u, "fluid.c0", 0.0, 1e9, &c0), 0);
  assert_rel(c0, 12.75, 0.0);
  assert_int_equal(cmn_case_has(u, "time"), 0);
  cmn_case_free(u);
  remove(path);
  rmdir(dir);
  snprintf(dir, sizeof dir, "%s/out", base);
  rmdir(dir);
}

/* Loading errors: the case's own message (file, and the --set assignment). */
static void load_body(void) {
  cmn_set_program_name("sabre-test");
  struct cmn_cli cli;
  cmn_cli_parse(&cli, argc_of(child_argv), child_argv, "run", usage, "def", options, 3);
  cmn_cli_load(&cli);
  _exit(0);
}

static void test_load_errors(void **state) {
  (void)state;
  make_case();
  char missing[300];
  snprintf(missing, sizeof missing, "%s/missing.yaml", base);
  char *no_file[] = {"run", missing, NULL};
  char *no_equal[] = {"run", case_path, "--set", "fluid.c0=3", "--set", "fluid.c0", NULL};
  char *bad_path[] = {"run", case_path, "--set", "fluid..c0=3", NULL};
  char *bad_value[] = {"run", case_path, "--set", "fluid.c0=[1, 2", NULL};
  /* The message: the file name, then `what` (all of it, or its start when `prefix`: the rest is
   * libyaml's). */
  struct {
    char **argv;
    const char *file, *what;
    int prefix;
  } bad[] = {
      {no_file, missing, ": cannot open: No such file or directory\n", 0},
      {no_equal, case_path, ": --set 'fluid.c0': expected key=value\n", 0},
      {bad_path, case_path, ": --set 'fluid..c0=3': malformed key path 'fluid..c0'\n", 0},
      {bad_value, case_path, ": --set 'fluid.c0=[1, 2': cannot parse the value: ", 1},
  };
  char out[1024], want[1024];
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    child_argv = bad[i].argv;
    snprintf(want, sizeof want, "sabre-test: error: %s%s", bad[i].file, bad[i].what);
    int rc = sabre_run_child(load_body, out, sizeof out);
    size_t n = bad[i].prefix ? strlen(want) : sizeof want;
    if (rc != CMN_EXIT_INPUT || strncmp(out, want, n) != 0)
      fail_msg("case %zu: exit %d, '%s' instead of '%s'", i, rc, out, want);
  }
}

/* The run directory cannot be made, or used_case.yaml cannot be written in it. */
static const char *write_dir;
static void write_body(void) {
  cmn_set_program_name("sabre-test");
  char err[512];
  struct cmn_case *c = cmn_case_load(case_path, err, sizeof err);
  if (c == NULL) _exit(4);
  cmn_cli_write_used(c, write_dir);
  _exit(0);
}

static void test_write_errors(void **state) {
  (void)state;
  make_case();
  char dir[300], out[1024], want[1024];
  /* The case file stands where a directory should be. */
  snprintf(dir, sizeof dir, "%s/sub", case_path);
  write_dir = dir;
  assert_int_equal(sabre_run_child(write_body, out, sizeof out), CMN_EXIT_INPUT);
  snprintf(want, sizeof want,
           "sabre-test: error: cannot create the output directory '%s': Not a directory\n", dir);
  assert_string_equal(out, want);
  /* A directory stands where used_case.yaml should be. */
  char blocker[400];
  snprintf(dir, sizeof dir, "%s/blocked", base);
  snprintf(blocker, sizeof blocker, "%s/used_case.yaml", dir);
  assert_int_equal(cmn_mkdir_p(blocker), 0);
  assert_int_equal(sabre_run_child(write_body, out, sizeof out), CMN_EXIT_INPUT);
  snprintf(want, sizeof want, "sabre-test: error: cannot write '%s': Is a directory\n", blocker);
  assert_string_equal(out, want);
  rmdir(blocker);
  rmdir(dir);
}

static int teardown(void **state) {
  (void)state;
  if (case_path[0] != '\0') {
    remove(case_path);
    rmdir(base);
  }
  return 0;
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_parse),        cmocka_unit_test(test_help),
      cmocka_unit_test(test_parse_errors), cmocka_unit_test(test_load_and_write),
      cmocka_unit_test(test_load_errors),  cmocka_unit_test(test_write_errors),
  };
  return cmocka_run_group_tests(tests, NULL, teardown);
}
