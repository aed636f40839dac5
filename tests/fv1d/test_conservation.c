/* Conservation to round-off: with periodic ends mass and momentum are constant; with walls mass
 * is constant and momentum changes exactly by the wall pressure impulse; with open ends both change
 * exactly by the time-integrated end fluxes. Every flux and every reconstruction, random data. */
#include <gsl/gsl_errno.h>
#include <stdlib.h>

#include "helpers.h"

enum { N = 48 };

/* Random smooth-plus-noise state, high-entropy values, seeded. */
static void random_state(struct fv1d_solver *s, uint64_t seed, double rho0, double c0) {
  struct sabre_rng rng;
  sabre_rng_seed(&rng, seed);
  double *y = fv1d_solver_state(s);
  for (long i = 0; i < fv1d_solver_cells(s); ++i) {
    double x = fv1d_solver_x(s, i);
    double rho =
        rho0 * (1.0 + 0.02 * sin(6.283185307179586 * x) + sabre_rng_uniform(&rng, -0.01, 0.01));
    double u = c0 * (0.03 * cos(6.283185307179586 * x) + sabre_rng_uniform(&rng, -0.02, 0.02));
    y[2 * i] = rho, y[2 * i + 1] = rho * u;
  }
}

static void check_balance(enum fv1d_bc_type left, enum fv1d_bc_type right) {
  const double rho0 = 998.2, c0 = 23.7;
  for (int f = 0; f < 3; ++f) {
    for (int r = 0; r < 3; ++r) {
      struct fv1d_params p;
      th_params(&p, -0.37, 0.63, N, rho0, c0, 7.0);
      p.flux = (enum fv1d_flux)f;
      p.recon = (enum fv1d_recon)r;
      p.bc[0].type = left, p.bc[1].type = right;
      if (left == FV1D_BC_OPEN) { /* imposed pressure, time dependent */
        p.bc[0].imposed = RMN_IMPOSE_PRESSURE;
        p.bc[0].signal.kind = FV1D_SIGNAL_SINUSOID;
        p.bc[0].signal.value = 350.0, p.bc[0].signal.amplitude = 420.0;
        p.bc[0].signal.frequency = 37.0;
      }
      if (right == FV1D_BC_OPEN) { /* imposed velocity */
        p.bc[1].imposed = RMN_IMPOSE_VELOCITY;
        p.bc[1].signal.kind = FV1D_SIGNAL_RAMP;
        p.bc[1].signal.start = 0.0, p.bc[1].signal.value = 0.41, p.bc[1].signal.duration = 0.01;
      }
      double t_end = 0.0173;
      p.t_end = t_end, p.output_times = &t_end, p.noutput = 1;
      struct fv1d_solver *s = fv1d_solver_create(&p);
      random_state(s, 1234u + 17u * (unsigned)(3 * f + r), rho0, c0);
      double tot0[3], tot1[3];
      double *y = fv1d_solver_state(s);
      fv1d_totals(s, y, tot0);
      struct fv1d_stats stats;
      th_run(s, &p, t_end, &stats);
      assert_true(stats.steps > 30);
      fv1d_totals(s, y, tot1);
      const double *q = y + 2 * N; /* ∫F_left dt (mass, momentum, energy), ∫F_right dt */
      double mass_scale = tot0[0], mom_scale = tot0[0] * c0;
      if (left == FV1D_BC_PERIODIC) {
        assert_abs(tot1[0], tot0[0], 4e-15 * mass_scale);
        assert_abs(tot1[1], tot0[1], 4e-15 * mom_scale);
      }
      if (left == FV1D_BC_WALL && right == FV1D_BC_WALL) {
        assert_abs(tot1[0], tot0[0], 4e-15 * mass_scale);
        assert_true(q[0] == 0.0 && q[3] == 0.0);
      }
      /* every case: the change equals what entered minus what left */
      assert_abs(tot1[0] - tot0[0], q[0] - q[3], 4e-15 * mass_scale);
      assert_abs(tot1[1] - tot0[1], q[1] - q[4], 4e-15 * mom_scale);
      /* closed domains: energy is dissipated, never created */
      if (left != FV1D_BC_OPEN && left != FV1D_BC_TRANSMISSIVE) assert_true(tot1[2] <= tot0[2]);
      fv1d_solver_destroy(s);
    }
  }
}

static void test_periodic(void **state) {
  (void)state;
  check_balance(FV1D_BC_PERIODIC, FV1D_BC_PERIODIC);
}
static void test_walls(void **state) {
  (void)state;
  check_balance(FV1D_BC_WALL, FV1D_BC_WALL);
}
static void test_open_and_transmissive(void **state) {
  (void)state;
  check_balance(FV1D_BC_OPEN, FV1D_BC_OPEN);
  check_balance(FV1D_BC_TRANSMISSIVE, FV1D_BC_WALL);
}

/* A symmetric state between two walls keeps zero momentum and mirror symmetry. */
static void test_wall_symmetry(void **state) {
  (void)state;
  struct fv1d_params p;
  th_params(&p, -0.5, 0.5, 40, 1000.0, 20.0, 7.0);
  p.bc[0].type = p.bc[1].type = FV1D_BC_WALL;
  p.recon = FV1D_RECON_MC;
  struct fv1d_region reg = {-0.1, 0.1, 1012.3, 0.0};
  p.initial.regions = &reg, p.initial.nregions = 1;
  double t_end = 0.04;
  p.t_end = t_end, p.output_times = &t_end, p.noutput = 1;
  struct fv1d_solver *s = fv1d_solver_create(&p);
  struct fv1d_stats stats;
  th_run(s, &p, t_end, &stats);
  const double *y = fv1d_solver_state(s);
  for (long i = 0; i < 20; ++i) {
    assert_rel(y[2 * i], y[2 * (39 - i)], 1e-13);
    assert_abs(y[2 * i + 1], -y[2 * (39 - i) + 1], 1e-10 * 1000.0 * 20.0);
  }
  fv1d_solver_destroy(s);
}

int main(void) {
  gsl_set_error_handler_off();
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_periodic),
      cmocka_unit_test(test_walls),
      cmocka_unit_test(test_open_and_transmissive),
      cmocka_unit_test(test_wall_symmetry),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
