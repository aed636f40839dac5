/* Wendland C2 kernel, M(1): normalisation (α_1 = 3/4 derived in docs/sph-gamma.md §1), values,
 * derivative and support, in d = 1, 2, 3. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>

#include "kernel.h"
#include "sabre/sph_walls.h"
#include "testutil.h"

static const double PI = 3.14159265358979323846;
static const double H = 0.0237; /* smoothing length [m], deliberately not 1 */

struct moment {
  const struct sph_kernel *k;
  int power; /* integrand w(r) r^power */
  int deriv; /* integrate dw/dr instead of w */
};

static double moment_integrand(double r, void *p) {
  const struct moment *m = p;
  const double f = m->deriv ? sph_kernel_dwdr(m->k, r) : sph_kernel_w(m->k, r);
  return f * pow(r, m->power);
}

static double integrate(const struct sph_kernel *k, int power, int deriv, double r0, double r1) {
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
  struct moment m = {k, power, deriv};
  gsl_function F = {moment_integrand, &m};
  double result, abserr;
  int status =
      gsl_integration_qag(&F, r0, r1, 0.0, 1e-12, 200, GSL_INTEG_GAUSS61, ws, &result, &abserr);
  gsl_integration_workspace_free(ws);
  assert_int_equal(status, GSL_SUCCESS);
  return result;
}

static void test_init_errors(void **state) {
  (void)state;
  struct sph_kernel k = {.dim = 7, .h = -3.0};
  assert_int_equal(sph_kernel_init(NULL, 2, H), -1);
  assert_int_equal(sph_kernel_init(&k, 0, H), -1);
  assert_int_equal(sph_kernel_init(&k, 4, H), -1);
  assert_int_equal(sph_kernel_init(&k, 2, 0.0), -1);
  assert_int_equal(sph_kernel_init(&k, 2, -H), -1);
  assert_int_equal(sph_kernel_init(&k, 2, NAN), -1);
  assert_int_equal(sph_kernel_init(&k, 2, INFINITY), -1);
  assert_int_equal(sph_kernel_init(&k, 2, 1e-320), -1); /* outside [1e-100, 1e100] */
  assert_int_equal(sph_kernel_init(&k, 2, 3e100), -1);
  assert_int_equal(k.dim, 7); /* untouched on error */
  assert_true(k.h == -3.0);
  for (int d = 1; d <= 3; d++) {
    assert_int_equal(sph_kernel_init(&k, d, H), 0);
    assert_int_equal(k.dim, d);
    assert_true(sph_kernel_support(&k) == 2.0 * H);
  }
}

/* ∫ w dV = 1: 2∫w dr (1D), 2π∫w r dr (2D), 4π∫w r² dr (3D). Fails for a wrong α_d or exponent. */
static void test_normalisation(void **state) {
  (void)state;
  const double shell[4] = {0.0, 2.0, 2.0 * PI, 4.0 * PI};
  for (int d = 1; d <= 3; d++) {
    struct sph_kernel k;
    assert_int_equal(sph_kernel_init(&k, d, H), 0);
    assert_rel(shell[d] * integrate(&k, d - 1, 0, 0.0, 2.0 * H), 1.0, 1e-13);
  }
  struct sph_kernel k;
  sph_kernel_init(&k, 1, H);
  assert_rel(k.alpha, 0.75, 1e-15);
  sph_kernel_init(&k, 2, H);
  assert_rel(k.alpha, 7.0 / (4.0 * PI), 1e-15);
  sph_kernel_init(&k, 3, H);
  assert_rel(k.alpha, 21.0 / (16.0 * PI), 1e-15);
}

/* Point values against the monomial form of docs/theory.md §3 and compact support. */
static void test_values(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 4242);
  for (int d = 1; d <= 3; d++) {
    struct sph_kernel k;
    sph_kernel_init(&k, d, H);
    const double norm = k.alpha / pow(H, d);
    assert_rel(sph_kernel_w(&k, 0.0), norm, 1e-15);
    assert_rel(sph_kernel_w(&k, H), norm * 3.0 / 16.0, 1e-14);
    assert_true(sph_kernel_w(&k, 2.0 * H) == 0.0);
    assert_true(sph_kernel_w(&k, 2.385 * H) == 0.0);
    assert_true(sph_kernel_dwdr(&k, 2.0 * H) == 0.0);
    assert_true(sph_kernel_dwdr(&k, 0.0) == 0.0);
    assert_rel(sph_kernel_w(&k, -0.7 * H), sph_kernel_w(&k, 0.7 * H), 1e-15);
    for (int i = 0; i < 200; i++) {
      const double q = sabre_rng_uniform(&rng, 0.0, 2.0);
      const double mono =
          1.0 - 2.5 * q * q + 2.5 * q * q * q - 15.0 / 16.0 * pow(q, 4) + 0.125 * pow(q, 5);
      assert_abs(sph_kernel_w(&k, q * H) / norm, mono, 1e-14);
      assert_abs(sph_kernel_w_inline(&k, q * H), sph_kernel_w(&k, q * H), 0.0);
    }
  }
}

/* dw/dr: central differences, and ∫_r0^r1 dw/dr = w(r1) − w(r0) by GSL quadrature. */
static void test_derivative(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 77);
  for (int d = 1; d <= 3; d++) {
    struct sph_kernel k;
    sph_kernel_init(&k, d, H);
    const double scale = k.alpha / pow(H, d + 1);
    for (int i = 0; i < 50; i++) {
      const double r = sabre_rng_uniform(&rng, 0.01, 1.99) * H, eps = 1e-6 * H;
      const double fd = (sph_kernel_w(&k, r + eps) - sph_kernel_w(&k, r - eps)) / (2.0 * eps);
      assert_abs(sph_kernel_dwdr(&k, r) / scale, fd / scale, 1e-8);
      assert_true(sph_kernel_dwdr(&k, r) < 0.0);
      const double r0 = sabre_rng_uniform(&rng, 0.0, 2.2) * H;
      const double integral = integrate(&k, 0, 1, r0, r);
      assert_abs(integral / (scale * H), (sph_kernel_w(&k, r) - sph_kernel_w(&k, r0)) / (scale * H),
                 1e-12);
    }
  }
}

/* The hot loops' dw/dr / r without a division (kernel.h) against dw/dr divided by r: equal to
 * round-off within the support (including r → 0, where it tends to −5 α_d/h^(d+2)), zero at and
 * beyond 2h. */
static void test_derivative_over_r(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 78);
  for (int d = 1; d <= 3; d++) {
    struct sph_kernel k;
    sph_kernel_init(&k, d, H);
    const double scale = k.alpha / pow(H, d + 2);
    double worst = 0.0;
    for (int i = 0; i < 2000; i++) {
      const double r = sabre_rng_uniform(&rng, 1e-9, 1.9999) * H;
      const double ref = sph_kernel_dwdr_inline(&k, r) / r;
      const double got = sph_kernel_dwdr_over_r_inline(&k, r);
      worst = fmax(worst, fabs(got - ref) / fabs(ref));
      assert_true(got < 0.0);
    }
    print_message("d = %d: largest relative difference %.2e\n", d, worst);
    assert_true(worst <= 2e-15);
    assert_abs(sph_kernel_dwdr_over_r_inline(&k, 1e-12 * H) / scale, -5.0, 1e-11);
    assert_true(sph_kernel_dwdr_over_r_inline(&k, 2.0 * H) == 0.0);
    assert_true(sph_kernel_dwdr_over_r_inline(&k, 2.5 * H) == 0.0);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_init_errors),
      cmocka_unit_test(test_normalisation),
      cmocka_unit_test(test_values),
      cmocka_unit_test(test_derivative),
      cmocka_unit_test(test_derivative_over_r),
  };
  return cmocka_run_group_tests(tests, sabre_setup_gsl_traps, NULL);
}
