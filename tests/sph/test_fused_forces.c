/* The momentum equation's fluid pairs fused into one pass (solver.c, operators/pressure.h) give
 * bitwise the accelerations of the operators called one after the other,
 * sph_op_grad_pressure and sph_op_lap: a 3D tank with viscosity, volume diffusion and the wall
 * impedance, particles off the lattice and moving; a 2D through-flow with the difference form next
 * to its open boundaries. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "operators/pair.h"
#include "operators/pressure.h"
#include "solver_fixture.h"

static const char tank[] =
    "geometry:\n"
    "  dimension: 3\n"
    "  dr: 0.025\n"
    "  h_over_dr: 2\n"
    "  first_row: 1\n"
    "  walls: [{type: box, lo: [0, 0, 0], hi: [0.2, 0.15, 0.15]}]\n"
    "  fluid: [{type: box, lo: [0, 0, 0], hi: [0.2, 0.15, 0.1]}]\n"
    "fluid: {rho0: 1000, c0: 20, nu: 1.0e-3}\n"
    "gravity: [0, 0, -9.81]\n"
    "initial: {pressure: hydrostatic}\n"
    "numerics: {diffusion: ferrari, wall_impedance: acoustic}\n"
    "time: {end: 1}\n";

/* Moves the fluid off its lattice and sets it moving, then compares the solver's accelerations
 * with those of the separate operators at the same state. */
static void compare(struct sph_solver *sv, int shake) {
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 17);
  for (size_t a = 0; shake && a < f->n; a++)
    for (int c = 0; c < sv->sys.dim; c++) {
      f->x[c][a] += sabre_rng_uniform(&rng, -0.2, 0.2) * sv->sys.dr;
      f->v[c][a] += sabre_rng_uniform(&rng, -0.3, 0.3);
    }
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
  const struct sph_system *s = &sv->sys;
  const double *pk[SPH_NKINDS] = {s->part[0].p, s->part[1].p, s->part[2].p};
  const double *muk[SPH_NKINDS] = {sv->mu[0], sv->mu[1], sv->mu[2]};
  const double *vel[SPH_NKINDS][3];
  for (int k = 0; k < SPH_NKINDS; k++)
    for (int c = 0; c < 3; c++) vel[k][c] = s->part[k].v[c];
  /* the wall shear of every F–S pair as an array, for the unfused operator */
  const struct sph_nlist *nls = &sv->nb.list[SPH_KIND_SEGMENT];
  const struct sph_wall_shear shear = {sv->mu[SPH_KIND_FLUID], sv->mu[SPH_KIND_SEGMENT],
                                       0.5 * s->dr};
  const size_t np = nls->offset[f->n];
  double *fl[3];
  for (int c = 0; c < 3; c++) fl[c] = malloc((np ? np : 1) * sizeof(double));
  for (size_t a = 0; a < f->n; a++)
    for (size_t q = nls->offset[a]; q < nls->offset[a + 1]; q++) {
      double w[3];
      sph_wall_shear_flux(s, &sv->nb, &shear, a, q, w);
      for (int c = 0; c < 3; c++) fl[c][q] = w[c];
    }
  const double *flux[3] = {fl[0], fl[1], fl[2]};
  const struct sph_op op = {s, &sv->kernel, &sv->nb, 0};
  const struct sph_wall_impedance imp = {
      sv->impedance,
      sv->cfg.wall_impedance == SPH_IMPEDANCE_CONTACT ? sv->cfg.wall_impedance_reach * s->dr : 0.0};
  const int viscous = sv->cfg.nu > 0.0;
  size_t compared = 0;
  for (size_t a = 0; a < f->n; a++) {
    if (sph_open_exit_segment(sv->open, sv, a) >= 0) continue; /* gravity only */
    double gp[3], lap[3] = {0.0, 0.0, 0.0};
    sph_op_grad_pressure(&op, sv->cfg.grad_k, pk, a, sv->cfg.wall_impedance ? &imp : NULL,
                         sv->cfg.open_gradient_difference, NULL, gp);
    if (viscous) sph_op_lap(&op, muk, (const double *const(*)[3])vel, flux, a, lap);
    for (int c = 0; c < 3; c++) {
      const double acc = (lap[c] - gp[c]) * (1.0 / f->rho[a]) + sv->cfg.gravity[c];
      if (acc != sv->acc[c][a])
        fail_msg("particle %zu, component %d: fused %.17g, operators %.17g", a, c, sv->acc[c][a],
                 acc);
    }
    compared++;
  }
  for (int c = 0; c < 3; c++) free(fl[c]);
  print_message("%zu particles: the same bits\n", compared);
  assert_true(compared > 100);
}

static void test_tank(void **state) {
  (void)state;
  struct sph_solver *sv = fixture_solver_from_case(tank);
  compare(sv, 1);
  fixture_solver_destroy(sv);
}

/* The same with the contact form of the wall impedance, its reach wide enough (2Δr) that the
 * shaken particles near the walls get every weight from 0 to 1. */
static void test_tank_contact(void **state) {
  (void)state;
  char text[sizeof tank + 64];
  const char *at = strstr(tank, "acoustic");
  snprintf(text, sizeof text, "%.*scontact, wall_impedance_reach: 2%s", (int)(at - tank), tank,
           at + strlen("acoustic"));
  struct sph_solver *sv = fixture_solver_from_case(text);
  assert_int_equal(sv->cfg.wall_impedance, SPH_IMPEDANCE_CONTACT);
  compare(sv, 1);
  fixture_solver_destroy(sv);
}

static void test_open_difference(void **state) {
  (void)state;
  char text[4096];
  snprintf(text, sizeof text, "%snumerics: {open_gradient: difference}\n", FIXTURE_THROUGH_CASE);
  struct sph_solver *sv = fixture_solver_from_case(text);
  char msg[1024];
  for (int n = 0; n < 60; n++) /* particles created and leaving */
    if (sph_solver_step(sv, INFINITY, msg, sizeof msg) != 0) fail_msg("%s", msg);
  compare(sv, 0);
  fixture_solver_destroy(sv);
}

/* The pair term both paths form for k = 1, m_b (ρ_a (f_b − fc)/ρ_b² + (f_a − fc)/ρ_a), against
 * M(37)'s V_b [(ρ_a/ρ_b)(f_b − fc) + (ρ_b/ρ_a)(f_a − fc)] at random densities (±5 %), values and
 * shares of the difference form: the same to round-off. */
static void test_pair_term_k1(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 91);
  double worst = 0.0;
  for (int i = 0; i < 10000; i++) {
    const double rho_a = 1000.0 * sabre_rng_uniform(&rng, 0.95, 1.05);
    const double rho_b = 1000.0 * sabre_rng_uniform(&rng, 0.95, 1.05);
    const double m_b = sabre_rng_uniform(&rng, 0.5, 2.0), fa = sabre_rng_uniform(&rng, -1e3, 1e4);
    const double fb = sabre_rng_uniform(&rng, -1e3, 1e4);
    const double fc = i % 2 ? 0.0 : sabre_rng_uniform(&rng, 0.0, 1.0) * fa;
    const double ratio = rho_a / rho_b, vb = m_b / rho_b;
    const double ref = vb * (ratio * fb + fa / ratio - fc * (ratio + 1.0 / ratio));
    const double got =
        sph_pair_pressure_k1(m_b, rho_a, sph_inv_rho2(rho_b), fb - fc, (fa - fc) / rho_a);
    const double size =
        vb * (ratio * fabs(fb) + fabs(fa) / ratio + fabs(fc) * (ratio + 1.0 / ratio));
    worst = fmax(worst, fabs(got - ref) / size);
  }
  print_message("k = 1 pair term: largest difference %.2e of the terms' size\n", worst);
  assert_true(worst <= 1e-15);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_tank), cmocka_unit_test(test_tank_contact),
      cmocka_unit_test(test_open_difference), cmocka_unit_test(test_pair_term_k1)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
