/*
 * numerics.artificial_viscosity and the repacking's independence of velocity-dependent terms
 * (docs/sph-solver.md §4 and §8):
 *   - α is the laminar viscosity ν_α = α h c0 / (2(d + 2)) added to fluid.nu: a run with α and
 *     one with that ν are the same, bit for bit;
 *   - the repacking ends where it ends whatever the viscosity and the wall impedance (its
 *     pseudo-velocities must not feel them), bit for bit;
 *   - repack.perturbation: the perturbed start is the same on every run (a seeded draw), the
 *     repacking still converges from it, it is part of the repacking (no steps, no draw), and
 *     the particles the repacking holds at a free surface are not perturbed.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_solver.h"
#include "solver_fixture.h"
#include "testutil.h"

/* A closed 2D box 0.5 m × 0.4 m, Δr = 0.025 m, h = 2Δr, a shear flow u = 0.1 sin(2π y/0.4) m/s
 * at uniform pressure: the viscous term acts from the first step. */
#define SHEAR_CASE                                                                 \
  "geometry:\n"                                                                    \
  "  dimension: 2\n"                                                               \
  "  dr: 0.025\n"                                                                  \
  "  h_over_dr: 2\n"                                                               \
  "  first_row: 1\n"                                                               \
  "  walls: [{type: box, lo: [0, 0], hi: [0.5, 0.4]}]\n"                           \
  "  fluid: [{type: box, lo: [0, 0], hi: [0.5, 0.4]}]\n"                           \
  "fluid: {rho0: 1000, c0: 20%s}\n"                                                \
  "initial: {pressure: 1000, velocity: ['0.1*sin(6.283185307179586*y/0.4)', 0]}\n" \
  "numerics: {vertex_volume: geometric%s}\n"                                       \
  "time: {end: 1}\n"                                                               \
  "%s"

static struct sph_solver *shear_solver(const char *fluid_extra, const char *numerics_extra,
                                       const char *more) {
  char text[2048];
  snprintf(text, sizeof text, SHEAR_CASE, fluid_extra, numerics_extra, more);
  return fixture_solver_from_case(text);
}

static void step_n(struct sph_solver *sv, int n) {
  char msg[1024];
  for (int i = 0; i < n; i++)
    if (sph_solver_step(sv, 1.0 - sv->time, msg, sizeof msg) != 0) fail_msg("%s", msg);
}

static int same_fluid(const struct sph_solver *a, const struct sph_solver *b) {
  const struct sph_parts *fa = &a->sys.part[SPH_KIND_FLUID], *fb = &b->sys.part[SPH_KIND_FLUID];
  if (fa->n != fb->n) return 0;
  for (int c = 0; c < 3; c++) {
    if (memcmp(fa->x[c], fb->x[c], fa->n * sizeof(double)) != 0) return 0;
    if (memcmp(fa->v[c], fb->v[c], fa->n * sizeof(double)) != 0) return 0;
  }
  return memcmp(fa->rho, fb->rho, fa->n * sizeof(double)) == 0;
}

/* α = 0.04: ν_α = 0.04 × 0.05 m × 20 m/s / 8 = 5·10⁻³ m²/s. */
static void test_equals_laminar(void **state) {
  (void)state;
  const double nu_alpha = 0.04 * 0.05 * 20.0 / 8.0;
  char fluid_nu[64];
  snprintf(fluid_nu, sizeof fluid_nu, ", nu: %.17g", nu_alpha);
  struct sph_solver *lam = shear_solver(fluid_nu, "", "");
  struct sph_solver *art = shear_solver("", ", artificial_viscosity: 0.04", "");
  assert_true(art->cfg.nu == lam->cfg.nu);
  assert_true(fabs(art->cfg.nu - 5e-3) <= 1e-17);
  step_n(lam, 20);
  step_n(art, 20);
  assert_true(same_fluid(lam, art));
  /* and the viscosity acts: the shear decays (against an inviscid run) */
  struct sph_solver *inv = shear_solver("", "", "");
  step_n(inv, 20);
  assert_false(same_fluid(lam, inv));
  fixture_solver_destroy(lam);
  fixture_solver_destroy(art);
  fixture_solver_destroy(inv);
}

/* The same repacking (300 steps) with and without a viscosity, an artificial viscosity and the
 * wall impedance: the same positions and densities at t = 0 (the velocities are set afterwards,
 * the same in both). Before the repacking ignored them, the viscous run ended elsewhere. */
static void test_repack_ignores_velocity_terms(void **state) {
  (void)state;
  const char *repack = "repack: {steps: 300}\n";
  struct sph_solver *plain = shear_solver("", "", repack);
  struct sph_solver *visc =
      shear_solver(", nu: 0.01", ", artificial_viscosity: 0.1, wall_impedance: acoustic", repack);
  printf("repacking defect %.3g -> %.3g; with the velocity terms %.3g\n", plain->repack_residual[0],
         plain->repack_residual[1], visc->repack_residual[1]);
  assert_true(plain->repack_residual[1] < 1e-3 * plain->repack_residual[0]);
  assert_true(visc->repack_residual[1] == plain->repack_residual[1]);
  assert_true(same_fluid(plain, visc));
  /* and the repacking moved the fluid */
  struct sph_solver *none = shear_solver("", "", "");
  assert_false(same_fluid(plain, none));
  fixture_solver_destroy(plain);
  fixture_solver_destroy(visc);
  fixture_solver_destroy(none);
}

/* repack.perturbation = 0.05 Δr: a start off the lattice (its defect larger than the
 * lattice's), the same on two runs bit for bit, converging as from the lattice; without
 * repacking steps the perturbation does nothing. */
static void test_repack_perturbed_start(void **state) {
  (void)state;
  const char *lattice = "repack: {steps: 300}\n";
  const char *perturbed = "repack: {steps: 300, perturbation: 0.05}\n";
  struct sph_solver *plain = shear_solver("", "", lattice);
  struct sph_solver *one = shear_solver("", "", perturbed);
  struct sph_solver *two = shear_solver("", "", perturbed);
  printf("repacking defect from the lattice %.3g -> %.3g; perturbed by 0.05 dr %.3g -> %.3g\n",
         plain->repack_residual[0], plain->repack_residual[1], one->repack_residual[0],
         one->repack_residual[1]);
  assert_true(one->cfg.repack_perturbation == 0.05);
  assert_true(plain->cfg.repack_perturbation == 0.0);
  assert_true(one->repack_residual[0] > plain->repack_residual[0]);
  assert_true(one->repack_residual[1] < 1e-3 * one->repack_residual[0]);
  assert_true(same_fluid(one, two));
  assert_false(same_fluid(one, plain));
  /* no steps: neither a repacking nor a draw */
  struct sph_solver *none = shear_solver("", "", "");
  struct sph_solver *none_p = shear_solver("", "", "repack: {steps: 0, perturbation: 0.05}\n");
  assert_true(same_fluid(none, none_p));
  fixture_solver_destroy(plain);
  fixture_solver_destroy(one);
  fixture_solver_destroy(two);
  fixture_solver_destroy(none);
  fixture_solver_destroy(none_p);
}

/* Under a free surface (the shear box half full, no lid) the repacking holds the top rows; a
 * perturbed start must leave exactly those where they were: the particles at their lattice
 * positions after a perturbed repacking are the held ones, as many as the repacking reports. */
static void test_repack_perturbation_spares_the_lid(void **state) {
  (void)state;
  const char *text =
      "geometry:\n"
      "  dimension: 2\n"
      "  dr: 0.025\n"
      "  h_over_dr: 2\n"
      "  first_row: 1\n"
      "  walls: [{type: box, lo: [0, 0], hi: [0.5, 0.4]}]\n"
      "  fluid: [{type: box, lo: [0, 0], hi: [0.5, 0.2]}]\n"
      "fluid: {rho0: 1000, c0: 20}\n"
      "initial: {pressure: 1000}\n"
      "numerics: {vertex_volume: geometric}\n"
      "time: {end: 1}\n"
      "%s";
  char lattice_case[2048], perturbed_case[2048];
  snprintf(lattice_case, sizeof lattice_case, text, "");
  snprintf(perturbed_case, sizeof perturbed_case, text,
           "repack: {steps: 50, perturbation: 0.05}\n");
  struct sph_solver *lattice = fixture_solver_from_case(lattice_case);
  struct sph_solver *perturbed = fixture_solver_from_case(perturbed_case);
  const struct sph_parts *fl = &lattice->sys.part[SPH_KIND_FLUID];
  const struct sph_parts *fp = &perturbed->sys.part[SPH_KIND_FLUID];
  assert_int_equal(fl->n, fp->n);
  size_t unmoved = 0;
  for (size_t a = 0; a < fp->n; a++) {
    int same = 1;
    for (int c = 0; c < 2; c++) same = same && fp->x[c][a] == fl->x[c][a];
    unmoved += (size_t)same;
  }
  printf("free-surface box: %zu of %zu particles held, %zu at their lattice positions\n",
         perturbed->repack_fixed, fp->n, unmoved);
  assert_true(perturbed->repack_fixed > 0 && perturbed->repack_fixed < fp->n);
  assert_int_equal(unmoved, perturbed->repack_fixed);
  fixture_solver_destroy(lattice);
  fixture_solver_destroy(perturbed);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_equals_laminar),
      cmocka_unit_test(test_repack_ignores_velocity_terms),
      cmocka_unit_test(test_repack_perturbed_start),
      cmocka_unit_test(test_repack_perturbation_spares_the_lid),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
