/* Case files: loading, every getter on good and bad input, messages with file:line:column, the
 * unused-key check, and fatal mode (exit 2, checked in a child process). */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sabre/common.h"
#include "testutil.h"

/* Line numbers below refer to this text: keep them in sync when editing it. */
static const char *const CASE_TEXT =
    "# SABRE test case\n"                    /* 1 */
    "fluid:\n"                               /* 2 */
    "  c0: 12.5\n"                           /* 3 */
    "  rho0: 998.2\n"                        /* 4 */
    "  name: water\n"                        /* 5 */
    "  flag: Yes\n"                          /* 6 */
    "  model: tait\n"                        /* 7 */
    "  gravity: [0.25, -9.81]\n"             /* 8 */
    "  bad:   abc\n"                         /* 9 */
    "regions:\n"                             /* 10 */
    "  - {min: [0, 0.5], max: [1, 2.385]}\n" /* 11 */
    "  - min: [1, 0]\n"                      /* 12 */
    "    max: [2, x]\n"                      /* 13 */
    "steps: 1200\n"                          /* 14 */
    "big: 1e6\n"                             /* 15 */
    "empty:\n"                               /* 16 */
    "quoted: \"1.5\"\n"                      /* 17 */
    "negative: -3.75\n";                     /* 18 */

static struct cmn_case *parse(const char *text) {
  char err[512];
  struct cmn_case *c = cmn_case_parse(text, "t.yaml", err, sizeof err);
  if (c == NULL) fail_msg("parse failed: %s", err);
  cmn_case_set_fatal(c, 0);
  return c;
}

/* The last error must contain `part`. */
static void expect_error(const struct cmn_case *c, const char *part) {
  const char *err = cmn_case_error(c);
  if (strstr(err, part) == NULL) fail_msg("error '%s' does not contain '%s'", err, part);
}

static void expect_parse_error(const char *text, const char *part) {
  char err[512] = "untouched";
  struct cmn_case *c = cmn_case_parse(text, "bad.yaml", err, sizeof err);
  assert_null(c);
  if (strstr(err, part) == NULL) fail_msg("error '%s' does not contain '%s'", err, part);
}

static int setup(void **state) {
  sabre_fp_traps_on();
  *state = parse(CASE_TEXT);
  return 0;
}

static int teardown(void **state) {
  cmn_case_free(*state);
  sabre_fp_traps_off();
  return 0;
}

static void test_parse_errors(void **state) {
  (void)state;
  expect_parse_error("a: [1, 2\nb: 3\n", "bad.yaml:2:2: did not find expected ',' or ']'");
  expect_parse_error("a: 1\n  b: 2\n", "bad.yaml:2:4: mapping values are not allowed");
  expect_parse_error("a: 1\nb: 2\na: 3\n",
                     "bad.yaml:3:1: duplicate key 'a' (first defined at line 1)");
  expect_parse_error("s:\n  x: 1\n  y: 2\n  x: 3\n", "bad.yaml:4:3: duplicate key 'x'");
  expect_parse_error("- 1\n- 2\n", "bad.yaml:1:1: expected a mapping");
  expect_parse_error("just text\n", "expected a mapping");
  expect_parse_error("", "bad.yaml: empty case file");
  expect_parse_error("# nothing\n", "bad.yaml: empty case file");
  expect_parse_error("a: 1\n---\nb: 2\n", "bad.yaml:2:1: more than one YAML document");
  expect_parse_error("a: &x 1\nb: *x\n", "bad.yaml:2:4: aliases");
  expect_parse_error("a: \"open\n", "bad.yaml:2:1:");
  expect_parse_error("[1, 2]: 3\n", "bad.yaml:1:1: mapping keys must be plain names");

  char err[512];
  assert_null(cmn_case_load("/nonexistent/dir/case.yaml", err, sizeof err));
  assert_non_null(strstr(err, "/nonexistent/dir/case.yaml: cannot open"));
  /* NULL err is accepted. */
  assert_null(cmn_case_parse("- 1\n", "x", NULL, 0));
}

static void test_load_file(void **state) {
  (void)state;
  char path[] = "/tmp/sabre_test_case_XXXXXX";
  int fd = mkstemp(path);
  assert_true(fd >= 0);
  FILE *f = fdopen(fd, "w");
  fputs(CASE_TEXT, f);
  fclose(f);
  char err[512];
  struct cmn_case *c = cmn_case_load(path, err, sizeof err);
  assert_non_null(c);
  assert_string_equal(cmn_case_name(c), path);
  assert_string_equal(cmn_case_error(c), "");
  double c0;
  assert_int_equal(cmn_case_get_double(c, "fluid.c0", -INFINITY, INFINITY, &c0), 0);
  assert_rel(c0, 12.5, 0.0);
  cmn_case_free(c);
  cmn_case_free(NULL);
  remove(path);
}

static void test_double(void **state) {
  struct cmn_case *c = *state;
  double x = 0;
  assert_int_equal(cmn_case_get_double(c, "fluid.c0", -INFINITY, INFINITY, &x), 0);
  assert_rel(x, 12.5, 0.0);
  assert_int_equal(cmn_case_get_double(c, "negative", -10.0, 0.0, &x), 0);
  assert_rel(x, -3.75, 0.0);
  assert_int_equal(cmn_case_get_positive(c, "fluid.rho0", &x), 0);
  assert_rel(x, 998.2, 0.0);
  /* A quoted number is still read as a number. */
  assert_int_equal(cmn_case_get_double(c, "quoted", -INFINITY, INFINITY, &x), 0);
  assert_rel(x, 1.5, 0.0);

  x = 7.0;
  assert_int_equal(cmn_case_get_double(c, "fluid.bad", -INFINITY, INFINITY, &x), -1);
  expect_error(c, "t.yaml:9:10: fluid.bad: expected a number, got 'abc'");
  assert_rel(x, 7.0, 0.0); /* untouched on error */
  assert_int_equal(cmn_case_get_positive(c, "fluid.bad", &x), -1);
  assert_string_equal(cmn_case_error(c),
                      "t.yaml:9:10: fluid.bad: expected a positive number, got 'abc'");
  assert_int_equal(cmn_case_get_positive(c, "negative", &x), -1);
  expect_error(c, "t.yaml:18:11: negative: expected a positive number, got '-3.75'");
  assert_int_equal(cmn_case_get_double(c, "fluid.c0", 0.0, 10.0, &x), -1);
  expect_error(c, "t.yaml:3:7: fluid.c0: expected a number in [0, 10], got '12.5'");
  assert_int_equal(cmn_case_get_double(c, "fluid.c0", 20.0, INFINITY, &x), -1);
  expect_error(c, "fluid.c0: expected a number >= 20, got '12.5'");
  assert_int_equal(cmn_case_get_double(c, "fluid.c0", -INFINITY, 1.5, &x), -1);
  expect_error(c, "fluid.c0: expected a number <= 1.5, got '12.5'");
  assert_int_equal(cmn_case_get_double(c, "fluid", -INFINITY, INFINITY, &x), -1);
  expect_error(c, "t.yaml:2:1: fluid: expected a number, got a mapping");
  assert_int_equal(cmn_case_get_double(c, "fluid.gravity", -INFINITY, INFINITY, &x), -1);
  expect_error(c, "fluid.gravity: expected a number, got a sequence");
  assert_int_equal(cmn_case_get_double(c, "empty", -INFINITY, INFINITY, &x), -1);
  expect_error(c, "t.yaml:16:7: empty: expected a number, got an empty value");

  /* Missing keys, at the top and inside a section (naming the section's line). */
  assert_int_equal(cmn_case_get_double(c, "fluid.c1", -INFINITY, INFINITY, &x), -1);
  assert_string_equal(cmn_case_error(c),
                      "t.yaml: fluid.c1: required key missing (in 'fluid' at line 2)");
  assert_int_equal(cmn_case_get_double(c, "solver.cfl", -INFINITY, INFINITY, &x), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml: solver.cfl: required key missing");
  assert_int_equal(cmn_case_get_positive(c, "regions[7].min", &x), -1);
  expect_error(c, "regions[7].min: required key missing");

  /* Paths through the wrong kind of node, and malformed paths. */
  assert_int_equal(cmn_case_get_double(c, "steps.x", -INFINITY, INFINITY, &x), -1);
  expect_error(c, "t.yaml:14:8: steps: expected a mapping, got a scalar");
  assert_int_equal(cmn_case_get_double(c, "fluid[0]", -INFINITY, INFINITY, &x), -1);
  expect_error(c, "fluid: expected a sequence, got a mapping");
  const char *bad_paths[] = {"",         "fluid..c0",  ".fluid",      "fluid.",   "[0]",
                             "regions[", "regions[x]", "regions[-1]", "regions]", "regions[0]x"};
  for (size_t i = 0; i < sizeof bad_paths / sizeof *bad_paths; ++i) {
    assert_int_equal(cmn_case_get_double(c, bad_paths[i], -INFINITY, INFINITY, &x), -1);
    expect_error(c, "malformed key path");
  }
}

static void test_opt_double(void **state) {
  struct cmn_case *c = *state;
  double x = 0;
  assert_int_equal(cmn_case_opt_double(c, "fluid.c0", 3.0, 0.0, 100.0, &x), 0);
  assert_rel(x, 12.5, 0.0);
  assert_int_equal(cmn_case_opt_double(c, "fluid.mu", 1.002e-3, 0.0, 1.0, &x), 0);
  assert_rel(x, 1.002e-3, 0.0);
  assert_true(cmn_case_has(c, "fluid.mu"));
  assert_int_equal(cmn_case_line(c, "fluid.mu"), 0); /* inserted, not from the file */
  /* The inserted default reads back as a value. */
  assert_int_equal(cmn_case_get_double(c, "fluid.mu", -INFINITY, INFINITY, &x), 0);
  assert_rel(x, 1.002e-3, 0.0);
  /* Defaults create missing sections. */
  assert_int_equal(cmn_case_opt_positive(c, "solver.time.cfl", 0.385, &x), 0);
  assert_rel(x, 0.385, 0.0);
  assert_int_equal(cmn_case_is_map(c, "solver.time"), 1);
  assert_int_equal(cmn_case_opt_positive(c, "fluid.rho0", 1.0, &x), 0);
  assert_rel(x, 998.2, 0.0);
  /* A present but bad value is an error, not a fallback to the default. */
  assert_int_equal(cmn_case_opt_double(c, "fluid.bad", 1.0, -INFINITY, INFINITY, &x), -1);
  expect_error(c, "t.yaml:9:10: fluid.bad: expected a number, got 'abc'");
  assert_int_equal(cmn_case_opt_positive(c, "negative", 1.0, &x), -1);
  expect_error(c, "negative: expected a positive number");
  assert_int_equal(cmn_case_opt_double(c, "fluid.c0", 1.0, 0.0, 1.0, &x), -1);
  expect_error(c, "expected a number in [0, 1], got '12.5'");
  /* A default cannot be placed below a scalar. */
  assert_int_equal(cmn_case_opt_double(c, "steps.x", 1.0, -INFINITY, INFINITY, &x), -1);
  expect_error(c, "steps: expected a mapping, got a scalar");
}

static void test_long(void **state) {
  struct cmn_case *c = *state;
  long n = 0;
  assert_int_equal(cmn_case_get_long(c, "steps", 0, LONG_MAX, &n), 0);
  assert_int_equal(n, 1200);
  assert_int_equal(cmn_case_get_long(c, "big", 1, 10000000, &n), 0);
  assert_int_equal(n, 1000000);
  assert_int_equal(cmn_case_get_long(c, "steps", 0, 1000, &n), -1);
  expect_error(c, "t.yaml:14:8: steps: expected an integer in [0, 1000], got '1200'");
  assert_int_equal(cmn_case_get_long(c, "steps", 2000, LONG_MAX, &n), -1);
  expect_error(c, "steps: expected an integer >= 2000, got '1200'");
  assert_int_equal(cmn_case_get_long(c, "steps", LONG_MIN, 5, &n), -1);
  expect_error(c, "steps: expected an integer <= 5, got '1200'");
  assert_int_equal(cmn_case_get_long(c, "quoted", LONG_MIN, LONG_MAX, &n), -1);
  expect_error(c, "quoted: expected an integer, got '1.5'");
  assert_int_equal(cmn_case_get_long(c, "fluid.name", LONG_MIN, LONG_MAX, &n), -1);
  expect_error(c, "t.yaml:5:9: fluid.name: expected an integer, got 'water'");
  assert_int_equal(cmn_case_get_long(c, "nsteps", 0, 10, &n), -1);
  expect_error(c, "t.yaml: nsteps: required key missing");
  assert_int_equal(n, 1000000);

  assert_int_equal(cmn_case_opt_long(c, "steps", 5, 0, LONG_MAX, &n), 0);
  assert_int_equal(n, 1200);
  assert_int_equal(cmn_case_opt_long(c, "output.every", 25, 1, 100, &n), 0);
  assert_int_equal(n, 25);
  assert_int_equal(cmn_case_get_long(c, "output.every", 1, 100, &n), 0);
  assert_int_equal(n, 25);
  assert_int_equal(cmn_case_opt_long(c, "fluid.c0", 1, 0, 100, &n), -1);
  expect_error(c, "fluid.c0: expected an integer in [0, 100], got '12.5'");
}

static void test_bool(void **state) {
  (void)state;
  struct cmn_case *c = parse(
      "a: true\nb: False\nc: YES\nd: no\ne: On\nf: off\ng: 1\nh: maybe\ni: [true]\nj: 'on'\n");
  int v = -1;
  const char *keys[] = {"a", "b", "c", "d", "e", "f", "j"};
  const int expected[] = {1, 0, 1, 0, 1, 0, 1};
  for (int i = 0; i < 7; ++i) {
    assert_int_equal(cmn_case_get_bool(c, keys[i], &v), 0);
    assert_int_equal(v, expected[i]);
  }
  assert_int_equal(cmn_case_get_bool(c, "g", &v), -1);
  expect_error(c, "t.yaml:7:4: g: expected a boolean (true/false, yes/no, on/off), got '1'");
  assert_int_equal(cmn_case_get_bool(c, "h", &v), -1);
  expect_error(c, "h: expected a boolean (true/false, yes/no, on/off), got 'maybe'");
  assert_int_equal(cmn_case_get_bool(c, "i", &v), -1);
  expect_error(c, "i: expected a boolean (true/false, yes/no, on/off), got a sequence");
  assert_int_equal(cmn_case_get_bool(c, "k", &v), -1);
  expect_error(c, "t.yaml: k: required key missing");
  assert_int_equal(cmn_case_opt_bool(c, "a", 0, &v), 0);
  assert_int_equal(v, 1);
  assert_int_equal(cmn_case_opt_bool(c, "k", 1, &v), 0);
  assert_int_equal(v, 1);
  assert_int_equal(cmn_case_opt_bool(c, "l", 0, &v), 0);
  assert_int_equal(v, 0);
  assert_int_equal(cmn_case_get_bool(c, "k", &v), 0);
  assert_int_equal(v, 1);
  assert_int_equal(cmn_case_opt_bool(c, "h", 1, &v), -1);
  cmn_case_free(c);
}

static void test_string_and_choice(void **state) {
  struct cmn_case *c = *state;
  const char *s = NULL;
  assert_int_equal(cmn_case_get_string(c, "fluid.name", &s), 0);
  assert_string_equal(s, "water");
  /* Any scalar is a string, numbers included. */
  assert_int_equal(cmn_case_get_string(c, "steps", &s), 0);
  assert_string_equal(s, "1200");
  assert_int_equal(cmn_case_get_string(c, "fluid", &s), -1);
  expect_error(c, "t.yaml:2:1: fluid: expected a string, got a mapping");
  assert_int_equal(cmn_case_get_string(c, "empty", &s), -1);
  expect_error(c, "empty: expected a string, got an empty value");
  assert_int_equal(cmn_case_get_string(c, "fluid.title", &s), -1);
  expect_error(c, "fluid.title: required key missing");
  assert_int_equal(cmn_case_opt_string(c, "fluid.title", "dam break", &s), 0);
  assert_string_equal(s, "dam break");
  assert_int_equal(cmn_case_opt_string(c, "fluid.name", "air", &s), 0);
  assert_string_equal(s, "water");
  assert_int_equal(cmn_case_opt_string(c, "fluid.gravity", "air", &s), -1);
  expect_error(c, "fluid.gravity: expected a string, got a sequence");

  static const char *const models[] = {"linear", "tait", "ideal", NULL};
  int k = -1;
  assert_int_equal(cmn_case_get_choice(c, "fluid.model", models, &k), 0);
  assert_int_equal(k, 1);
  assert_int_equal(cmn_case_get_choice(c, "fluid.name", models, &k), -1);
  assert_string_equal(cmn_case_error(c),
                      "t.yaml:5:9: fluid.name: expected one of: linear, tait, ideal; got 'water'");
  assert_int_equal(cmn_case_get_choice(c, "fluid.gravity", models, &k), -1);
  expect_error(c, "expected one of: linear, tait, ideal; got a sequence");
  assert_int_equal(cmn_case_get_choice(c, "fluid.eos", models, &k), -1);
  expect_error(c, "fluid.eos: required key missing");
  assert_int_equal(k, 1);
  assert_int_equal(cmn_case_opt_choice(c, "fluid.eos", models, 2, &k), 0);
  assert_int_equal(k, 2);
  assert_int_equal(cmn_case_get_choice(c, "fluid.eos", models, &k), 0);
  assert_int_equal(k, 2);
  assert_int_equal(cmn_case_opt_choice(c, "fluid.model", models, 0, &k), 0);
  assert_int_equal(k, 1);
  assert_int_equal(cmn_case_opt_choice(c, "fluid.bad", models, 0, &k), -1);
  expect_error(c, "t.yaml:9:10: fluid.bad: expected one of: linear, tait, ideal; got 'abc'");
}

static void test_doubles(void **state) {
  struct cmn_case *c = *state;
  double v[5] = {0};
  int count = -1;
  assert_int_equal(cmn_case_get_doubles(c, "fluid.gravity", 2, 0, v, NULL), 0);
  assert_rel(v[0], 0.25, 0.0);
  assert_rel(v[1], -9.81, 0.0);
  assert_int_equal(cmn_case_get_doubles(c, "fluid.gravity", 0, 5, v, &count), 0);
  assert_int_equal(count, 2);
  assert_int_equal(cmn_case_get_doubles(c, "fluid.gravity", 3, 0, v, &count), -1);
  expect_error(c, "t.yaml:8:3: fluid.gravity: expected a sequence of 3 numbers, got 2 elements");
  assert_int_equal(cmn_case_get_doubles(c, "fluid.gravity", 0, 1, v, &count), -1);
  expect_error(c, "fluid.gravity: expected a sequence of 1 number, got 2 elements");
  assert_int_equal(cmn_case_get_doubles(c, "fluid.c0", 1, 0, v, &count), -1);
  expect_error(c, "fluid.c0: expected a sequence of 1 number, got '12.5'");
  assert_int_equal(cmn_case_get_doubles(c, "regions[1].max", 2, 0, v, NULL), -1);
  expect_error(c, "t.yaml:13:14: regions[1].max[1]: expected a number, got 'x'");
  assert_int_equal(cmn_case_get_doubles(c, "regions[0].max", 2, 0, v, NULL), 0);
  assert_rel(v[0], 1.0, 0.0);
  assert_rel(v[1], 2.385, 0.0);
  assert_int_equal(cmn_case_get_doubles(c, "regions[2].max", 2, 0, v, NULL), -1);
  expect_error(c, "t.yaml: regions[2].max: required key missing");

  const double def[3] = {1.5, -2.25, 1e-300};
  double w[3];
  assert_int_equal(cmn_case_opt_doubles(c, "origin", 3, def, w), 0);
  assert_memory_equal(w, def, sizeof def);
  assert_int_equal(cmn_case_get_doubles(c, "origin", 3, 0, v, NULL), 0);
  assert_memory_equal(v, def, sizeof def);
  assert_int_equal(cmn_case_opt_doubles(c, "fluid.gravity", 2, def, w), 0);
  assert_rel(w[1], -9.81, 0.0);
  assert_int_equal(cmn_case_opt_doubles(c, "fluid.gravity", 3, def, w), -1);
  expect_error(c, "fluid.gravity: expected a sequence of 3 numbers, got 2 elements");
}

static void test_structure(void **state) {
  struct cmn_case *c = *state;
  assert_int_equal(cmn_case_seq_length(c, "regions"), 2);
  assert_int_equal(cmn_case_seq_length(c, "nothing"), 0);
  assert_int_equal(cmn_case_seq_length(c, "fluid"), -1);
  expect_error(c, "t.yaml:2:1: fluid: expected a sequence, got a mapping");
  assert_int_equal(cmn_case_is_map(c, "fluid"), 1);
  assert_int_equal(cmn_case_is_map(c, "regions[1]"), 1);
  assert_int_equal(cmn_case_is_map(c, "nothing"), 0);
  assert_int_equal(cmn_case_is_map(c, "steps"), -1);
  expect_error(c, "t.yaml:14:8: steps: expected a mapping, got a scalar");

  assert_int_equal(cmn_case_has(c, "fluid.c0"), 1);
  assert_int_equal(cmn_case_has(c, "regions[1].min"), 1);
  assert_int_equal(cmn_case_has(c, "regions[2]"), 0);
  assert_int_equal(cmn_case_has(c, "fluid.c0.x"), 0);
  assert_int_equal(cmn_case_has(c, "steps[0]"), 0);
  assert_int_equal(cmn_case_has(c, "fluid..c0"), 0);
  assert_int_equal(cmn_case_line(c, "fluid.c0"), 3);
  assert_int_equal(cmn_case_line(c, "regions[1].max"), 13);
  assert_int_equal(cmn_case_line(c, "regions[1].max[1]"), 13);
  /* A section is where its key is written. */
  assert_int_equal(cmn_case_line(c, "fluid"), 2);
  assert_int_equal(cmn_case_line(c, "regions"), 10);
  assert_int_equal(cmn_case_line(c, "regions[1]"), 12);
  double x;
  assert_int_equal(cmn_case_get_double(c, "regions[0].foo", -INFINITY, INFINITY, &x), -1);
  assert_string_equal(cmn_case_error(c),
                      "t.yaml: regions[0].foo: required key missing (in 'regions[0]' at line 11)");
  assert_int_equal(cmn_case_line(c, "nothing"), 0);

  assert_int_equal(cmn_case_fail(c, "fluid.rho0", "must exceed %g", 1000.0), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml:4:9: fluid.rho0: must exceed 1000");
  assert_int_equal(cmn_case_fail(c, "fluid.nothing", "needed when %s", "x"), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml: fluid.nothing: needed when x");
}

/* An empty value with nothing below ("output:") is an empty section. */
static void test_empty_section(void **state) {
  struct cmn_case *c = *state;
  long n = 0;
  double x;
  assert_int_equal(cmn_case_is_map(c, "empty"), 0);
  assert_int_equal(cmn_case_seq_length(c, "empty"), 0);
  assert_int_equal(cmn_case_get_double(c, "empty.x", -INFINITY, INFINITY, &x), -1);
  assert_string_equal(cmn_case_error(c),
                      "t.yaml: empty.x: required key missing (in 'empty' at line 16)");
  assert_int_equal(cmn_case_opt_long(c, "empty.every", 10, 1, 100, &n), 0);
  assert_int_equal(n, 10);
  assert_int_equal(cmn_case_is_map(c, "empty"), 1);
  assert_int_equal(cmn_case_get_long(c, "empty.every", 1, 100, &n), 0);
  assert_int_equal(n, 10);
  /* A scalar that is not empty is not a section. */
  assert_int_equal(cmn_case_opt_long(c, "steps.every", 10, 1, 100, &n), -1);
  expect_error(c, "t.yaml:14:8: steps: expected a mapping, got a scalar");
}

static void test_unused(void **state) {
  (void)state;
  struct cmn_case *c = parse(
      "fluid:\n"
      "  c0: 10\n"
      "  cc: 20\n"
      "list:\n"
      "  - {a: 1, b: 2}\n"
      "  - a: 3\n"
      "    bb: 4\n"
      "typo_section:\n"
      "  x: 1\n"
      "generic: {p: [1, 2], q: {r: 3}}\n");
  double x;
  long n;
  assert_int_equal(cmn_case_get_double(c, "fluid.c0", -INFINITY, INFINITY, &x), 0);
  assert_int_equal(cmn_case_check_unused(c), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml:3:3: unknown key 'fluid.cc'");
  assert_int_equal(cmn_case_has(c, "fluid.cc"), 1); /* has() does not mark */
  assert_int_equal(cmn_case_check_unused(c), -1);
  cmn_case_mark_used(c, "fluid.cc");
  assert_int_equal(cmn_case_check_unused(c), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml:4:1: unknown key 'list'");
  assert_int_equal(cmn_case_seq_length(c, "list"), 2);
  /* Reading the length does not read the elements. */
  assert_int_equal(cmn_case_check_unused(c), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml:5:5: unknown key 'list[0]'");
  for (int i = 0; i < 2; ++i) {
    char path[32];
    snprintf(path, sizeof path, "list[%d].a", i);
    assert_int_equal(cmn_case_get_long(c, path, 0, 10, &n), 0);
  }
  assert_int_equal(cmn_case_check_unused(c), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml:5:12: unknown key 'list[0].b'");
  assert_int_equal(cmn_case_opt_long(c, "list[0].b", 0, 0, 10, &n), 0);
  assert_int_equal(cmn_case_check_unused(c), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml:7:5: unknown key 'list[1].bb'");
  assert_int_equal(cmn_case_get_long(c, "list[1].bb", 0, 10, &n), 0);
  assert_int_equal(cmn_case_check_unused(c), -1);
  /* A section nobody reads is named as a whole. */
  assert_string_equal(cmn_case_error(c), "t.yaml:8:1: unknown key 'typo_section'");
  cmn_case_mark_used(c, "typo_section");
  cmn_case_mark_used(c, "no.such.path"); /* harmless */
  cmn_case_mark_used(c, "fluid..bad");   /* harmless */
  assert_int_equal(cmn_case_check_unused(c), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml:10:1: unknown key 'generic'");
  cmn_case_mark_used(c, "generic");
  assert_int_equal(cmn_case_check_unused(c), 0);
  /* Defaults inserted later are used by construction. */
  assert_int_equal(cmn_case_opt_positive(c, "extra.value", 2.5, &x), 0);
  assert_int_equal(cmn_case_check_unused(c), 0);
  cmn_case_free(c);
}

static void fatal_getter(void) {
  struct cmn_case *c = cmn_case_parse("fluid:\n  c0: abc\n", "f.yaml", NULL, 0);
  cmn_set_program_name("/usr/bin/sabre-test");
  double x;
  cmn_case_get_positive(c, "fluid.c0", &x);
}

static void fatal_unused(void) {
  struct cmn_case *c = cmn_case_parse("a: 1\nb: 2\n", "f.yaml", NULL, 0);
  cmn_set_program_name("sph");
  cmn_case_mark_used(c, "a");
  cmn_case_check_unused(c);
}

static void test_fatal_mode(void **state) {
  (void)state;
  char out[1024];
  assert_int_equal(sabre_run_child(fatal_getter, out, sizeof out), CMN_EXIT_INPUT);
  assert_string_equal(
      out, "sabre-test: error: f.yaml:2:7: fluid.c0: expected a positive number, got 'abc'\n");
  assert_int_equal(sabre_run_child(fatal_unused, out, sizeof out), CMN_EXIT_INPUT);
  assert_string_equal(out, "sph: error: f.yaml:2:1: unknown key 'b'\n");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_parse_errors),
      cmocka_unit_test(test_load_file),
      cmocka_unit_test_setup_teardown(test_double, setup, teardown),
      cmocka_unit_test_setup_teardown(test_opt_double, setup, teardown),
      cmocka_unit_test_setup_teardown(test_long, setup, teardown),
      cmocka_unit_test(test_bool),
      cmocka_unit_test_setup_teardown(test_string_and_choice, setup, teardown),
      cmocka_unit_test_setup_teardown(test_doubles, setup, teardown),
      cmocka_unit_test_setup_teardown(test_structure, setup, teardown),
      cmocka_unit_test_setup_teardown(test_empty_section, setup, teardown),
      cmocka_unit_test(test_unused),
      cmocka_unit_test(test_fatal_mode),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
