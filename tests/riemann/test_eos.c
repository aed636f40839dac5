/* Equation of state, invariants and local frame: round trips, derivatives, frame algebra. */
#include <math.h>

#include "sabre/riemann.h"
#include "testutil.h"

static const double XIS[] = {1.0, 1.4, 2.0, 7.0};

static void test_round_trips(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 20161);
  for (size_t k = 0; k < sizeof XIS / sizeof *XIS; ++k) {
    struct rmn_eos e;
    assert_int_equal(rmn_eos_init(&e, 998.2, 23.85, XIS[k]), RMN_SUCCESS);
    for (int i = 0; i < 2000; ++i) {
      /* ρ(p) is ill-conditioned where p(ρ) is flat (p → p(0) for ξ = 7 at low density), so the
       * round trip is checked on the range of weakly-compressible flows and beyond. */
      double rho = 998.2 * sabre_rng_uniform(&rng, 0.5, 1.5);
      assert_rel(rmn_eos_density(&e, rmn_eos_pressure(&e, rho)), rho, 1e-14);
      assert_rel(rmn_eos_density_from_psi(&e, rmn_eos_psi(&e, rho)), rho, 1e-14);
      double p = rmn_eos_pressure(&e, rho);
      assert_rel(rmn_eos_pressure(&e, rmn_eos_density(&e, p)), p, 1e-12);
      /* increments are consistent with the absolute maps */
      double drho = rho * sabre_rng_uniform(&rng, -0.3, 0.3);
      double dp = rmn_eos_pressure_increment(&e, rho, drho);
      assert_rel(dp, rmn_eos_pressure(&e, rho + drho) - p,
                 1e-12 * fmax(1.0, fabs(p) / fmax(fabs(dp), 1e-300)));
      assert_rel(rmn_eos_density_increment(&e, rho, dp), drho, 1e-13);
    }
  }
}

static void test_increments_small(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct rmn_eos e;
  rmn_eos_init(&e, 1000.0, 20.0, 7.0);
  /* For tiny increments δp = c² δρ to first order, with full relative precision. */
  double rho = 1010.0, c = rmn_eos_sound_speed(&e, rho);
  for (double drho = 1e-3; drho > 1e-13; drho *= 0.1) {
    double dp = rmn_eos_pressure_increment(&e, rho, drho);
    assert_rel(dp, c * c * drho, 10.0 * drho / rho * 7.0);
    assert_rel(rmn_eos_density_increment(&e, rho, dp), drho, 1e-14);
  }
}

/* c² = dp/dρ and dψ/dρ = c/ρ, checked by central differences. */
static void test_derivatives(void **state) {
  (void)state;
  sabre_fp_traps_on();
  for (size_t k = 0; k < sizeof XIS / sizeof *XIS; ++k) {
    struct rmn_eos e;
    rmn_eos_init(&e, 1.2, 340.0, XIS[k]);
    for (double rho = 0.5; rho < 2.0; rho += 0.173) {
      double h = 1e-5 * rho;
      double c = rmn_eos_sound_speed(&e, rho);
      double dpdrho = (rmn_eos_pressure(&e, rho + h) - rmn_eos_pressure(&e, rho - h)) / (2 * h);
      double dpsidrho = (rmn_eos_psi(&e, rho + h) - rmn_eos_psi(&e, rho - h)) / (2 * h);
      assert_rel(dpdrho, c * c, 1e-8);
      assert_rel(dpsidrho, c / rho, 1e-8);
      assert_rel(rmn_eos_sound_speed_from_psi(&e, rmn_eos_psi(&e, rho)), c, 1e-14);
    }
  }
}

static void test_reference_values(void **state) {
  (void)state;
  struct rmn_eos e;
  rmn_eos_init(&e, 1000.0, 20.0, 7.0);
  assert_abs(rmn_eos_pressure(&e, 1000.0), 0.0, 0.0);
  assert_rel(rmn_eos_sound_speed(&e, 1000.0), 20.0, 1e-15);
  assert_rel(rmn_eos_psi(&e, 1000.0), 2.0 * 20.0 / 6.0, 1e-15);
  assert_rel(rmn_eos_min_pressure(&e), -1000.0 * 400.0 / 7.0, 1e-15);
  assert_rel(rmn_eos_pressure(&e, 0.0), rmn_eos_min_pressure(&e), 1e-15);
  assert_abs(rmn_eos_psi(&e, 0.0), 0.0, 0.0);
  rmn_eos_init(&e, 1.0, 3.0, 1.0);
  assert_rel(rmn_eos_pressure(&e, 2.0), 9.0, 1e-15);
  assert_abs(rmn_eos_psi(&e, 1.0), 0.0, 0.0);
  assert_true(isinf(rmn_eos_min_pressure(&e)));
  /* invariants J(21-23) */
  rmn_eos_init(&e, 1000.0, 20.0, 7.0);
  double psi = rmn_eos_psi(&e, 1003.0);
  assert_rel(rmn_invariant_minus(&e, 1003.0, 0.37), 0.37 + psi, 1e-15);
  assert_rel(rmn_invariant_plus(&e, 1003.0, 0.37), 0.37 - psi, 1e-15);
  assert_rel(rmn_invariant_zero(0.37), 0.37, 0.0);
}

static void test_eos_errors(void **state) {
  (void)state;
  sabre_fp_traps_off();
  struct rmn_eos e = {0};
  assert_int_equal(rmn_eos_init(&e, 1000.0, 20.0, 0.99), RMN_EINVAL);
  assert_int_equal(rmn_eos_init(&e, 0.0, 20.0, 7.0), RMN_EINVAL);
  assert_int_equal(rmn_eos_init(&e, 1000.0, -1.0, 7.0), RMN_EINVAL);
  assert_int_equal(rmn_eos_init(&e, NAN, 20.0, 7.0), RMN_EINVAL);
  assert_int_equal(rmn_eos_init(&e, 1000.0, INFINITY, 7.0), RMN_EINVAL);
  assert_int_equal(rmn_eos_init(NULL, 1000.0, 20.0, 7.0), RMN_EINVAL);
  assert_true(e.rho0 == 0.0); /* untouched on error */
  assert_int_equal(rmn_eos_check_density(1.0), RMN_SUCCESS);
  assert_int_equal(rmn_eos_check_density(0.0), RMN_EDENSITY);
  assert_int_equal(rmn_eos_check_density(-3.0), RMN_EDENSITY);
  assert_int_equal(rmn_eos_check_density(NAN), RMN_EINVAL);
  /* every status has a distinct name and a text */
  for (int s = RMN_SUCCESS; s <= RMN_EUNDEFINED; ++s) {
    assert_string_not_equal(rmn_status_name(s), "RMN_UNKNOWN");
    assert_true(rmn_strerror(s)[0] != '\0');
  }
  assert_string_equal(rmn_status_name(RMN_ECAVITATION), "RMN_ECAVITATION");
  assert_string_equal(rmn_status_name(99), "RMN_UNKNOWN");
}

static void check_frame(int dim, const double *normal) {
  struct rmn_frame f;
  assert_int_equal(rmn_frame_from_normal(dim, normal, &f), RMN_SUCCESS);
  const double *ax[3] = {f.n, f.t1, f.t2};
  double nn = 0.0;
  for (int i = 0; i < dim; ++i) nn += normal[i] * normal[i];
  for (int i = 0; i < dim; ++i) assert_rel(f.n[i], normal[i] / sqrt(nn), 1e-15);
  for (int a = 0; a < dim; ++a)
    for (int b = 0; b < dim; ++b) {
      double dot = 0.0;
      for (int i = 0; i < dim; ++i) dot += ax[a][i] * ax[b][i];
      assert_abs(dot, a == b ? 1.0 : 0.0, 1e-15);
    }
  if (dim == 3) { /* right-handed: t2 = n × t1 */
    assert_abs(f.n[0] * (f.t1[1] * f.t2[2] - f.t1[2] * f.t2[1]) +
                   f.n[1] * (f.t1[2] * f.t2[0] - f.t1[0] * f.t2[2]) +
                   f.n[2] * (f.t1[0] * f.t2[1] - f.t1[1] * f.t2[0]),
               1.0, 1e-15);
  }
  double v[3] = {0.385, -2.17, 1.234}, loc[3], back[3];
  rmn_frame_to_local(&f, v, loc);
  rmn_frame_to_global(&f, loc, back);
  for (int i = 0; i < dim; ++i) assert_abs(back[i], v[i], 4e-15);
  double vn = 0.0;
  for (int i = 0; i < dim; ++i) vn += v[i] * f.n[i];
  assert_abs(loc[0], vn, 1e-15);
}

static void test_frame(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 7);
  check_frame(1, (double[]){-2.0});
  check_frame(2, (double[]){0.0, 3.0});
  check_frame(3, (double[]){0.0, 0.0, -1.0});
  check_frame(3, (double[]){1.0, 1.0, 1.0});
  for (int i = 0; i < 200; ++i) {
    double n[3] = {sabre_rng_uniform(&rng, -1, 1), sabre_rng_uniform(&rng, -1, 1),
                   sabre_rng_uniform(&rng, -1, 1)};
    check_frame(2, n);
    check_frame(3, n);
  }
  struct rmn_frame f;
  sabre_fp_traps_off();
  assert_int_equal(rmn_frame_from_normal(4, (double[]){1, 0, 0, 0}, &f), RMN_EINVAL);
  assert_int_equal(rmn_frame_from_normal(2, (double[]){0.0, 0.0}, &f), RMN_EINVAL);
  assert_int_equal(rmn_frame_from_normal(2, (double[]){NAN, 1.0}, &f), RMN_EINVAL);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_round_trips), cmocka_unit_test(test_increments_small),
      cmocka_unit_test(test_derivatives), cmocka_unit_test(test_reference_values),
      cmocka_unit_test(test_eos_errors),  cmocka_unit_test(test_frame),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
