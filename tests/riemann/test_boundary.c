/* Boundary Riemann problem (J §III, docs/theory.md §1.1): invariants on expansions,
 * Rankine–Hugoniot and Lax on shocks, Newton against the closed form, continuity at the
 * expansion/shock switch, consistency with the exact solver, tangential rules, batch, and every
 * error code. */
#include <float.h>
#include <gsl/gsl_errno.h>
#include <math.h>

#include "fixture.h"
#include "sabre/riemann.h"
#include "testutil.h"

static const double XIS[] = {1.0, 2.0, 7.0};

/* Random subsonic interior state and imposed value of either kind, either wave direction. */
static void random_problem(struct sabre_rng *rng, const struct rmn_eos *e, double *rho, double *un,
                           enum rmn_imposed *imposed, double *value, int want_shock) {
  *rho = e->rho0 * sabre_rng_uniform(rng, 0.9, 1.1);
  double c = rmn_eos_sound_speed(e, *rho);
  *un = c * sabre_rng_uniform(rng, -0.3, 0.3);
  double sign = want_shock ? 1.0 : -1.0;
  if (sabre_rng_uniform(rng, 0, 1) < 0.5) {
    *imposed = RMN_IMPOSE_PRESSURE;
    double dp = sign * (*rho) * c * c * pow(10.0, sabre_rng_uniform(rng, -9, -1.3));
    *value = rmn_eos_pressure(e, *rho) + dp;
  } else {
    *imposed = RMN_IMPOSE_VELOCITY;
    *value = *un + sign * c * pow(10.0, sabre_rng_uniform(rng, -9, -1.3));
  }
}

static void test_expansion_invariant(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 11);
  for (size_t k = 0; k < 3; ++k) {
    struct rmn_eos e;
    rmn_eos_init(&e, 1000.0, 23.85, XIS[k]);
    for (int i = 0; i < 3000; ++i) {
      double rho, un, value;
      enum rmn_imposed imp;
      random_problem(&rng, &e, &rho, &un, &imp, &value, 0);
      struct rmn_normal_state s;
      assert_int_equal(rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, imp, value, &s),
                       RMN_SUCCESS);
      assert_int_equal(s.wave, RMN_WAVE_EXPANSION);
      assert_true(s.rho < rho);
      /* R+1 conserved, J(29); λ+1(2) < λ+1(int), J(28) */
      assert_abs(rmn_invariant_plus(&e, s.rho, s.un), rmn_invariant_plus(&e, rho, un),
                 1e-14 * e.c0);
      assert_true(s.un + rmn_eos_sound_speed(&e, s.rho) < un + rmn_eos_sound_speed(&e, rho));
      assert_abs(s.p - rmn_eos_pressure(&e, s.rho), 0.0, 1e-14 * rho * e.c0 * e.c0);
      if (imp == RMN_IMPOSE_PRESSURE) assert_true(s.p == value);
      if (imp == RMN_IMPOSE_VELOCITY) assert_true(s.un == value);
      assert_int_equal(s.flow, s.un >= 0 ? RMN_FLOW_INFLOW : RMN_FLOW_OUTFLOW);
      assert_true(isnan(s.shock_speed));
    }
  }
}

/* Every shock: RH residuals ≤ 1e-12 (relative to ρc and ρc²), Lax condition, Newton = closed form.
 */
static void test_shock_rankine_hugoniot(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 12);
  int max_it = 0;
  for (size_t k = 0; k < 3; ++k) {
    struct rmn_eos e;
    rmn_eos_init(&e, 1000.0, 23.85, XIS[k]);
    for (int i = 0; i < 3000; ++i) {
      double rho, un, value;
      enum rmn_imposed imp;
      random_problem(&rng, &e, &rho, &un, &imp, &value, 1);
      struct rmn_normal_state s;
      assert_int_equal(rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, imp, value, &s),
                       RMN_SUCCESS);
      assert_int_equal(s.wave, RMN_WAVE_SHOCK);
      assert_true(s.rho > rho);
      double c = rmn_eos_sound_speed(&e, rho), c2 = rmn_eos_sound_speed(&e, s.rho);
      double res[2];
      rmn_shock_residuals(&e, rho, un, s.rho, s.un, s.shock_speed, res);
      assert_abs(res[0] / (rho * c), 0.0, 1e-12);
      assert_abs(res[1] / (rho * c * c), 0.0, 1e-12);
      /* Lax: λ+1(int) < S < λ+1(2) (J 30) */
      assert_true(un + c < s.shock_speed);
      assert_true(s.shock_speed < s.un + c2);
      /* Newton result against the closed form with S eliminated */
      assert_abs(s.un, rmn_shock_velocity_closed_form(&e, rho, un, s.rho), 1e-12 * c);
      if (imp == RMN_IMPOSE_PRESSURE) assert_true(s.p == value);
      if (imp == RMN_IMPOSE_VELOCITY) assert_true(s.un == value);
      if (s.iterations > max_it) max_it = s.iterations;
    }
  }
  assert_true(max_it <= 8); /* Newton from the acoustic guess is quadratic */
}

/* Strong shocks (density ratio up to 2 for ξ = 1 and ξ = 2, pressure of 100 ρ0c0² for ξ = 7). */
static void test_strong_shocks(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  for (size_t k = 0; k < 3; ++k) {
    struct rmn_eos e;
    rmn_eos_init(&e, 1.0, 1.0, XIS[k]);
    for (double ratio = 1.01; ratio < 2.0; ratio *= 1.1) {
      double rho = 1.0, un = -0.2, rho2 = ratio * rho;
      struct rmn_normal_state s;
      int st = rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, RMN_IMPOSE_PRESSURE,
                                         rmn_eos_pressure(&e, rho2), &s);
      double u_cf = rmn_shock_velocity_closed_form(&e, rho, un, rho2);
      if (fabs(u_cf) >= rmn_eos_sound_speed(&e, rho2)) {
        assert_int_equal(st, RMN_ESUPERSONIC);
        continue;
      }
      assert_int_equal(st, RMN_SUCCESS);
      assert_abs(s.un, u_cf, 1e-12);
      struct rmn_normal_state v;
      assert_int_equal(
          rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, RMN_IMPOSE_VELOCITY, s.un, &v),
          RMN_SUCCESS);
      assert_rel(v.rho, s.rho, 1e-12); /* imposing the velocity found gives back the density */
      assert_rel(v.shock_speed, s.shock_speed, 1e-11);
    }
  }
}

/* Continuity across the expansion/shock switch: as ρ2 → ρ_int from both sides, u2 → u_int with
 * the acoustic slope 1/(ρc) (pressure) and ρ2 with slope ρ/c (velocity), S → λ+1(int). */
static void test_switch_continuity(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  for (size_t k = 0; k < 3; ++k) {
    struct rmn_eos e;
    rmn_eos_init(&e, 1000.0, 20.0, XIS[k]);
    const double rho = 1010.0, un = 1.5, c = rmn_eos_sound_speed(&e, rho);
    const double p = rmn_eos_pressure(&e, rho);
    for (double eps = 1e-2; eps > 1e-10; eps *= 0.1) {
      double dp = eps * rho * c * c, du = eps * c;
      /* second-order term, plus the representation of ρ2 and u2 themselves (one ulp of ρ, c) */
      const double tol = 4.0 * eps + 4.0 * DBL_EPSILON / eps;
      struct rmn_normal_state a, b, va, vb;
      assert_int_equal(
          rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, RMN_IMPOSE_PRESSURE, p - dp, &a),
          RMN_SUCCESS);
      assert_int_equal(
          rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, RMN_IMPOSE_PRESSURE, p + dp, &b),
          RMN_SUCCESS);
      assert_int_equal(a.wave, RMN_WAVE_EXPANSION);
      assert_int_equal(b.wave, RMN_WAVE_SHOCK);
      /* first order: u2 − u_int = ±dp/(ρc) + O(eps²) on both sides */
      assert_abs((a.un - un) / (eps * c), -1.0, tol);
      assert_abs((b.un - un) / (eps * c), 1.0, tol);
      assert_abs((b.shock_speed - un - c) / c, 0.0, 4.0 * eps);
      assert_int_equal(
          rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, RMN_IMPOSE_VELOCITY, un - du, &va),
          RMN_SUCCESS);
      assert_int_equal(
          rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, RMN_IMPOSE_VELOCITY, un + du, &vb),
          RMN_SUCCESS);
      assert_abs((va.rho - rho) / (eps * rho), -1.0, tol);
      assert_abs((vb.rho - rho) / (eps * rho), 1.0, tol);
    }
    /* exactly at the interior state: a contact, the interior itself */
    struct rmn_normal_state s;
    assert_int_equal(
        rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, RMN_IMPOSE_PRESSURE, p, &s),
        RMN_SUCCESS);
    assert_int_equal(s.wave, RMN_WAVE_CONTACT);
    assert_rel(s.rho, rho, 1e-15);
    assert_abs(s.un, un, 1e-14);
    assert_int_equal(
        rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, RMN_IMPOSE_VELOCITY, un, &s),
        RMN_SUCCESS);
    assert_int_equal(s.wave, RMN_WAVE_CONTACT);
    assert_rel(s.rho, rho, 1e-15);
  }
}

/* The boundary state is the star state of the full Riemann problem (left = state 2, right =
 * interior): the left wave is void and the right wave is the boundary's λ+1 wave. Catches any
 * left/right mix-up between the two solvers. */
static void test_consistent_with_exact_solver(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 13);
  for (size_t k = 0; k < 3; ++k) {
    struct rmn_eos e;
    rmn_eos_init(&e, 1000.0, 23.85, XIS[k]);
    for (int i = 0; i < 500; ++i) {
      double rho, un, value;
      enum rmn_imposed imp;
      random_problem(&rng, &e, &rho, &un, &imp, &value, i % 2);
      struct rmn_normal_state s;
      assert_int_equal(rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, imp, value, &s),
                       RMN_SUCCESS);
      struct rmn_exact x;
      assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, s.rho, s.un, rho, un, &x), RMN_SUCCESS);
      assert_rel(x.rho_star, s.rho, 1e-12);
      assert_abs(x.u_star, s.un, 1e-11 * e.c0);
      assert_int_equal(x.right, s.wave == RMN_WAVE_SHOCK ? RMN_EXACT_SHOCK : RMN_EXACT_RAREFACTION);
      if (s.wave == RMN_WAVE_SHOCK && s.rho - rho > 1e-6 * rho)
        assert_rel(x.right_head, s.shock_speed, 1e-8);
    }
  }
}

/* Tangential rules of J §III in 2D and 3D with arbitrary normals, and the batch call. */
static void test_tangential_and_batch(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  struct rmn_eos e;
  rmn_eos_init(&e, 1000.0, 20.0, 7.0);
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 14);
  enum { N = 64 };
  struct rmn_boundary_input in[N];
  struct rmn_boundary_result out[N];
  for (int dim = 1; dim <= 3; ++dim) {
    for (int i = 0; i < N; ++i) {
      struct rmn_boundary_input b = {.rho = 1000.0 * sabre_rng_uniform(&rng, 0.99, 1.01),
                                     .imposed = i % 2 ? RMN_IMPOSE_VELOCITY : RMN_IMPOSE_PRESSURE,
                                     .ut = {0.31, -0.72}};
      for (int d = 0; d < dim; ++d) {
        b.normal[d] = sabre_rng_uniform(&rng, -1, 1);
        b.u[d] = sabre_rng_uniform(&rng, -2, 2);
      }
      b.value = b.imposed == RMN_IMPOSE_VELOCITY ? sabre_rng_uniform(&rng, -2, 2)
                                                 : sabre_rng_uniform(&rng, -3000, 3000);
      in[i] = b;
    }
    size_t first = 99;
    assert_int_equal(rmn_boundary_solve_batch(&e, &f->par, f->ws, dim, N, in, out, &first),
                     RMN_SUCCESS);
    assert_int_equal(first, 99);
    for (int i = 0; i < N; ++i) {
      struct rmn_boundary_result one;
      assert_int_equal(rmn_boundary_solve(&e, &f->par, f->ws, dim, &in[i], &one), RMN_SUCCESS);
      struct rmn_frame fr;
      rmn_frame_from_normal(dim, in[i].normal, &fr);
      double loc_in[3], loc_out[3];
      rmn_frame_to_local(&fr, in[i].u, loc_in);
      rmn_frame_to_local(&fr, out[i].u, loc_out);
      struct rmn_normal_state ns;
      rmn_boundary_solve_normal(&e, &f->par, f->ws, in[i].rho, loc_in[0], in[i].imposed,
                                in[i].value, &ns);
      assert_rel(out[i].rho, ns.rho, 1e-15);
      assert_abs(loc_out[0], ns.un, 1e-13);
      assert_abs(out[i].un, ns.un, 0.0);
      for (int t = 1; t < dim; ++t) {
        double expect = ns.flow == RMN_FLOW_INFLOW ? in[i].ut[t - 1] : loc_in[t];
        assert_abs(loc_out[t], expect, 1e-13);
        assert_abs(out[i].ut[t - 1], expect, 1e-15);
      }
      for (int d = 0; d < dim; ++d) assert_abs(one.u[d], out[i].u[d], 0.0);
    }
  }
  /* a failing segment in the middle: the others are still solved, its index is reported */
  in[5].rho = -1.0;
  in[9].u[0] = 1e6;
  size_t first = 0;
  sabre_fp_traps_off();
  assert_int_equal(rmn_boundary_solve_batch(&e, &f->par, f->ws, 3, N, in, out, &first),
                   RMN_EDENSITY);
  assert_int_equal(first, 5);
  assert_int_equal(out[5].status, RMN_EDENSITY);
  assert_true(isnan(out[5].rho));
  assert_int_equal(out[9].status, RMN_ESUPERSONIC);
  assert_int_equal(out[6].status, RMN_SUCCESS);
}

/* The linearised (GPUSPH-style) shock: p2 − p_int = ρ_int u_int (u_int − u2), shock at rest. */
static void test_linearised_shock(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  struct rmn_eos e;
  rmn_eos_init(&e, 1000.0, 20.0, 7.0);
  struct rmn_params lin = f->par;
  lin.shock = RMN_SHOCK_LINEARISED;
  double rho = 1000.0, un = -0.5, p = rmn_eos_pressure(&e, rho);
  struct rmn_normal_state s;
  assert_int_equal(rmn_boundary_solve_normal(&e, &lin, NULL, rho, un, RMN_IMPOSE_VELOCITY, 0.0, &s),
                   RMN_SUCCESS);
  assert_rel(s.p - p, rho * un * (un - 0.0), 1e-12);
  assert_abs(s.shock_speed, 0.0, 0.0);
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &lin, NULL, rho, un, RMN_IMPOSE_PRESSURE, p + 200.0, &s),
      RMN_SUCCESS);
  assert_rel(s.un, un - 200.0 / (rho * un), 1e-14);
  /* it differs from the exact shock by far more than round-off: it is a model, not the default */
  struct rmn_normal_state x;
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, f->ws, rho, un, RMN_IMPOSE_PRESSURE, p + 200.0, &x),
      RMN_SUCCESS);
  assert_true(fabs(x.un - s.un) > 0.1);
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &lin, NULL, rho, 0.0, RMN_IMPOSE_PRESSURE, p + 200.0, &s),
      RMN_EUNDEFINED);
}

/* Every error code of the boundary solver, triggered on purpose. */
static void test_errors(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_off();
  struct rmn_eos e;
  rmn_eos_init(&e, 1000.0, 20.0, 7.0);
  struct rmn_normal_state s = {.rho = 123.0};
  const double p0 = 0.0;
  /* supersonic interior (|u| ≥ c) and supersonic result */
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, f->ws, 1000.0, 25.0, RMN_IMPOSE_PRESSURE, p0, &s),
      RMN_ESUPERSONIC);
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, f->ws, 1000.0, -20.0, RMN_IMPOSE_PRESSURE, p0, &s),
      RMN_ESUPERSONIC);
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, f->ws, 1000.0, 0.0, RMN_IMPOSE_VELOCITY, -6.0, &s),
      RMN_ESUPERSONIC); /* ψ2 = 20/3 − 6 > 0 but c2 = 3ψ2 = 2 < 6 */
  /* cavitation: pressure at or below p(0), or an expansion down to ψ = 0 */
  assert_int_equal(rmn_boundary_solve_normal(&e, &f->par, f->ws, 1000.0, 0.0, RMN_IMPOSE_PRESSURE,
                                             rmn_eos_min_pressure(&e), &s),
                   RMN_ECAVITATION);
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, f->ws, 1000.0, 0.0, RMN_IMPOSE_PRESSURE, -1e9, &s),
      RMN_ECAVITATION);
  assert_int_equal(rmn_boundary_solve_normal(&e, &f->par, f->ws, 1000.0, 5.0, RMN_IMPOSE_VELOCITY,
                                             5.0 - rmn_eos_psi(&e, 1000.0), &s),
                   RMN_ECAVITATION);
  /* invalid input */
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, f->ws, 0.0, 0.0, RMN_IMPOSE_PRESSURE, p0, &s),
      RMN_EDENSITY);
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, f->ws, -5.0, 0.0, RMN_IMPOSE_PRESSURE, p0, &s),
      RMN_EDENSITY);
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, f->ws, NAN, 0.0, RMN_IMPOSE_PRESSURE, p0, &s),
      RMN_EINVAL);
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, f->ws, 1000.0, 0.0, RMN_IMPOSE_PRESSURE, NAN, &s),
      RMN_EINVAL);
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, f->ws, 1000.0, 0.0, (enum rmn_imposed)7, p0, &s),
      RMN_EINVAL);
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &f->par, NULL, 1000.0, 0.0, RMN_IMPOSE_PRESSURE, 100.0, &s),
      RMN_EINVAL); /* a shock needs the workspace */
  struct rmn_params bad = f->par;
  bad.tol_rel = 0.0;
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &bad, f->ws, 1000.0, 0.0, RMN_IMPOSE_PRESSURE, p0, &s),
      RMN_EINVAL);
  bad = f->par;
  bad.max_iter = 0;
  assert_int_equal(rmn_params_check(&bad), RMN_EINVAL);
  /* non-convergence: one Newton iteration cannot reach 1e-14 on a strong shock */
  bad = f->par;
  bad.max_iter = 1;
  assert_int_equal(
      rmn_boundary_solve_normal(&e, &bad, f->ws, 1000.0, 0.0, RMN_IMPOSE_PRESSURE, 5e4, &s),
      RMN_ENOCONV);
  assert_rel(s.rho, 123.0, 0.0); /* untouched on error */
  /* the full call reports a bad normal and marks the result */
  struct rmn_boundary_input in = {.normal = {0, 0, 0}, .rho = 1000.0};
  struct rmn_boundary_result r;
  assert_int_equal(rmn_boundary_solve(&e, &f->par, f->ws, 2, &in, &r), RMN_EINVAL);
  assert_int_equal(r.status, RMN_EINVAL);
  assert_true(isnan(r.p));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_expansion_invariant),
      cmocka_unit_test(test_shock_rankine_hugoniot),
      cmocka_unit_test(test_strong_shocks),
      cmocka_unit_test(test_switch_continuity),
      cmocka_unit_test(test_consistent_with_exact_solver),
      cmocka_unit_test(test_tangential_and_batch),
      cmocka_unit_test(test_linearised_shock),
      cmocka_unit_test(test_errors),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
