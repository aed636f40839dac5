/* CSV output: header, rows written with %.17g and read back bit for bit, write errors. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sabre/common.h"
#include "testutil.h"

static void test_write_read_back(void **state) {
  (void)state;
  sabre_fp_traps_on();
  char dir[] = "/tmp/sabre_test_csv_XXXXXX";
  assert_non_null(mkdtemp(dir));
  char path[256];
  snprintf(path, sizeof path, "%s/probe.csv", dir);
  const char *const names[] = {"t", "rho", "u, m/s", "say \"hi\""};
  struct cmn_csv *csv = cmn_csv_open(path, 4, names);
  assert_non_null(csv);
  enum { ROWS = 100 };
  double rows[ROWS][4];
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 2385);
  for (int i = 0; i < ROWS; ++i) {
    for (int k = 0; k < 4; ++k)
      rows[i][k] =
          ldexp(sabre_rng_uniform(&rng, -1.0, 1.0), (int)sabre_rng_uniform(&rng, -1000, 1000));
    if (i == 0) {
      rows[0][0] = 0.1;
      rows[0][1] = -0.0;
      rows[0][2] = 5e-324;
      rows[0][3] = 1.7976931348623157e308;
    }
    assert_int_equal(cmn_csv_row(csv, rows[i]), 0);
    if (i == ROWS / 2) assert_int_equal(cmn_csv_flush(csv), 0);
  }
  assert_int_equal(cmn_csv_close(csv), 0);
  assert_int_equal(cmn_csv_close(NULL), 0);

  FILE *f = fopen(path, "r");
  assert_non_null(f);
  char line[1024];
  assert_non_null(fgets(line, sizeof line, f));
  assert_string_equal(line, "t,rho,\"u, m/s\",\"say \"\"hi\"\"\"\n");
  for (int i = 0; i < ROWS; ++i) {
    assert_non_null(fgets(line, sizeof line, f));
    char *p = line;
    for (int k = 0; k < 4; ++k) {
      char *end;
      double x = strtod(p, &end);
      assert_true(end != p);
      assert_memory_equal(&x, &rows[i][k], sizeof x);
      assert_int_equal(*end, k < 3 ? ',' : '\n');
      p = end + 1;
    }
  }
  assert_null(fgets(line, sizeof line, f));
  fclose(f);
  remove(path);
  remove(dir);
  sabre_fp_traps_off();
}

static void test_errors(void **state) {
  (void)state;
  const char *const names[] = {"a", "b"};
  const double row[2] = {1.5, 2.5};
  assert_null(cmn_csv_open("/nonexistent/dir/x.csv", 2, names));
  /* A full device: some write, flush or the close must fail, and close must say so. */
  struct cmn_csv *csv = cmn_csv_open("/dev/full", 2, names);
  if (csv != NULL) {
    for (int i = 0; i < 10000; ++i) cmn_csv_row(csv, row);
    assert_int_equal(cmn_csv_flush(csv), -1);
    assert_int_equal(cmn_csv_row(csv, row), -1);
    assert_int_equal(cmn_csv_close(csv), -1);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_write_read_back),
      cmocka_unit_test(test_errors),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
