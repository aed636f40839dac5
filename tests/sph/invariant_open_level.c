/*
 * A through-flow at a pressure level holds (docs/sph-solver.md §10, "The pressure level with
 * M(37)"): the smallest case of the open boundaries' pressure-level defect, a 2D channel
 * 1 m × 0.22 m full of fluid between two walls, no gravity, inviscid, Δr = 0.02 m, h = 2Δr,
 * c0 = 14 m/s, 300 repacking steps, a velocity inlet at 0.5 m/s and an outlet at 1 kPa
 * (p/B = 0.036), with M(37). Before the inflow vertices' layer and the outflow vertices' phase
 * rule its mean speed was 2.4 % low at 2.5 s and it stopped at 3.0 s (the fluid next to the outlet
 * stalled); asserted here to 5 s, every 0.25 s from 1.5 s on (measured: 1.2 %, 0.052 m/s, 6.5 %,
 * 3.7 %, 0.13 %): the mean speed within 2 % of 0.5 m/s, every particle within 0.08 m/s of
 * (0.5, 0), the mean pressure within 8 % of the level and its mean over the samples within 6 %
 * (the channel rings acoustically between a velocity inlet and a pressure outlet, both
 * reflecting: ±3 % about a level 3–4 % above the outlet's), the mass in the channel (fluid and
 * vertices) within 0.5 % of its start. Measured figures are printed.
 */
#include <math.h>
#include <stdio.h>

#include "solver_fixture.h"
#include "testutil.h"

static const char channel[] =
    "geometry:\n"
    "  dimension: 2\n"
    "  dr: 0.02\n"
    "  h_over_dr: 2\n"
    "  first_row: 1\n"
    "  walls:\n"
    "    - {type: box, lo: [0, 0], hi: [1, 0.22], open: [x-, x+]}\n"
    "  fluid:\n"
    "    - {type: box, lo: [0, 0], hi: [1, 0.22]}\n"
    "fluid: {rho0: 1000, c0: 14}\n"
    "initial: {pressure: 1000, velocity: [0.5, 0]}\n"
    "repack: {steps: 300}\n"
    "open_boundaries:\n"
    "  - {name: inlet, wall: 0, faces: [x-], impose: velocity, normal_velocity: 0.5}\n"
    "  - {name: outlet, wall: 0, faces: [x+], impose: pressure, pressure: 1000}\n"
    "time: {end: 5}\n";

static double total_mass(const struct sph_solver *sv) {
  double m = 0.0;
  for (int k = SPH_KIND_FLUID; k <= SPH_KIND_VERTEX; k++)
    for (size_t i = 0; i < sv->sys.part[k].n; i++) m += sv->sys.part[k].mass[i];
  return m;
}

static void test_channel_at_level(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_solver *sv = fixture_solver_from_case(channel);
  const double m0 = total_mass(sv);
  char msg[1024];
  double worst_u = 0.0, worst_dev = 0.0, worst_p = 0.0, worst_m = 0.0, p_sum = 0.0;
  int n_p = 0;
  print_message("2D channel, 0.5 m/s through a velocity inlet and an outlet at 1 kPa:\n");
  for (int k = 1; k <= 20; k++) {
    const double t = 0.25 * k;
    while (sv->time < t - 1e-12)
      if (sph_solver_step(sv, t - sv->time, msg, sizeof msg) != 0) fail_msg("%s", msg);
    const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
    double u = 0.0, p = 0.0, dev = 0.0;
    for (size_t a = 0; a < f->n; a++) {
      u += f->v[0][a];
      p += f->p[a];
      dev = fmax(dev, hypot(f->v[0][a] - 0.5, f->v[1][a]));
    }
    u /= (double)f->n;
    p /= (double)f->n;
    const double dm = fabs(total_mass(sv) / m0 - 1.0);
    print_message(
        "  t = %.1f s: %zu particles, mean u %.4f m/s, max |u - U| %.3f m/s, mean p "
        "%.1f Pa, mass %+.2e\n",
        sv->time, f->n, u, dev, p, total_mass(sv) / m0 - 1.0);
    if (t < 1.5) continue; /* the start-up: the inlet's first rows */
    worst_u = fmax(worst_u, fabs(u / 0.5 - 1.0));
    worst_dev = fmax(worst_dev, dev);
    worst_p = fmax(worst_p, fabs(p / 1000.0 - 1.0));
    worst_m = fmax(worst_m, dm);
    p_sum += p;
    n_p++;
  }
  const double p_mean = p_sum / n_p;
  print_message(
      "from 1.5 s: mean u within %.3g, max |u - U| %.3g m/s, mean p within %.3g of the "
      "level (its mean %.1f Pa), mass within %.2e\n",
      worst_u, worst_dev, worst_p, p_mean, worst_m);
  assert_true(worst_u <= 0.02);
  assert_true(worst_dev <= 0.08);
  assert_true(worst_p <= 0.08);
  assert_true(fabs(p_mean / 1000.0 - 1.0) <= 0.06);
  assert_true(worst_m <= 0.005);
  fixture_solver_destroy(sv);
}

int main(void) {
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_channel_at_level)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
