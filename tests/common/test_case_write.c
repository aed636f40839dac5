/* Case files: --set overrides (creating and replacing nodes, sequences included), defaults written
 * back, and write -> re-parse round trips that keep every double bit for bit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "testutil.h"

static struct cmn_case *parse(const char *text) {
  char err[512];
  struct cmn_case *c = cmn_case_parse(text, "t.yaml", err, sizeof err);
  if (c == NULL) fail_msg("parse failed: %s", err);
  cmn_case_set_fatal(c, 0);
  return c;
}

static void expect_error(const struct cmn_case *c, const char *part) {
  const char *err = cmn_case_error(c);
  if (strstr(err, part) == NULL) fail_msg("error '%s' does not contain '%s'", err, part);
}

/* Write the case to memory and parse it again. */
static struct cmn_case *reparse(const struct cmn_case *c, char *text, size_t len) {
  FILE *f = tmpfile();
  assert_non_null(f);
  assert_int_equal(cmn_case_write(c, f), 0);
  rewind(f);
  size_t got = fread(text, 1, len - 1, f);
  assert_true(got < len - 1);
  text[got] = '\0';
  fclose(f);
  return parse(text);
}

static double get(struct cmn_case *c, const char *path) {
  double x = NAN;
  if (cmn_case_get_double(c, path, -INFINITY, INFINITY, &x) != 0)
    fail_msg("%s: %s", path, cmn_case_error(c));
  return x;
}

static void test_set_scalars(void **state) {
  (void)state;
  struct cmn_case *c = parse("fluid:\n  c0: 10\n  rho0: 1000\nname: a\n");
  assert_int_equal(cmn_case_set(c, "fluid.c0=12.75"), 0);
  assert_rel(get(c, "fluid.c0"), 12.75, 0.0);
  /* The replaced node keeps its key's place in the file. */
  assert_int_equal(cmn_case_line(c, "fluid.c0"), 0);
  /* Blanks around the key are ignored; the value is YAML. */
  assert_int_equal(cmn_case_set(c, " fluid.rho0 = 998.25"), 0);
  assert_rel(get(c, "fluid.rho0"), 998.25, 0.0);
  assert_int_equal(cmn_case_set(c, "name=\"a=b, c\""), 0);
  const char *s;
  assert_int_equal(cmn_case_get_string(c, "name", &s), 0);
  assert_string_equal(s, "a=b, c");
  /* Intermediate mappings are created. */
  assert_int_equal(cmn_case_set(c, "solver.time.cfl=0.385"), 0);
  assert_int_equal(cmn_case_is_map(c, "solver"), 1);
  assert_rel(get(c, "solver.time.cfl"), 0.385, 0.0);
  /* A scalar can be replaced by a mapping. */
  assert_int_equal(cmn_case_set(c, "name={first: x, second: 2.5}"), 0);
  assert_rel(get(c, "name.second"), 2.5, 0.0);
  /* Empty value: an empty (null) scalar. */
  assert_int_equal(cmn_case_set(c, "fluid.note="), 0);
  assert_int_equal(cmn_case_get_string(c, "fluid.note", &s), -1);
  expect_error(c, "t.yaml (--set fluid.note=): fluid.note: expected a string, got an empty value");
  /* A bad value set on the command line is reported against the --set. */
  assert_int_equal(cmn_case_set(c, "fluid.c0=fast"), 0);
  double x;
  assert_int_equal(cmn_case_get_positive(c, "fluid.c0", &x), -1);
  assert_string_equal(
      cmn_case_error(c),
      "t.yaml (--set fluid.c0=fast): fluid.c0: expected a positive number, got 'fast'");
  cmn_case_free(c);
}

static void test_set_sequences(void **state) {
  (void)state;
  struct cmn_case *c =
      parse("regions:\n  - {min: [0, 0], max: [1, 1]}\n  - {min: [1, 0], max: [2, 1]}\n");
  double v[3];
  assert_int_equal(cmn_case_set(c, "gravity=[0, -9.81, 0.5]"), 0);
  assert_int_equal(cmn_case_get_doubles(c, "gravity", 3, 0, v, NULL), 0);
  assert_rel(v[1], -9.81, 0.0);
  assert_rel(v[2], 0.5, 0.0);
  /* Replace an element inside a sequence, and a whole sequence. */
  assert_int_equal(cmn_case_set(c, "regions[1].min=[1.5, 0.25]"), 0);
  assert_int_equal(cmn_case_get_doubles(c, "regions[1].min", 2, 0, v, NULL), 0);
  assert_rel(v[0], 1.5, 0.0);
  assert_rel(v[1], 0.25, 0.0);
  assert_int_equal(cmn_case_set(c, "regions[0].max[1]=3.5"), 0);
  assert_rel(get(c, "regions[0].max[1]"), 3.5, 0.0);
  assert_int_equal(cmn_case_get_doubles(c, "regions[0].max", 2, 0, v, NULL), 0);
  assert_rel(v[1], 3.5, 0.0);
  /* Append at index == length, creating the element's mapping. */
  assert_int_equal(cmn_case_set(c, "regions[2].min=[4, 4]"), 0);
  assert_int_equal(cmn_case_seq_length(c, "regions"), 3);
  assert_int_equal(cmn_case_get_doubles(c, "regions[2].min", 2, 0, v, NULL), 0);
  assert_rel(v[0], 4.0, 0.0);
  /* A new sequence can be started at index 0 only. */
  assert_int_equal(cmn_case_set(c, "probes[0].x=0.5"), 0);
  assert_int_equal(cmn_case_seq_length(c, "probes"), 1);
  assert_rel(get(c, "probes[0].x"), 0.5, 0.0);
  assert_int_equal(cmn_case_set(c, "others[1]=0.5"), -1);
  expect_error(c, "others[1]: index 1 out of range (new sequence)");
  assert_int_equal(cmn_case_has(c, "others"), 0); /* nothing half-built */
  assert_int_equal(cmn_case_set(c, "regions[5].min=[0, 0]"), -1);
  expect_error(c, "regions[5].min: index 5 out of range (the sequence has 3 elements)");
  /* An empty value on the way becomes a section. */
  assert_int_equal(cmn_case_set(c, "output="), 0);
  assert_int_equal(cmn_case_set(c, "output.every=5"), 0);
  assert_rel(get(c, "output.every"), 5.0, 0.0);
  assert_int_equal(cmn_case_set(c, "regions=[]"), 0);
  assert_int_equal(cmn_case_seq_length(c, "regions"), 0);
  cmn_case_free(c);
}

static void test_set_errors(void **state) {
  (void)state;
  struct cmn_case *c = parse("a: 1\nb: [1, 2]\n");
  assert_int_equal(cmn_case_set(c, "a"), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml: --set 'a': expected key=value");
  assert_int_equal(cmn_case_set(c, "=3"), -1);
  expect_error(c, "--set '=3': empty key");
  assert_int_equal(cmn_case_set(c, " =3"), -1);
  expect_error(c, "empty key");
  assert_int_equal(cmn_case_set(c, "a..b=3"), -1);
  expect_error(c, "--set 'a..b=3': malformed key path 'a..b'");
  assert_int_equal(cmn_case_set(c, "b[x]=3"), -1);
  expect_error(c, "malformed key path");
  assert_int_equal(cmn_case_set(c, "a=[1, 2"), -1);
  expect_error(
      c, "--set 'a=[1, 2': cannot parse the value: value:2:1: did not find expected ',' or ']'");
  assert_int_equal(cmn_case_set(c, "a=x: y: z"), -1);
  expect_error(c, "cannot parse the value");
  assert_int_equal(cmn_case_set(c, "a={k: 1, k: 2}"), -1);
  expect_error(c, "duplicate key 'k'");
  assert_int_equal(cmn_case_set(c, "a.x=3"), -1);
  expect_error(c, "a.x: cannot set a key inside a scalar");
  assert_int_equal(cmn_case_set(c, "a[0]=3"), -1);
  expect_error(c, "a[0]: cannot index a scalar");
  /* The failed overrides left the tree as it was. */
  assert_rel(get(c, "a"), 1.0, 0.0);
  double v[2];
  assert_int_equal(cmn_case_get_doubles(c, "b", 2, 0, v, NULL), 0);
  assert_int_equal(cmn_case_check_unused(c), 0);
  cmn_case_free(c);
}

static void test_set_unused(void **state) {
  (void)state;
  struct cmn_case *c = parse("fluid:\n  c0: 10\n");
  assert_int_equal(cmn_case_set(c, "fluid.cc=3"), 0);
  double x;
  assert_int_equal(cmn_case_get_positive(c, "fluid.c0", &x), 0);
  assert_int_equal(cmn_case_check_unused(c), -1);
  assert_string_equal(cmn_case_error(c), "t.yaml (--set fluid.cc=3): unknown key 'fluid.cc'");
  cmn_case_free(c);
}

static void test_write_defaults(void **state) {
  (void)state;
  struct cmn_case *c = parse(
      "# comment dropped\n"
      "fluid:\n"
      "  c0: 10   # stays as written\n"
      "  name: 'on'\n"
      "list: [1, 2.5e-3, x]\n"
      "nested:\n"
      "  - {a: 1}\n"
      "  - [1, 2]\n"
      "empty_map: {}\n");
  double x, v[2];
  long n;
  int b, k;
  const char *s;
  static const char *const kinds[] = {"wendland", "cubic", NULL};
  const double gravity[2] = {0.0, -9.81};
  assert_int_equal(cmn_case_opt_positive(c, "fluid.rho0", 998.2, &x), 0);
  assert_int_equal(cmn_case_opt_long(c, "output.every", 50, 1, 1000, &n), 0);
  assert_int_equal(cmn_case_opt_bool(c, "output.vtk", 1, &b), 0);
  assert_int_equal(cmn_case_opt_string(c, "output.dir", "yes", &s), 0);
  assert_int_equal(cmn_case_opt_string(c, "output.title", "dam: break #1", &s), 0);
  assert_int_equal(cmn_case_opt_choice(c, "sph.kernel", kinds, 1, &k), 0);
  assert_int_equal(cmn_case_opt_doubles(c, "fluid.gravity", 2, gravity, v), 0);

  char text[4096];
  struct cmn_case *r = reparse(c, text, sizeof text);
  /* Values from the file stay as written; defaults are present with their values. */
  assert_non_null(strstr(text, "c0: 10\n"));
  assert_null(strstr(text, "comment"));
  assert_rel(get(r, "fluid.c0"), 10.0, 0.0);
  assert_rel(get(r, "fluid.rho0"), 998.2, 0.0);
  assert_int_equal(cmn_case_get_long(r, "output.every", 0, 100, &n), 0);
  assert_int_equal(n, 50);
  assert_int_equal(cmn_case_get_bool(r, "output.vtk", &b), 0);
  assert_int_equal(b, 1);
  /* Strings that look like booleans or hold YAML syntax come back as the same strings. */
  assert_int_equal(cmn_case_get_string(r, "fluid.name", &s), 0);
  assert_string_equal(s, "on");
  assert_int_equal(cmn_case_get_string(r, "output.dir", &s), 0);
  assert_string_equal(s, "yes");
  assert_int_equal(cmn_case_get_string(r, "output.title", &s), 0);
  assert_string_equal(s, "dam: break #1");
  assert_int_equal(cmn_case_get_choice(r, "sph.kernel", kinds, &k), 0);
  assert_int_equal(k, 1);
  assert_int_equal(cmn_case_get_doubles(r, "fluid.gravity", 2, 0, v, NULL), 0);
  assert_memory_equal(v, gravity, sizeof gravity);
  assert_int_equal(cmn_case_seq_length(r, "list"), 3);
  assert_int_equal(cmn_case_get_string(r, "list[2]", &s), 0);
  assert_string_equal(s, "x");
  assert_rel(get(r, "nested[0].a"), 1.0, 0.0);
  assert_rel(get(r, "nested[1][1]"), 2.0, 0.0);
  assert_int_equal(cmn_case_is_map(r, "empty_map"), 1);
  assert_int_equal(cmn_case_seq_length(r, "list"), 3);
  cmn_case_free(r);
  cmn_case_free(c);
}

/* Defaults of random magnitude and sign, and awkward values, re-read bit for bit. */
static void test_round_trip_bits(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 20261122);
  enum { N = 200 };
  double values[N];
  for (int i = 0; i < N; ++i) {
    double mantissa = sabre_rng_uniform(&rng, -1.0, 1.0);
    double exponent = floor(sabre_rng_uniform(&rng, -300.0, 300.0));
    values[i] = ldexp(mantissa, (int)exponent);
  }
  const double special[] = {0.1,
                            1.0 / 3.0,
                            -0.0,
                            5e-324,
                            1.7976931348623157e308,
                            2.385,
                            0x1.fffffffffffffp-1,
                            1e23,
                            2.2250738585072014e-308};
  memcpy(values, special, sizeof special);
  struct cmn_case *c = parse("fluid: {c0: 0.1}\n");
  for (int i = 0; i < N; ++i) {
    char path[32];
    double x;
    snprintf(path, sizeof path, "v.x%d", i);
    assert_int_equal(cmn_case_opt_double(c, path, values[i], -INFINITY, INFINITY, &x), 0);
    assert_memory_equal(&x, &values[i], sizeof x);
  }
  assert_int_equal(cmn_case_set(c, "w=[1e-310, -2.5e+300]"), 0);
  static char text[65536];
  struct cmn_case *r = reparse(c, text, sizeof text);
  for (int i = 0; i < N; ++i) {
    char path[32];
    snprintf(path, sizeof path, "v.x%d", i);
    double x = get(r, path);
    assert_memory_equal(&x, &values[i], sizeof x);
  }
  assert_rel(get(r, "w[0]"), 1e-310, 0.0);
  assert_rel(get(r, "w[1]"), -2.5e300, 0.0);
  /* Short forms are used where they round-trip. */
  assert_non_null(strstr(text, "x5: 2.385\n"));
  /* A second pass writes the same text. */
  static char text2[65536];
  struct cmn_case *r2 = reparse(r, text2, sizeof text2);
  assert_string_equal(text, text2);
  cmn_case_free(r2);
  cmn_case_free(r);
  cmn_case_free(c);
}

static void test_write_file(void **state) {
  (void)state;
  struct cmn_case *c = parse("a: 2.5\n");
  char dir[] = "/tmp/sabre_test_write_XXXXXX";
  assert_non_null(mkdtemp(dir));
  char path[256];
  snprintf(path, sizeof path, "%s/used_case.yaml", dir);
  assert_int_equal(cmn_case_write_file(c, path), 0);
  char err[256];
  struct cmn_case *r = cmn_case_load(path, err, sizeof err);
  assert_non_null(r);
  assert_rel(get(r, "a"), 2.5, 0.0);
  cmn_case_free(r);
  remove(path);
  remove(dir);
  snprintf(path, sizeof path, "%s/missing/used_case.yaml", dir);
  assert_int_equal(cmn_case_write_file(c, path), -1);
  /* A full disk is reported. */
  FILE *full = fopen("/dev/full", "w");
  if (full != NULL) {
    assert_int_equal(cmn_case_write(c, full), -1);
    fclose(full);
  }
  cmn_case_free(c);
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_set_scalars),    cmocka_unit_test(test_set_sequences),
      cmocka_unit_test(test_set_errors),     cmocka_unit_test(test_set_unused),
      cmocka_unit_test(test_write_defaults), cmocka_unit_test(test_round_trip_bits),
      cmocka_unit_test(test_write_file),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
