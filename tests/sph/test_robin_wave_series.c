/* Analytical series M(78–79) of the Robin wave problem M(75–77), checked by itself: the roots
 * κ_i of M(79) (residual, ordering, none missed), orthogonality, norms and projections against GSL
 * quadrature, the Robin residual at both ends, the initial conditions, the wave equation by
 * finite differences, and the truncation error against an independent d'Alembert solution. */
#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/sph_analytic.h"
#include "testutil.h"

static const double K = 2.0 * M_PI; /* u_t(x, 0) = sin(Kx) */
static const double TIMES[] = {0.1, 0.22, 0.7, 0.81};
#define NTERMS 4000

static struct sph_robin_wave W;

/* ---------------------------------------------------------------------------------------------
 * Independent reference for t ≤ 1: d'Alembert u = H(x + t) − H(x − t), H' = g/2 on [0, 1], and H
 * extended beyond both ends so that the Robin conditions hold (docs/sph-robin.md §3.5):
 *   K(s) = H(−s):    K' + K = H − H',        K(0) = H(0) = 0
 *   J(s) = H(1 + s): J' + J = H(1−s) + H'(1−s), J(0) = H(1)
 * K and J by GSL quadrature of the variation-of-constants integrals.
 * ------------------------------------------------------------------------------------------- */
static double h0(double s) { return (1.0 - cos(K * s)) / (2.0 * K); }
static double dh0(double s) { return 0.5 * sin(K * s); }

struct ext_param {
  double s;
  int side; /* 0: K (left), 1: J (right) */
};
static double ext_integrand(double tau, void *vp) {
  const struct ext_param *p = vp;
  const double src = p->side == 0 ? h0(tau) - dh0(tau) : h0(1.0 - tau) + dh0(1.0 - tau);
  return exp(-(p->s - tau)) * src;
}
static double ext_value(int side, double s) {
  if (s == 0.0) return side == 0 ? h0(0.0) : h0(1.0);
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(100);
  struct ext_param p = {s, side};
  gsl_function f = {ext_integrand, &p};
  double r, err;
  assert_int_equal(
      gsl_integration_qag(&f, 0.0, s, 1e-15, 1e-12, 100, GSL_INTEG_GAUSS41, ws, &r, &err),
      GSL_SUCCESS);
  gsl_integration_workspace_free(ws);
  return (side == 0 ? h0(0.0) : h0(1.0)) * exp(-s) + r;
}
/* H(y) and H'(y) for y ∈ [−1, 2]. */
static void hext(double y, double *hv, double *dhv) {
  if (y < 0.0) {
    const double kv = ext_value(0, -y);
    *hv = kv;
    *dhv = kv - h0(-y) + dh0(-y); /* H'(−s) = −K'(s) = K − H + H' */
  } else if (y > 1.0) {
    const double s = y - 1.0, jv = ext_value(1, s);
    *hv = jv;
    *dhv = -jv + h0(1.0 - s) + dh0(1.0 - s); /* H'(1 + s) = J'(s) */
  } else {
    *hv = h0(y);
    *dhv = dh0(y);
  }
}
static void dalembert(double x, double t, double *u, double *u_t, double *u_x) {
  double hp, dhp, hm, dhm;
  hext(x + t, &hp, &dhp);
  hext(x - t, &hm, &dhm);
  *u = hp - hm;
  *u_t = dhp + dhm;
  *u_x = dhp - dhm;
}

/* ------------------------------------------------------------------------------------------- */

static double phi(double kap, double x) { return sin(kap * x) + kap * cos(kap * x); }

/* κ_i satisfy M(79), lie in ((i − 1)π, iπ), increase, and are all the roots: the number of sign
 * changes of (κ² − 1) sin κ − 2κ cos κ on a fine grid of (0, 200π) is 200. */
static void test_roots(void **state) {
  (void)state;
  double worst = 0.0;
  for (size_t i = 1; i <= NTERMS; i++) {
    const double kap = W.kappa[i - 1];
    assert_true(kap > (double)(i - 1) * M_PI && kap < (double)i * M_PI);
    if (i > 1) assert_true(kap - W.kappa[i - 2] > 2.0);
    /* M(79) multiplied by (κ² − 1) cos κ, normalised: equals sin(κ − 2 arctan(1/κ)). */
    const double res = ((kap * kap - 1.0) * sin(kap) - 2.0 * kap * cos(kap)) / (kap * kap + 1.0);
    if (i <= 200) {
      assert_abs(res, 0.0, 1e-12);
      worst = fmax(worst, fabs(res));
      /* and M(79) as written, where tan is not near a pole */
      if (fabs(cos(kap)) > 0.1) assert_abs(tan(kap), 2.0 * kap / (kap * kap - 1.0), 1e-12);
    } else {
      assert_abs(res, 0.0, 8.0 * DBL_EPSILON * kap); /* sin of a large argument: ε κ */
    }
    double single;
    if (i <= 50 || i % 397 == 0) {
      assert_int_equal(sph_robin_wave_root(i, &single), SPH_ROBIN_SUCCESS);
      assert_true(single == kap);
    }
  }
  print_message("M(79) residual, i <= 200: %.2e; kappa_1..4 = %.15f %.15f %.15f %.15f\n", worst,
                W.kappa[0], W.kappa[1], W.kappa[2], W.kappa[3]);
  /* κ_1 from κ = 2 arctan(1/κ) by fixed-point iteration (a contraction near the root). */
  double k1 = 1.0;
  for (int it = 0; it < 200; it++) k1 = 0.5 * (k1 + 2.0 * atan(1.0 / k1));
  assert_rel(W.kappa[0], k1, 1e-14);
  int changes = 0;
  const int n = 200000;
  double prev = -1.0; /* value just above κ = 0 is −2κ·1 + O(κ²) < 0 */
  for (int j = 1; j <= n; j++) {
    const double kap = 200.0 * M_PI * j / (n + 0.5);
    const double g = (kap * kap - 1.0) * sin(kap) - 2.0 * kap * cos(kap);
    if ((g > 0.0) != (prev > 0.0)) changes++;
    prev = g;
  }
  assert_int_equal(changes, 200);
  assert_int_equal(sph_robin_wave_root(0, &k1), SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_wave_root(3, NULL), SPH_ROBIN_EINVAL);
}

struct prod_param {
  double ki, kj; /* kj < 0: sin(Kx) instead of φ_j */
};
static double prod_integrand(double x, void *vp) {
  const struct prod_param *p = vp;
  return phi(p->ki, x) * (p->kj < 0.0 ? sin(K * x) : phi(p->kj, x));
}
static double integrate01(struct prod_param *p) {
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
  gsl_function f = {prod_integrand, p};
  double r, err;
  assert_int_equal(
      gsl_integration_qag(&f, 0.0, 1.0, 1e-11, 1e-12, 200, GSL_INTEG_GAUSS61, ws, &r, &err),
      GSL_SUCCESS);
  gsl_integration_workspace_free(ws);
  return r;
}

/* The eigenfunctions are orthogonal in plain L²(0, 1) (weight 1), ‖φ_i‖² = (κ_i² + 3)/2, and
 * α_i κ_i = <sin Kx, φ_i>/‖φ_i‖² as used by the library. */
static void test_orthogonality_and_projection(void **state) {
  (void)state;
  for (size_t i = 1; i <= 12; i++) {
    const double ki = W.kappa[i - 1];
    for (size_t j = 1; j <= i; j++) {
      struct prod_param p = {ki, W.kappa[j - 1]};
      const double v = integrate01(&p);
      if (i == j)
        assert_rel(v, 0.5 * (ki * ki + 3.0), 1e-12);
      else
        assert_abs(v, 0.0, 1e-12 * ki * W.kappa[j - 1]);
    }
    struct prod_param q = {ki, -1.0};
    const double proj = integrate01(&q);
    assert_abs(W.alpha[i - 1] * ki, proj / (0.5 * (ki * ki + 3.0)), 1e-13);
    /* φ_i(1) = (−1)^(i−1) κ_i, used to close the projection */
    assert_rel(phi(ki, 1.0), (i % 2 ? 1.0 : -1.0) * ki, 1e-12);
  }
}

/* ∂u/∂n − u = 0 at x = 0 (n = +x) and x = 1 (n = −x), with and without the tail correction. */
static void test_robin_residual(void **state) {
  (void)state;
  const double times[] = {0.1, 0.22, 0.7, 0.81, 1.37, 5.113};
  double worst = 0.0;
  for (int tail = 0; tail <= 1; tail++) {
    struct sph_robin_wave w = W;
    w.tail = tail;
    for (size_t it = 0; it < sizeof times / sizeof times[0]; it++) {
      double u0, ux0, u1, ux1;
      sph_robin_wave_eval(&w, 0.0, times[it], &u0, NULL, &ux0);
      sph_robin_wave_eval(&w, 1.0, times[it], &u1, NULL, &ux1);
      assert_abs(ux0 - u0, 0.0, 1e-10);
      assert_abs(-ux1 - u1, 0.0, 1e-10);
      worst = fmax(worst, fmax(fabs(ux0 - u0), fabs(ux1 + u1)));
    }
  }
  print_message("Robin residual at x = 0, 1: max %.2e (%d terms)\n", worst, NTERMS);
}

/* u(x, 0) = 0 and u_t(x, 0) = sin(2πx) to 1e-6 on x ∈ [0, 1] (boundaries included). */
static void test_initial_condition(void **state) {
  (void)state;
  double worst_t = 0.0, worst_plain = 0.0;
  for (int j = 0; j <= 100; j++) {
    const double x = j / 100.0;
    double u, ut;
    sph_robin_wave_eval(&W, x, 0.0, &u, &ut, NULL);
    assert_true(u == 0.0);
    assert_abs(ut, sin(K * x), 1e-6);
    worst_t = fmax(worst_t, fabs(ut - sin(K * x)));
    struct sph_robin_wave w = W;
    w.tail = 0;
    sph_robin_wave_eval(&w, x, 0.0, NULL, &ut, NULL);
    worst_plain = fmax(worst_plain, fabs(ut - sin(K * x)));
  }
  print_message(
      "u_t(x,0) - sin(2 pi x): max %.2e with the tail correction, %.2e without (%d "
      "terms)\n",
      worst_t, worst_plain, NTERMS);
}

/* Truncation error against the d'Alembert solution at the paper's four times (Fig. 6). */
static void test_against_dalembert(void **state) {
  (void)state;
  const size_t nts[] = {250, 1000, NTERMS};
  for (size_t in = 0; in < 2 * sizeof nts / sizeof nts[0]; in++) {
    struct sph_robin_wave w = W;
    const int tail = in % 2 == 0;
    w.n_terms = nts[in / 2];
    w.tail = tail;
    double eu = 0.0, eut = 0.0, eux = 0.0;
    for (size_t it = 0; it < sizeof TIMES / sizeof TIMES[0]; it++)
      for (int j = 0; j <= 100; j++) {
        const double x = j / 100.0, t = TIMES[it];
        double u, ut, ux, ue, ute, uxe;
        sph_robin_wave_eval(&w, x, t, &u, &ut, &ux);
        dalembert(x, t, &ue, &ute, &uxe);
        eu = fmax(eu, fabs(u - ue));
        eut = fmax(eut, fabs(ut - ute));
        eux = fmax(eux, fabs(ux - uxe));
      }
    print_message(
        "%5zu terms, tail correction %s: max |u - exact| = %.2e, |u_t - exact| = %.2e, "
        "|u_x - exact| = %.2e\n",
        w.n_terms, tail ? "on " : "off", eu, eut, eux);
    if (w.n_terms == NTERMS && tail) {
      assert_abs(eu, 0.0, 1e-8);
      assert_abs(eut, 0.0, 1e-6);
      assert_abs(eux, 0.0, 1e-6);
    }
  }
  /* The reference itself satisfies the initial and boundary conditions. */
  double u, ut, ux;
  dalembert(0.37, 0.0, &u, &ut, &ux);
  assert_abs(u, 0.0, 1e-15);
  assert_abs(ut, sin(K * 0.37), 1e-15);
  for (size_t it = 0; it < sizeof TIMES / sizeof TIMES[0]; it++) {
    dalembert(0.0, TIMES[it], &u, &ut, &ux);
    assert_abs(ux - u, 0.0, 1e-12);
    dalembert(1.0, TIMES[it], &u, &ut, &ux);
    assert_abs(-ux - u, 0.0, 1e-12);
  }
}

/* u_tt − u_xx = 0 by central differences of u_t in t and u_x in x, at points whose
 * characteristics x ± t stay away from the integers (the tail correction has kinks there). */
static void test_wave_equation(void **state) {
  (void)state;
  const double d = 1e-4;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 75u);
  int checked = 0;
  while (checked < 40) {
    const double x = sabre_rng_uniform(&rng, 0.01, 0.99), t = sabre_rng_uniform(&rng, 0.0, 3.0);
    const double fp = x + t - floor(x + t), fm = x - t - floor(x - t);
    if (fmin(fp, 1.0 - fp) < 10.0 * d || fmin(fm, 1.0 - fm) < 10.0 * d) continue;
    double utp, utm, uxp, uxm, uxx_dummy;
    sph_robin_wave_eval(&W, x, t + d, NULL, &utp, &uxx_dummy);
    sph_robin_wave_eval(&W, x, t - d, NULL, &utm, NULL);
    sph_robin_wave_eval(&W, x + d, t, NULL, NULL, &uxp);
    sph_robin_wave_eval(&W, x - d, t, NULL, NULL, &uxm);
    const double utt = (utp - utm) / (2.0 * d), uxx = (uxp - uxm) / (2.0 * d);
    /* u_tt is O(K²) = O(40); central differences err by d²/6 |u''''| ≲ 1e-6. */
    assert_abs(utt - uxx, 0.0, 1e-5);
    checked++;
  }
}

/* With SABRE_ROBIN_WAVE_CSV=<path> in the environment, write the analytical solution at the four
 * times of M Fig. 6 for cases/sph/robin_wave_1d/plot_analytic.py (columns t, x, u, u_t, u_x).
 * Without it the test only checks that the evaluation is finite on that grid. */
static void test_fig6_table(void **state) {
  (void)state;
  const char *path = getenv("SABRE_ROBIN_WAVE_CSV");
  FILE *f = path != NULL ? fopen(path, "w") : NULL;
  if (path != NULL) assert_non_null(f);
  if (f != NULL) fprintf(f, "t,x,u,u_t,u_x\n");
  for (size_t it = 0; it < sizeof TIMES / sizeof TIMES[0]; it++)
    for (int j = 0; j <= 200; j++) {
      const double x = j / 200.0;
      double u, ut, ux;
      sph_robin_wave_eval(&W, x, TIMES[it], &u, &ut, &ux);
      assert_true(isfinite(u) && isfinite(ut) && isfinite(ux));
      if (f != NULL) fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g\n", TIMES[it], x, u, ut, ux);
    }
  if (f != NULL) {
    assert_int_equal(fclose(f), 0);
    print_message("wrote %s\n", path);
  }
}

static void test_bad_input(void **state) {
  (void)state;
  struct sph_robin_wave w;
  assert_int_equal(sph_robin_wave_init(&w, 0), SPH_ROBIN_EINVAL);
  assert_null(w.kappa);
  sph_robin_wave_free(&w);
  assert_int_equal(sph_robin_wave_init(NULL, 10), SPH_ROBIN_EINVAL);
  sph_robin_wave_free(NULL);
  assert_string_equal(sph_robin_status_name(SPH_ROBIN_ENOCONV), "SPH_ROBIN_ENOCONV");
  assert_string_equal(sph_robin_status_name(SPH_ROBIN_ENOMEM), "SPH_ROBIN_ENOMEM");
}

static int setup(void **state) {
  (void)state;
  gsl_set_error_handler_off();
  sabre_fp_traps_on();
  return sph_robin_wave_init(&W, NTERMS) == SPH_ROBIN_SUCCESS ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  sph_robin_wave_free(&W);
  return 0;
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_roots),
      cmocka_unit_test(test_orthogonality_and_projection),
      cmocka_unit_test(test_robin_residual),
      cmocka_unit_test(test_initial_condition),
      cmocka_unit_test(test_against_dalembert),
      cmocka_unit_test(test_wave_equation),
      cmocka_unit_test(test_fig6_table),
      cmocka_unit_test(test_bad_input),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
