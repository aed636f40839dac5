/* Exact two-wave Riemann solver (docs/theory.md §1.2): shallow-water closed forms for ξ = 2 (Ritter
 * dry bed, Stoker wet bed, computed here independently of the solver), Rankine–Hugoniot across
 * shocks, invariants across fans, mirror symmetry, vacuum, errors. */
#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>

#include "fixture.h"
#include "sabre/riemann.h"
#include "testutil.h"

/* Shallow water as ξ = 2: h ↔ ρ with ρ0 = 1 and g = c0²/ρ0, so c = sqrt(g h). */
static struct rmn_eos shallow_water(double g) {
  struct rmn_eos e;
  rmn_eos_init(&e, 1.0, sqrt(g), 2.0);
  return e;
}

/* Ritter (1892): dam break on a dry bed, h_L at rest for x < 0. */
static void test_ritter(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  const double g = 9.81, hl = 0.6, cl = sqrt(g * hl);
  struct rmn_eos e = shallow_water(g);
  struct rmn_exact s;
  assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, hl, 0.0, 0.0, 0.0, &s), RMN_SUCCESS);
  assert_true(s.vacuum);
  assert_rel(s.left_head, -cl, 1e-15);
  assert_rel(s.left_tail, 2.0 * cl, 1e-15);
  for (double xi = -2.0 * cl; xi <= 3.0 * cl; xi += 0.0137 * cl) {
    double h, u;
    rmn_exact_sample(&s, xi, &h, &u);
    if (xi <= -cl) {
      assert_rel(h, hl, 0.0);
      assert_abs(u, 0.0, 0.0);
    } else if (xi < 2.0 * cl) {
      assert_rel(h, (2.0 * cl - xi) * (2.0 * cl - xi) / (9.0 * g), 1e-13);
      assert_abs(u, 2.0 / 3.0 * (xi + cl), 1e-13 * cl);
    } else {
      assert_abs(h, 0.0, 0.0);
    }
  }
}

/* Stoker (1957): wet-bed dam break, h_L > h_R, both at rest. Independent computation: the shock
 * speed S solves u_m(S) from the shock = u_m from the rarefaction, with
 *   h_m = h_R/2 (sqrt(1 + 8 S²/(g h_R)) − 1),  u_m = S (1 − h_R/h_m),  u_m + 2 c_m = 2 c_L. */
struct stoker {
  double g, hl, hr;
};

static double stoker_hm(const struct stoker *p, double s) {
  return 0.5 * p->hr * (sqrt(1.0 + 8.0 * s * s / (p->g * p->hr)) - 1.0);
}

static double stoker_residual(double s, void *params) {
  const struct stoker *p = params;
  double hm = stoker_hm(p, s);
  return s * (1.0 - p->hr / hm) + 2.0 * sqrt(p->g * hm) - 2.0 * sqrt(p->g * p->hl);
}

static void test_stoker(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  const double ratios[] = {0.05, 0.1, 0.3, 0.7};
  for (size_t k = 0; k < 4; ++k) {
    struct stoker p = {9.81, 1.0, ratios[k]};
    gsl_function fn = {stoker_residual, &p};
    gsl_root_fsolver *solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    /* S lies between sqrt(g h_R) (weak shock) and 2 sqrt(g h_L) */
    gsl_root_fsolver_set(solver, &fn, sqrt(p.g * p.hr) * (1.0 + 1e-12), 2.0 * sqrt(p.g * p.hl));
    int status = GSL_CONTINUE;
    for (int it = 0; it < 200 && status == GSL_CONTINUE; ++it) {
      gsl_root_fsolver_iterate(solver);
      status = gsl_root_test_interval(gsl_root_fsolver_x_lower(solver),
                                      gsl_root_fsolver_x_upper(solver), 0.0, 1e-15);
    }
    assert_int_equal(status, GSL_SUCCESS);
    const double shock = gsl_root_fsolver_root(solver);
    gsl_root_fsolver_free(solver);
    const double hm = stoker_hm(&p, shock), um = shock * (1.0 - p.hr / hm);
    const double cl = sqrt(p.g * p.hl), cm = sqrt(p.g * hm);

    struct rmn_eos e = shallow_water(p.g);
    struct rmn_exact s;
    assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, p.hl, 0.0, p.hr, 0.0, &s), RMN_SUCCESS);
    assert_false(s.vacuum);
    assert_int_equal(s.left, RMN_EXACT_RAREFACTION);
    assert_int_equal(s.right, RMN_EXACT_SHOCK);
    assert_rel(s.rho_star, hm, 1e-12);
    assert_rel(s.u_star, um, 1e-12);
    assert_rel(s.right_head, shock, 1e-12);
    assert_rel(s.left_tail, um - cm, 1e-12);
    for (double xi = -1.5 * cl; xi <= 1.5 * shock; xi += 0.0093 * cl) {
      double h, u, h_ref, u_ref;
      if (xi <= -cl) {
        h_ref = p.hl, u_ref = 0.0;
      } else if (xi <= um - cm) {
        h_ref = (2.0 * cl - xi) * (2.0 * cl - xi) / (9.0 * p.g);
        u_ref = 2.0 / 3.0 * (xi + cl);
      } else if (xi < shock) {
        h_ref = hm, u_ref = um;
      } else {
        h_ref = p.hr, u_ref = 0.0;
      }
      if (fabs(xi - shock) < 1e-9 * cl) continue; /* exactly on the jump */
      rmn_exact_sample(&s, xi, &h, &u);
      assert_rel(h, h_ref, 1e-11);
      assert_abs(u, u_ref, 1e-11 * cl);
    }
  }
}

static double random_state(struct sabre_rng *rng, const struct rmn_eos *e, double *u) {
  double rho = e->rho0 * sabre_rng_uniform(rng, 0.3, 2.0);
  *u = e->c0 * sabre_rng_uniform(rng, -1.5, 1.5);
  return rho;
}

/* Every wave of random problems: RH across shocks (and Lax), invariants across fans, f(ρ*) = 0,
 * continuity of the sampled solution at fan edges, mirror symmetry. */
static void test_random_problems(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 31);
  const double xis[] = {1.0, 2.0, 7.0, 1.4};
  int n_vacuum = 0, n_shock = 0, n_raref = 0;
  for (size_t k = 0; k < 4; ++k) {
    struct rmn_eos e;
    rmn_eos_init(&e, 1000.0, 20.0, xis[k]);
    for (int i = 0; i < 2000; ++i) {
      double ul, ur;
      double rl = random_state(&rng, &e, &ul), rr = random_state(&rng, &e, &ur);
      struct rmn_exact s, m;
      assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, rl, ul, rr, ur, &s), RMN_SUCCESS);
      /* mirror: (ρ_R, −u_R | ρ_L, −u_L) sampled at −x/t is (ρ, −u) at x/t */
      assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, rr, -ur, rl, -ul, &m), RMN_SUCCESS);
      assert_int_equal(s.vacuum, m.vacuum);
      if (s.vacuum) {
        ++n_vacuum;
        assert_true(e.xi > 1.0);
        assert_true(ur - ul >= rmn_eos_psi(&e, rl) + rmn_eos_psi(&e, rr));
      } else {
        assert_abs(rmn_exact_star_function(&e, s.rho_star, rl, ul, rr, ur) / e.c0, 0.0, 1e-13);
        assert_rel(m.rho_star, s.rho_star, 1e-12);
        assert_abs(m.u_star, -s.u_star, 1e-12 * e.c0);
        assert_int_equal(m.left, s.right);
        assert_int_equal(m.right, s.left);
        const double side_rho[2] = {rl, rr}, side_u[2] = {ul, ur};
        const enum rmn_exact_wave wave[2] = {s.left, s.right};
        const double speed[2] = {s.left_head, s.right_head};
        for (int side = 0; side < 2; ++side) {
          double c_k = rmn_eos_sound_speed(&e, side_rho[side]);
          double c_s = rmn_eos_sound_speed(&e, s.rho_star);
          if (wave[side] == RMN_EXACT_SHOCK) {
            ++n_shock;
            double res[2];
            /* residuals of the moving shock between the star state and the data */
            rmn_shock_residuals(&e, side_rho[side], side_u[side], s.rho_star, s.u_star, speed[side],
                                res);
            double scale = side_rho[side] * (e.c0 + fabs(side_u[side]));
            assert_abs(res[0] / scale, 0.0, 1e-10);
            assert_abs(res[1] / (scale * (e.c0 + fabs(side_u[side]))), 0.0, 1e-10);
            /* Lax: characteristics converge into the shock */
            if (side == 0) {
              assert_true(s.u_star - c_s < speed[0] + 1e-12 * e.c0);
              assert_true(speed[0] < side_u[0] - c_k + 1e-12 * e.c0);
            } else {
              assert_true(s.u_star + c_s > speed[1] - 1e-12 * e.c0);
              assert_true(speed[1] > side_u[1] + c_k - 1e-12 * e.c0);
            }
          } else {
            ++n_raref;
            if (side == 0)
              assert_abs(rmn_invariant_minus(&e, s.rho_star, s.u_star),
                         rmn_invariant_minus(&e, rl, ul), 1e-12 * e.c0);
            else
              assert_abs(rmn_invariant_plus(&e, s.rho_star, s.u_star),
                         rmn_invariant_plus(&e, rr, ur), 1e-12 * e.c0);
          }
        }
      }
      /* sampled profile: mirror symmetric and continuous at fan edges */
      for (int j = 0; j < 20; ++j) {
        double xi = e.c0 * sabre_rng_uniform(&rng, -4, 4), r1, u1, r2, u2;
        rmn_exact_sample(&s, xi, &r1, &u1);
        rmn_exact_sample(&m, -xi, &r2, &u2);
        if (fabs(xi - s.left_head) < 1e-9 * e.c0 || fabs(xi - s.right_head) < 1e-9 * e.c0) continue;
        assert_rel(r2, r1, 1e-11);
        if (r1 > 0.0) assert_abs(u2, -u1, 1e-11 * e.c0);
      }
      if (!s.vacuum && s.left == RMN_EXACT_RAREFACTION && s.left_tail > s.left_head) {
        double r_in, u_in;
        rmn_exact_sample(&s, s.left_head + 1e-9 * e.c0, &r_in, &u_in);
        assert_rel(r_in, rl, 1e-7);
        rmn_exact_sample(&s, s.left_tail - 1e-9 * e.c0, &r_in, &u_in);
        assert_rel(r_in, s.rho_star, 1e-7);
      }
    }
  }
  /* the random set exercised every branch */
  assert_true(n_vacuum > 0 && n_shock > 0 && n_raref > 0);
}

/* Dry states: a fan into vacuum with its front at u ∓ ψ (ξ > 1) or reaching infinity (ξ = 1). */
static void test_dry_states(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_on();
  struct rmn_eos e;
  rmn_eos_init(&e, 1000.0, 20.0, 7.0);
  struct rmn_exact s;
  assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, 0.0, 0.0, 1000.0, 1.0, &s), RMN_SUCCESS);
  assert_true(s.vacuum);
  assert_rel(s.right_tail, 1.0 - rmn_eos_psi(&e, 1000.0), 1e-15);
  double r, u;
  rmn_exact_sample(&s, s.right_tail - 1.0, &r, &u);
  assert_abs(r, 0.0, 0.0);
  rmn_exact_sample(&s, 0.5 * (s.right_tail + s.right_head), &r, &u);
  assert_true(r > 0.0 && r < 1000.0);
  assert_abs(rmn_invariant_plus(&e, r, u), rmn_invariant_plus(&e, 1000.0, 1.0), 1e-12);
  /* isothermal: the fan has no front; density decays exponentially with R+1 conserved */
  rmn_eos_init(&e, 1.0, 1.0, 1.0);
  assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, 2.0, 0.5, 0.0, 0.0, &s), RMN_SUCCESS);
  assert_true(isinf(s.left_tail));
  for (double xi = 0.0; xi < 30.0; xi += 2.5) {
    rmn_exact_sample(&s, xi, &r, &u);
    assert_true(r > 0.0);
    assert_abs(u - xi, 1.0, 1e-13); /* u − c = ξ with c = c0 = 1 */
    assert_abs(rmn_invariant_minus(&e, r, u), rmn_invariant_minus(&e, 2.0, 0.5), 1e-12);
  }
}

static void test_errors(void **state) {
  struct fixture *f = *state;
  sabre_fp_traps_off();
  struct rmn_eos e;
  rmn_eos_init(&e, 1000.0, 20.0, 7.0);
  struct rmn_exact s;
  assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, 0.0, 0.0, 0.0, 0.0, &s), RMN_EINVAL);
  assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, -1.0, 0.0, 1.0, 0.0, &s), RMN_EINVAL);
  assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, 1.0, NAN, 1.0, 0.0, &s), RMN_EINVAL);
  assert_int_equal(rmn_exact_solve(&e, &f->par, f->ws, 1.0, 0.0, INFINITY, 0.0, &s), RMN_EINVAL);
  /* a shock needs the workspace; two rarefactions do not */
  assert_int_equal(rmn_exact_solve(&e, &f->par, NULL, 1000.0, 1.0, 1000.0, -1.0, &s), RMN_EINVAL);
  assert_int_equal(rmn_exact_solve(&e, &f->par, NULL, 1000.0, -1.0, 1000.0, 1.0, &s), RMN_SUCCESS);
  struct rmn_params bad = f->par;
  bad.max_iter = 2;
  assert_int_equal(rmn_exact_solve(&e, &bad, f->ws, 1000.0, 5.0, 1100.0, -5.0, &s), RMN_ENOCONV);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_ritter),          cmocka_unit_test(test_stoker),
      cmocka_unit_test(test_random_problems), cmocka_unit_test(test_dry_states),
      cmocka_unit_test(test_errors),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
