/* Expressions (cmn_expr_*): precedence and associativity against hand-evaluated values, every
 * function against the C library, several variables in any order, deep nesting (the heap stack),
 * and every error with its exact message and column. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sabre/common.h"
#include "testutil.h"

#define PI 3.14159265358979323846

static const char *const xyz[] = {"x", "y", "z"};

static double eval3(const char *text, double x, double y, double z) {
  char err[512];
  struct cmn_expr *e = cmn_expr_compile(text, 3, xyz, err, sizeof err);
  if (!e) print_error("%s\n", err);
  assert_non_null(e);
  const double v[3] = {x, y, z};
  double r = cmn_expr_eval(e, v);
  cmn_expr_free(e);
  return r;
}

static void test_expr_values(void **state) {
  (void)state;
  const double x = 2.385, y = -0.731, z = 0.4172;
  assert_rel(eval3("2^3^2 - -x/4 + exp(0)*abs(-1.5e0)", x, y, z), 512.0 + x / 4 + 1.5, 1e-15);
  assert_rel(eval3("-x^2", x, y, z), -x * x, 1e-15);
  assert_rel(eval3("2^-x", x, y, z), pow(2.0, -x), 1e-15);
  assert_rel(eval3("x - y - z", x, y, z), x - y - z, 1e-15);
  assert_rel(eval3("x / y / z", x, y, z), x / y / z, 1e-15);
  assert_rel(eval3("x + y * z", x, y, z), x + y * z, 1e-15);
  assert_rel(eval3("(x + y) * z", x, y, z), (x + y) * z, 1e-15);
  assert_rel(eval3(" +x*  -y ", x, y, z), -x * y, 1e-15);
  assert_rel(eval3("2.5 * sin(4 * pi * z)", x, y, z), 2.5 * sin(4 * PI * z), 1e-15);
  assert_rel(eval3("1e3*(1 + .01*cos(2*pi*x))", x, y, z), 1e3 * (1 + .01 * cos(2 * PI * x)), 1e-15);
  struct {
    const char *name;
    double (*f)(double);
    double arg;
  } fun[] = {{"sin", sin, z},   {"cos", cos, z},   {"tan", tan, z},   {"asin", asin, z},
             {"acos", acos, z}, {"atan", atan, y}, {"exp", exp, y},   {"log", log, x},
             {"sqrt", sqrt, x}, {"abs", fabs, y},  {"tanh", tanh, y}, {"cosh", cosh, y},
             {"sinh", sinh, y}};
  for (size_t k = 0; k < sizeof fun / sizeof fun[0]; k++) {
    char text[64];
    snprintf(text, sizeof text, "%s(%s)", fun[k].name,
             fun[k].arg == x   ? "x"
             : fun[k].arg == y ? "y"
                               : "z");
    assert_rel(eval3(text, x, y, z), fun[k].f(fun[k].arg), 1e-15);
  }
  /* Variables in the caller's order, names longer than a letter. */
  const char *const names[] = {"rho0", "x_1"};
  char err[256];
  struct cmn_expr *e = cmn_expr_compile("rho0 * x_1", 2, names, err, sizeof err);
  assert_non_null(e);
  const double v[2] = {1000.0, 0.381};
  assert_rel(cmn_expr_eval(e, v), 381.0, 1e-15);
  cmn_expr_free(e);
  cmn_expr_free(NULL);
  /* No variables at all: constants. */
  e = cmn_expr_compile("pi/4", 0, NULL, err, sizeof err);
  assert_non_null(e);
  assert_rel(cmn_expr_eval(e, NULL), PI / 4, 1e-15);
  cmn_expr_free(e);
}

/* Nesting deeper than the evaluator's stack on the C stack (32): the heap path. */
static void test_expr_deep(void **state) {
  (void)state;
  char text[4096] = "";
  const int depth = 100;
  for (int k = 0; k < depth; k++) strcat(text, "(1 + ");
  strcat(text, "x");
  for (int k = 0; k < depth; k++) strcat(text, ")");
  assert_rel(eval3(text, 2.385, 0, 0), depth + 2.385, 1e-15);
}

static void expect_error(const char *text, const char *message) {
  char err[512];
  struct cmn_expr *e = cmn_expr_compile(text, 3, xyz, err, sizeof err);
  if (e || strcmp(err, message) != 0) print_error("got '%s'\nwanted '%s'\n", err, message);
  assert_null(e);
  assert_string_equal(err, message);
}

static void test_expr_errors(void **state) {
  (void)state;
  expect_error("sin(x", "expression 'sin(x': expected ')' at column 6");
  expect_error("(x + 1", "expression '(x + 1': expected ')' at column 7");
  expect_error("x +", "expression 'x +': unexpected end at column 4");
  expect_error("x $ 2", "expression 'x $ 2': unexpected character at column 3");
  expect_error("", "expression '': unexpected end at column 1");
  expect_error("sin x", "expression 'sin x': expected '(' after a function name at column 5");
  expect_error("t + 1",
               "expression 't + 1': unknown name 't' (variables: x, y, z, pi; functions: sin cos "
               "tan asin acos atan exp log sqrt abs tanh cosh sinh) at column 1");
  expect_error("2 * sinus(x)",
               "expression '2 * sinus(x)': unknown name 'sinus' (variables: x, y, z, pi; "
               "functions: sin cos tan asin acos atan exp log sqrt abs tanh cosh sinh) at "
               "column 5");
  /* NULL err is allowed. */
  assert_null(cmn_expr_compile("x +", 3, xyz, NULL, 0));
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_expr_values),
                                     cmocka_unit_test(test_expr_deep),
                                     cmocka_unit_test(test_expr_errors)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
