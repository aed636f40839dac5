/*
 * Imposed volume flux through the solver (M §5, docs/sph-robin.md §4–5): a small periodic channel
 * (10 rows, first row Δr from the walls), started at rest and driven only by the controller.
 * - M(63): the measured bulk velocity ṽ, M(56–57), reaches the target to 2e-6 relative and the
 *   driving acceleration reaches the one of plane Poiseuille flow, 12 ν v/H², within the SPH
 *   error of the profile (a few %);
 * - M(58): ṽ settles below the target (the internal force is ignored), by about 2kΔt with
 *   k = 12ν/H² (docs/sph-robin.md §4.3);
 * - off: no force at all; the measurement equals a direct slice sum.
 */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>

#include "solver_fixture.h"
#include "testutil.h"

static const double DR = 0.01, NU = 0.01, V = 0.1;

/* Run the channel for t_end with the given method: the last measured ṽ, the last driving
 * acceleration and step, the largest velocity error against Poiseuille (relative to u_max). */
static void channel(int method, double t_end, double *vt, double *force, double *dt,
                    double *profile_err) {
  struct sph_system s;
  fixture_lattice_offset(&s, 10, 10, DR, 2.0, FIX_CHANNEL, 1.0);
  const double H = s.domain.hi[1];
  struct sph_config cfg;
  fixture_config(&cfg);
  cfg.nu = NU;
  cfg.c0 = 15 * V;
  cfg.flux_method = method;
  cfg.flux_velocity = V;
  cfg.flux_normal[0] = 1.0;
  cfg.flux_point[0] = 0.0537;
  cfg.flux_width = 2 * DR;
  cfg.flux_area = H;
  struct sph_solver sv;
  sph_solver_init(&sv, &cfg, &s, NULL, NULL);
  sph_system_free(&s);
  char msg[512];
  while (sv.time < t_end) assert_int_equal(sph_solver_step(&sv, INFINITY, msg, sizeof msg), 0);
  *vt = sph_solver_flux_measure(&sv);
  *force = sv.flux_force;
  *dt = sv.dt;
  /* against the Poiseuille profile of bulk velocity V: u = 6 V y (H − y)/H² */
  const struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
  double err = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    const double y = f->x[1][a];
    err = fmax(err, fabs(f->v[0][a] - 6 * V * y * (H - y) / (H * H)) / (1.5 * V));
  }
  *profile_err = err;
  /* the slice measurement by hand: V_b v_b over the particles in the slice / (width · area) */
  double sum = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    const double d = f->x[0][a] - cfg.flux_point[0]; /* slice inside the period: no wrap */
    if (d >= -DR && d < DR) sum += f->mass[a] / f->rho[a] * f->v[0][a];
  }
  assert_rel(*vt, sum / (2 * DR * H), 1e-13);
  sph_solver_free(&sv);
}

static void test_flux(void **state) {
  (void)state;
  sabre_fp_traps_on();
  const double H = 0.11, t_end = 0.3 * H * H / NU, f_exact = 12 * NU * V / (H * H);
  double vt63, f63, dt63, e63, vt58, f58, dt58, e58, vt0, f0, dt0, e0;
  channel(SPH_FLUXSEL_M63, t_end, &vt63, &f63, &dt63, &e63);
  channel(SPH_FLUXSEL_M58, t_end, &vt58, &f58, &dt58, &e58);
  channel(SPH_FLUXSEL_OFF, 0.01, &vt0, &f0, &dt0, &e0);
  const double k = 12 * NU / (H * H);
  print_message("M(63): |v~ - v|/v = %.2e, F/F_exact = %.4f, profile error %.2e u_max\n",
                fabs(vt63 / V - 1), f63 / f_exact, e63);
  print_message("M(58): v~/v - 1 = %.3e (toy model -2k dt/(1 + 2k dt) = %.3e), F/F_exact = %.4f\n",
                vt58 / V - 1, -2 * k * dt58 / (1 + 2 * k * dt58), f58 / f_exact);
  assert_true(fabs(vt63 / V - 1) < 2e-6);
  assert_rel(f63, f_exact, 0.05);
  assert_true(e63 < 0.03);
  assert_true(vt58 < V && fabs(vt58 / V - 1) > 1e3 * fabs(vt63 / V - 1));
  assert_rel(vt58 / V - 1, -2 * k * dt58 / (1 + 2 * k * dt58), 0.3);
  assert_true(vt0 == 0.0 && f0 == 0.0);
}

int main(void) {
  gsl_set_error_handler_off();
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_flux)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
