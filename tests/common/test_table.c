/* CSV tables: what cmn_csv_open/cmn_csv_row write reads back bit for bit (names too); comments,
 * blank lines, CRLF, a byte-order mark and blanks around cells are accepted; every error gives
 * its exact message with file, line and column; linear interpolation at and between nodes, beyond
 * either end, on arrays and on table columns. The tests run in a fresh temporary directory so
 * that the messages carry the short file names a user would see. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sabre/common.h"
#include "testutil.h"

static char tmpdir[] = "/tmp/sabre_test_table_XXXXXX";

static void write_bytes(const char *path, const char *text, size_t len) {
  FILE *f = fopen(path, "wb");
  assert_non_null(f);
  assert_int_equal(fwrite(text, 1, len, f), len);
  assert_int_equal(fclose(f), 0);
}

static void write_text(const char *path, const char *text) {
  write_bytes(path, text, strlen(text));
}

/* Read `text` as tab.csv: it must fail with exactly `message`, and leave the table empty. */
static void expect_error(const char *text, const char *message) {
  write_text("tab.csv", text);
  struct cmn_table t;
  char err[512];
  int status = cmn_table_read("tab.csv", &t, err, sizeof err);
  if (status != -1 || strcmp(err, message) != 0) print_error("for the table\n%s\n", text);
  assert_int_equal(status, -1);
  assert_string_equal(err, message);
  assert_null(t.names);
  assert_null(t.data);
  assert_int_equal(t.ncols, 0);
  assert_int_equal((int)t.nrows, 0);
  cmn_table_free(&t);
  /* no message buffer: same status, nothing written */
  assert_int_equal(cmn_table_read("tab.csv", &t, NULL, 0), -1);
}

/* Read `text` as tab.csv, which must succeed. */
static void read_ok(const char *text, struct cmn_table *t) {
  write_text("tab.csv", text);
  char err[512];
  int status = cmn_table_read("tab.csv", t, err, sizeof err);
  if (status != 0) print_error("%s\n", err);
  assert_int_equal(status, 0);
  assert_string_equal(err, "");
}

static void test_round_trip(void **state) {
  (void)state;
  /* names that need quotes: separator, quotes, '#' first (else a comment line), blanks at the
   * ends (else dropped), a line break (the rows then start one line later) */
  const char *const names[] = {"#t", "rho", "u, m/s", "say \"hi\"", " p ", "two\nlines"};
  enum { NCOLS = 6, ROWS = 300 };
  struct cmn_csv *csv = cmn_csv_open("round.csv", NCOLS, names);
  assert_non_null(csv);
  static double rows[ROWS][NCOLS];
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 2385);
  for (int i = 0; i < ROWS; ++i) {
    for (int k = 0; k < NCOLS; ++k)
      rows[i][k] =
          ldexp(sabre_rng_uniform(&rng, -1.0, 1.0), (int)sabre_rng_uniform(&rng, -1070, 1020));
    assert_int_equal(cmn_csv_row(csv, rows[i]), 0);
  }
  const double extremes[NCOLS] = {-0.0, 5e-324, -DBL_MAX, DBL_MIN, 0.1, 2.385e-300};
  assert_int_equal(cmn_csv_row(csv, extremes), 0);
  assert_int_equal(cmn_csv_close(csv), 0);

  struct cmn_table t;
  char err[512];
  assert_int_equal(cmn_table_read("round.csv", &t, err, sizeof err), 0);
  assert_string_equal(t.path, "round.csv");
  assert_int_equal(t.ncols, NCOLS);
  assert_int_equal((int)t.nrows, ROWS + 1);
  for (int k = 0; k < NCOLS; ++k) {
    assert_string_equal(t.names[k], names[k]);
    assert_int_equal(cmn_table_column(&t, names[k]), k);
  }
  assert_int_equal(cmn_table_column(&t, "p"), -1);
  assert_int_equal(cmn_table_column(&t, "t"), -1);
  for (int i = 0; i < ROWS; ++i) /* bit for bit, -0 included */
    assert_memory_equal(&t.data[(size_t)i * NCOLS], rows[i], sizeof rows[i]);
  assert_memory_equal(&t.data[(size_t)ROWS * NCOLS], extremes, sizeof extremes);
  assert_int_equal(t.header_line, 1);
  assert_int_equal(t.lines[0], 3);
  assert_int_equal(t.lines[ROWS], ROWS + 3);
  cmn_table_free(&t);
  assert_null(t.names);
  cmn_table_free(&t); /* a freed table can be freed again */
  cmn_table_free(NULL);
  remove("round.csv");
}

static void test_comments_and_blanks(void **state) {
  (void)state;
  struct cmn_table t;
  /* BOM, comments before the header and between rows, blank lines (also of blanks only), CRLF,
   * blanks around cells and names, a quoted number, an exponent, no final line end */
  read_ok(
      "\xEF\xBB\xBF# imposed pressure at the outlet\r\n"
      "\r\n"
      "  t , value\r\n"
      "# t [s], value [Pa]\n"
      "0,\t1.5e3\n"
      "   \t\n"
      "  # indented comment\n"
      "0.25 , \"1012.5\"\n"
      "\n"
      "1e-1,-2.385",
      &t);
  assert_int_equal(t.ncols, 2);
  assert_string_equal(t.names[0], "t");
  assert_string_equal(t.names[1], "value");
  assert_int_equal(t.header_line, 3);
  assert_int_equal((int)t.nrows, 3);
  const double want[6] = {0.0, 1500.0, 0.25, 1012.5, 0.1, -2.385};
  const long lines[3] = {5, 8, 10};
  for (int k = 0; k < 6; ++k) assert_true(t.data[k] == want[k]);
  for (int i = 0; i < 3; ++i) assert_int_equal(t.lines[i], lines[i]);
  cmn_table_free(&t);

  /* one column; quoted names keep their blanks; a lone CR ends a line too */
  read_ok("\" x\"\r7.5\r\r-3\n", &t);
  assert_int_equal(t.ncols, 1);
  assert_string_equal(t.names[0], " x");
  assert_int_equal((int)t.nrows, 2);
  assert_true(t.data[0] == 7.5 && t.data[1] == -3.0);
  assert_int_equal(t.lines[1], 4);
  cmn_table_free(&t);

  /* a name may look like a number as long as not all do */
  read_ok("1,b\n2,3\n", &t);
  assert_string_equal(t.names[0], "1");
  cmn_table_free(&t);
}

static void test_errors(void **state) {
  (void)state;
  sabre_fp_traps_on(); /* 1e400 and nan must be refused without a trap */
  struct cmn_table t;
  char err[512];
  assert_int_equal(cmn_table_read("missing.csv", &t, err, sizeof err), -1);
  assert_string_equal(err, "missing.csv: cannot open: No such file or directory");
  assert_null(t.data);
  assert_int_equal(mkdir("dir.csv", 0700), 0);
  assert_int_equal(cmn_table_read("dir.csv", &t, err, sizeof err), -1);
  assert_string_equal(err, "dir.csv: cannot read: Is a directory");
  rmdir("dir.csv");

  expect_error("",
               "tab.csv: no header line (the file is empty or holds only comments and blank "
               "lines)");
  expect_error("# only\n\n  # comments\n",
               "tab.csv: no header line (the file is empty or holds only comments and blank "
               "lines)");
  expect_error("# a table\nt,value\n# nothing\n\n",
               "tab.csv: no data rows after the header (line 2)");
  expect_error("0,0\n1,2\n", "tab.csv:1: expected a header line of column names, got only numbers");
  expect_error("# header\n\nt,,value\n0,1,2\n", "tab.csv:3: column 2 of the header: empty name");
  expect_error("t,value,\n", "tab.csv:1: column 3 of the header: empty name");
  expect_error("t,\"\"\n", "tab.csv:1: column 2 of the header: empty name");
  expect_error("t,p,\"p\"\n0,1,2\n",
               "tab.csv:1: column 3 of the header: duplicate name 'p' (also column 2)");
  expect_error("t,\"p\n0,1\n", "tab.csv:1: column 2: the quote is never closed");
  expect_error("t,\"p\"q\n0,1\n",
               "tab.csv:1: column 2: expected ',' or the end of the line after the closing quote");

  /* the message shown in the documentation, line 7 */
  expect_error("# probe\n\nt,p\n0,1\n\n# more\n0.5,abc\n",
               "tab.csv:7: column 2 ('p'): expected a number, got 'abc'");
  expect_error("t,p\n0,\n", "tab.csv:2: column 2 ('p'): expected a number, got an empty cell");
  expect_error("t,p\n,1\n", "tab.csv:2: column 1 ('t'): expected a number, got an empty cell");
  expect_error("t,p\n0,1 2\n", "tab.csv:2: column 2 ('p'): expected a number, got '1 2'");
  expect_error("t,p\n0,1.5 # note\n",
               "tab.csv:2: column 2 ('p'): expected a number, got '1.5 # note'");
  expect_error("t,p\n0,\" 1\"\n", "tab.csv:2: column 2 ('p'): expected a number, got ' 1'");
  expect_error("t;p\n0;1\n", "tab.csv:2: column 1 ('t;p'): expected a number, got '0;1'");
  expect_error("t,p\n0,nan\n", "tab.csv:2: column 2 ('p'): expected a finite number, got 'nan'");
  expect_error("t,p\n0,-inf\n", "tab.csv:2: column 2 ('p'): expected a finite number, got '-inf'");
  expect_error("t,p\n1e400,0\n",
               "tab.csv:2: column 1 ('t'): expected a finite number, got '1e400'");
  expect_error("t,p\n0,1\n1,2,3\n", "tab.csv:3: expected 2 cells as in the header (line 1), got 3");
  expect_error("t,p\n0,1\n1,2,\n", "tab.csv:3: expected 2 cells as in the header (line 1), got 3");
  expect_error("t,p,u\n0,1\n", "tab.csv:2: expected 3 cells as in the header (line 1), got 2");
  expect_error("t\n0\n1,2\n", "tab.csv:3: expected 1 cell as in the header (line 1), got 2");
  expect_error("t,p\n0,\"1\n", "tab.csv:2: column 2: the quote is never closed");
  expect_error("t,p\n0,1\n1.2.3.4.5.6.7.8.9.10.11.12.13.14.15.16.17.18.19.20,1\n",
               "tab.csv:3: column 1 ('t'): expected a number, got "
               "'1.2.3.4.5.6.7.8.9.10.11.12.13.14.15.16.1...'");
  /* a quoted name over two lines: the next record is on line 3 */
  expect_error("t,\"p\nq\"\n0,x\n", "tab.csv:3: column 2 ('p\nq'): expected a number, got 'x'");

  const char binary[] = "t,p\n0,1\n2,\0\n";
  write_bytes("tab.csv", binary, sizeof binary - 1);
  assert_int_equal(cmn_table_read("tab.csv", &t, err, sizeof err), -1);
  assert_string_equal(err, "tab.csv:3: NUL byte: this is not a text file");

  /* a short message buffer truncates, it does not overflow */
  write_text("tab.csv", "t,p\n0,abc\n");
  char small[12];
  assert_int_equal(cmn_table_read("tab.csv", &t, small, sizeof small), -1);
  assert_string_equal(small, "tab.csv:2: ");
  sabre_fp_traps_off();
}

static void test_header_and_order_checks(void **state) {
  (void)state;
  struct cmn_table t;
  char err[512];
  read_ok("time,value\n0,1\n", &t);
  const char *const tv[] = {"t", "value"}, *const time_value[] = {"time", "value"};
  const char *const xru[] = {"x", "rho", "u"};
  assert_int_equal(cmn_table_expect_columns(&t, 2, time_value, err, sizeof err), 0);
  assert_int_equal(cmn_table_expect_columns(&t, 2, tv, err, sizeof err), -1);
  assert_string_equal(err, "tab.csv:1: the header must be 't,value', got 'time,value'");
  assert_int_equal(cmn_table_expect_columns(&t, 3, xru, err, sizeof err), -1);
  assert_string_equal(err, "tab.csv:1: the header must be 'x,rho,u', got 'time,value'");
  assert_int_equal(cmn_table_expect_columns(&t, 1, time_value, NULL, 0), -1);
  cmn_table_free(&t);

  read_ok("# profile\nx,rho,u\n-0.5,1000,0\n0.1,1000,0\n\n0.1,1010,0\n", &t);
  assert_int_equal(cmn_table_check_increasing(&t, 1, err, sizeof err), -1);
  assert_string_equal(err,
                      "tab.csv:4: column 2 ('rho'): values must increase strictly, got 1000 "
                      "after 1000 (line 3)");
  assert_int_equal(cmn_table_check_increasing(&t, 0, err, sizeof err), -1);
  assert_string_equal(err,
                      "tab.csv:6: column 1 ('x'): values must increase strictly, got 0.1 after "
                      "0.1 (line 4)");
  assert_int_equal(cmn_table_check_increasing(&t, 3, err, sizeof err), -1);
  assert_string_equal(err, "tab.csv: no column 4 (the table has 3)");
  cmn_table_free(&t);

  read_ok("t,v\n0.30000000000000004,1\n0.3,2\n2,3\n", &t);
  assert_int_equal(cmn_table_check_increasing(&t, 0, err, sizeof err), -1);
  assert_string_equal(err,
                      "tab.csv:3: column 1 ('t'): values must increase strictly, got 0.3 after "
                      "0.30000000000000004 (line 2)");
  assert_int_equal(cmn_table_check_increasing(&t, 1, err, sizeof err), 0);
  cmn_table_free(&t);

  read_ok("t,v\n4.5,1\n", &t); /* one row is increasing */
  assert_int_equal(cmn_table_check_increasing(&t, 0, err, sizeof err), 0);
  cmn_table_free(&t);
}

static void test_interpolation(void **state) {
  (void)state;
  sabre_fp_traps_on();
  /* nodes of the line y = 2.385 - 1.75 x (exact answers between nodes) and a kink at x = 3.3 */
  const double x[5] = {-1.25, 0.5, 0.8125, 3.3, 7.0};
  double y[5];
  for (int k = 0; k < 4; ++k) y[k] = 2.385 - 1.75 * x[k];
  y[4] = y[3] + 0.6 * (x[4] - x[3]);
  for (int k = 0; k < 5; ++k) assert_true(cmn_interp_linear(5, x, y, 1, x[k]) == y[k]);
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 7);
  for (int i = 0; i < 1000; ++i) {
    double xq = sabre_rng_uniform(&rng, x[0], x[3]);
    assert_abs(cmn_interp_linear(5, x, y, 1, xq), 2.385 - 1.75 * xq, 1e-14); /* |y| ≤ 6 */
    xq = sabre_rng_uniform(&rng, x[3], x[4]);
    assert_abs(cmn_interp_linear(5, x, y, 1, xq), y[3] + 0.6 * (xq - x[3]), 1e-14);
  }
  /* constant beyond either end */
  assert_true(cmn_interp_linear(5, x, y, 1, -1.2500000000000002) == y[0]);
  assert_true(cmn_interp_linear(5, x, y, 1, -1e300) == y[0]);
  assert_true(cmn_interp_linear(5, x, y, 1, 7.000000000000001) == y[4]);
  assert_true(cmn_interp_linear(5, x, y, 1, INFINITY) == y[4]);
  assert_true(cmn_interp_linear(5, x, y, 1, -INFINITY) == y[0]);
  /* one node: constant; two nodes */
  assert_true(cmn_interp_linear(1, x, y, 1, -3.0) == y[0]);
  assert_true(cmn_interp_linear(1, x, y, 1, x[0]) == y[0]);
  assert_true(cmn_interp_linear(1, x, y, 1, 9.0) == y[0]);
  assert_rel(cmn_interp_linear(2, x, y, 1, 0.0), 2.385, 1e-15);
  /* NaN in, NaN out, without FE_INVALID; no nodes */
  assert_true(isnan(cmn_interp_linear(5, x, y, 1, NAN)));
  assert_true(isnan(cmn_interp_linear(0, x, y, 1, 0.5)));

  /* the same nodes as two columns of a table (stride = ncols) give the same values bit for bit */
  const char *const names[] = {"y", "pad", "x"};
  struct cmn_csv *csv = cmn_csv_open("interp.csv", 3, names);
  assert_non_null(csv);
  for (int k = 0; k < 5; ++k) assert_int_equal(cmn_csv_row(csv, (double[3]){y[k], -9.5, x[k]}), 0);
  assert_int_equal(cmn_csv_close(csv), 0);
  struct cmn_table t;
  char err[512];
  assert_int_equal(cmn_table_read("interp.csv", &t, err, sizeof err), 0);
  int xc = cmn_table_column(&t, "x"), yc = cmn_table_column(&t, "y");
  assert_int_equal(xc, 2);
  assert_int_equal(yc, 0);
  assert_int_equal(cmn_table_check_increasing(&t, xc, err, sizeof err), 0);
  for (int i = 0; i < 200; ++i) {
    double xq = sabre_rng_uniform(&rng, -3.0, 9.0);
    double a = cmn_table_interp(&t, xc, yc, xq), b = cmn_interp_linear(5, x, y, 1, xq);
    assert_memory_equal(&a, &b, sizeof a);
  }
  for (int k = 0; k < 5; ++k) assert_true(cmn_table_interp(&t, xc, yc, x[k]) == y[k]);
  assert_true(cmn_table_interp(&t, xc, 1, 2.0) == -9.5);
  cmn_table_free(&t);
  remove("interp.csv");
  sabre_fp_traps_off();
}

static int setup(void **state) {
  (void)state;
  if (mkdtemp(tmpdir) == NULL || chdir(tmpdir) != 0) return -1;
  return 0;
}

static int teardown(void **state) {
  (void)state;
  remove("tab.csv");
  if (chdir("/") != 0) return -1;
  return rmdir(tmpdir);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_round_trip),    cmocka_unit_test(test_comments_and_blanks),
      cmocka_unit_test(test_errors),        cmocka_unit_test(test_header_and_order_checks),
      cmocka_unit_test(test_interpolation),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
