/* Open ends: the face state is the riemann/ boundary solution for the adjacent cell state and the
 * imposed quantity at the stage time, and the face flux is F(U_s). Also: imposed signals, and the
 * wall face (zero mass flux, exact-solver pressure). */
#include <gsl/gsl_errno.h>
#include <stdlib.h>

#include "helpers.h"

enum { N = 12 };

static struct rmn_workspace *ws;

static int setup(void **state) {
  (void)state;
  ws = rmn_workspace_alloc();
  return ws ? 0 : -1;
}
static int teardown(void **state) {
  (void)state;
  rmn_workspace_free(ws);
  return 0;
}

/* Build a solver with open ends, set a state, evaluate the RHS at t and compare each end with a
 * direct call of rmn_boundary_solve_normal. */
static void check_open(enum rmn_imposed imposed_l, double value_l, enum rmn_imposed imposed_r,
                       double value_r, double rho_first, double u_first, double rho_last,
                       double u_last, int expect_wave_l, int expect_wave_r) {
  struct fv1d_params p;
  th_params(&p, 0.0, 1.2, N, 1000.0, 20.0, 7.0);
  p.recon = FV1D_RECON_NONE;
  p.flux = FV1D_FLUX_HLL;
  p.bc[0].type = p.bc[1].type = FV1D_BC_OPEN;
  p.bc[0].imposed = imposed_l;
  p.bc[1].imposed = imposed_r;
  /* time dependent: the value is reached at the evaluation time t = 0.37 s exactly */
  p.bc[0].signal.kind = FV1D_SIGNAL_SINUSOID;
  p.bc[0].signal.value = value_l, p.bc[0].signal.amplitude = 3.1, p.bc[0].signal.frequency = 2.5;
  p.bc[0].signal.phase = -FV1D_TEST_TWO_PI * 2.5 * 0.37; /* sin(0) at t = 0.37 */
  p.bc[1].signal.kind = FV1D_SIGNAL_RAMP;
  p.bc[1].signal.start = 0.0, p.bc[1].signal.value = value_r;
  p.bc[1].signal.t_start = 0.1, p.bc[1].signal.duration = 0.2;
  const double t = 0.37;
  struct fv1d_solver *s = fv1d_solver_create(&p);
  double *y = fv1d_solver_state(s);
  for (long i = 0; i < N; ++i) {
    double w = (double)i / (N - 1);
    double rho = rho_first + w * (rho_last - rho_first), u = u_first + w * (u_last - u_first);
    y[2 * i] = rho, y[2 * i + 1] = rho * u;
  }
  double *ydot = calloc((size_t)fv1d_solver_state_length(s), sizeof(double));
  assert_int_equal(fv1d_rhs_eval(s, t, y, ydot), 0);

  const struct rmn_eos *eos = &p.eos;
  const double dx = fv1d_solver_dx(s);
  for (int side = 0; side < 2; ++side) {
    const double normal = side == 0 ? 1.0 : -1.0;
    const long cell = side == 0 ? 0 : N - 1;
    const double rho_int = y[2 * cell], u_int = y[2 * cell + 1] / rho_int;
    enum rmn_imposed imposed = side == 0 ? imposed_l : imposed_r;
    double value = side == 0 ? value_l : value_r;
    if (imposed == RMN_IMPOSE_VELOCITY) value *= normal;
    struct rmn_normal_state ref;
    assert_int_equal(
        rmn_boundary_solve_normal(eos, &p.rmn, ws, rho_int, normal * u_int, imposed, value, &ref),
        RMN_SUCCESS);
    assert_int_equal(ref.wave, side == 0 ? expect_wave_l : expect_wave_r);
    const struct fv1d_boundary_state *b = fv1d_solver_boundary(s, side);
    assert_rel(b->segment.rho, ref.rho, 1e-15);
    assert_abs(b->segment.un, ref.un, 1e-15 * 20.0);
    assert_rel(b->rho, ref.rho, 1e-15);
    assert_abs(b->u, normal * ref.un, 1e-15 * 20.0);
    assert_abs(b->p, ref.p, 1e-15 * fabs(rmn_eos_min_pressure(eos)));
    if (imposed == RMN_IMPOSE_PRESSURE)
      assert_abs(ref.p, value, 1e-9 * fabs(value) + 1e-9);
    else
      assert_abs(normal * ref.un, normal * value, 1e-14);
    /* face flux F(U_s) and the cell update it feeds */
    double fs[2] = {ref.rho * normal * ref.un, ref.rho * ref.un * ref.un + ref.p};
    assert_abs(b->flux[0], fs[0], 1e-14 * 1000.0 * 20.0);
    assert_abs(b->flux[1], fs[1], 1e-14 * 1000.0 * 400.0);
    double fi[2];
    long other = side == 0 ? 1 : N - 2;
    const double *a = side == 0 ? y : y + 2 * other, *c = side == 0 ? y + 2 * other : y + 2 * cell;
    assert_int_equal(
        fv1d_flux_numerical(p.flux, eos, &p.rmn, ws, a[0], a[1] / a[0], c[0], c[1] / c[0], fi),
        RMN_SUCCESS);
    for (int k = 0; k < 2; ++k) {
      double expected = side == 0 ? (fs[k] - fi[k]) / dx : (fi[k] - fs[k]) / dx;
      assert_abs(ydot[2 * cell + k], expected, 1e-12 * (k == 0 ? 1000.0 * 20.0 : 4e5) / dx);
    }
  }
  free(ydot);
  fv1d_solver_destroy(s);
}

static void test_open_pressure(void **state) {
  (void)state;
  /* p above the interior pressure at the left (shock), below at the right (expansion) */
  check_open(RMN_IMPOSE_PRESSURE, 2345.6, RMN_IMPOSE_PRESSURE, -1234.5, 1000.0, 0.31, 1000.0, 0.27,
             RMN_WAVE_SHOCK, RMN_WAVE_EXPANSION);
}

static void test_open_velocity(void **state) {
  (void)state;
  /* left: inflow 0.93 m/s into a cell moving at 0.2 (compression: shock); right: outflow along
   * +x faster than the cell (expansion) */
  check_open(RMN_IMPOSE_VELOCITY, 0.93, RMN_IMPOSE_VELOCITY, 0.71, 1003.1, 0.2, 1001.7, 0.35,
             RMN_WAVE_SHOCK, RMN_WAVE_EXPANSION);
}

static void test_open_mixed(void **state) {
  (void)state;
  check_open(RMN_IMPOSE_VELOCITY, -0.12, RMN_IMPOSE_PRESSURE, 812.0, 999.2, 0.05, 1000.4, -0.08,
             RMN_WAVE_EXPANSION, RMN_WAVE_SHOCK);
}

static void test_signals(void **state) {
  (void)state;
  struct fv1d_signal sig = {0};
  sig.kind = FV1D_SIGNAL_CONSTANT, sig.value = 3.7;
  assert_true(fv1d_signal_eval(&sig, 12.0) == 3.7);
  sig.kind = FV1D_SIGNAL_SINUSOID, sig.value = 1.5, sig.amplitude = 2.0, sig.frequency = 0.25;
  sig.phase = 0.0;
  assert_rel(fv1d_signal_eval(&sig, 1.0), 3.5, 1e-15); /* sin(π/2) */
  sig.kind = FV1D_SIGNAL_RAMP, sig.start = -1.0, sig.value = 3.0, sig.t_start = 2.0;
  sig.duration = 4.0;
  assert_true(fv1d_signal_eval(&sig, 1.0) == -1.0);
  assert_abs(fv1d_signal_eval(&sig, 3.0), 0.0, 1e-15);
  assert_true(fv1d_signal_eval(&sig, 7.0) == 3.0);
  sig.duration = 0.0; /* a step */
  assert_true(fv1d_signal_eval(&sig, 1.999) == -1.0 && fv1d_signal_eval(&sig, 2.001) == 3.0);
  double tt[3] = {0.0, 1.0, 3.0}, vv[3] = {2.0, 4.0, 0.0};
  sig.kind = FV1D_SIGNAL_TABLE, sig.ntable = 3, sig.table_t = tt, sig.table_v = vv;
  assert_true(fv1d_signal_eval(&sig, -1.0) == 2.0);
  assert_abs(fv1d_signal_eval(&sig, 0.25), 2.5, 1e-15);
  assert_abs(fv1d_signal_eval(&sig, 2.5), 1.0, 1e-15);
  assert_true(fv1d_signal_eval(&sig, 9.0) == 0.0);
}

/* Wall faces: no mass flux, and (Godunov) the momentum flux is the exact solver's star pressure
 * of the mirrored problem. */
static void test_wall_face(void **state) {
  (void)state;
  struct fv1d_params p;
  th_params(&p, 0.0, 1.0, N, 1000.0, 20.0, 7.0);
  p.recon = FV1D_RECON_NONE;
  p.bc[0].type = p.bc[1].type = FV1D_BC_WALL;
  struct fv1d_solver *s = fv1d_solver_create(&p);
  double *y = fv1d_solver_state(s);
  for (long i = 0; i < N; ++i) y[2 * i] = 1002.5, y[2 * i + 1] = 1002.5 * (i == 0 ? -0.4 : 0.3);
  double *ydot = calloc((size_t)fv1d_solver_state_length(s), sizeof(double));
  assert_int_equal(fv1d_rhs_eval(s, 0.0, y, ydot), 0);
  struct rmn_exact ex;
  /* left wall, cell moving into it at −0.4 m/s: mirror (ρ, +0.4) | (ρ, −0.4) */
  assert_int_equal(rmn_exact_solve(&p.eos, &p.rmn, ws, 1002.5, 0.4, 1002.5, -0.4, &ex), 0);
  assert_true(fv1d_solver_boundary(s, 0)->flux[0] == 0.0);
  assert_rel(fv1d_solver_boundary(s, 0)->flux[1], ex.p_star, 1e-12);
  /* right wall, cell moving away at +0.3 m/s: an expansion */
  assert_int_equal(rmn_exact_solve(&p.eos, &p.rmn, ws, 1002.5, 0.3, 1002.5, -0.3, &ex), 0);
  assert_true(fv1d_solver_boundary(s, 1)->flux[0] == 0.0);
  assert_rel(fv1d_solver_boundary(s, 1)->flux[1], ex.p_star, 1e-12);
  free(ydot);
  fv1d_solver_destroy(s);
}

int main(void) {
  gsl_set_error_handler_off();
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_open_pressure), cmocka_unit_test(test_open_velocity),
      cmocka_unit_test(test_open_mixed),    cmocka_unit_test(test_signals),
      cmocka_unit_test(test_wall_face),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
