/*
 * The solver's case-file sections (docs/sph-case-file.md): defaults, and bad input failing with
 * a message naming the file, line and key (non-fatal mode so that the messages can be checked).
 */
#include <math.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_open.h"
#include "sabre/sph_solver.h"
#include "solver_fixture.h"
#include "testutil.h"

static const char base[] =
    "geometry:\n"
    "  walls: [{type: box, lo: [0, 0], hi: [1, 1]}, {type: box, lo: [2, 0], hi: [3, 1]}]\n"
    "fluid: {rho0: 1000, c0: 20}\n"
    "time: {end: 2.5}\n";

static int read_case(const char *extra, struct sph_config *cfg, char *msg, size_t len) {
  return fixture_read_case(base, extra, cfg, msg, len);
}

static void test_defaults(void **state) {
  (void)state;
  struct sph_config cfg;
  char msg[512];
  assert_int_equal(read_case("", &cfg, msg, sizeof msg), 0);
  assert_true(cfg.xi == 7.0 && cfg.nu == 0.0 && cfg.grad_k == 1.0);
  assert_true(cfg.artificial_viscosity == 0.0);
  assert_int_equal(cfg.diffusion, SPH_DIFFUSION_FERRARI);
  assert_int_equal(cfg.gravity_correction, 2);
  assert_int_equal(cfg.vertex_hydro, SPH_VHYDRO_FULL);
  assert_int_equal(cfg.gamma_dynamic, 0);
  assert_int_equal(cfg.open_gradient_difference, 0);
  assert_int_equal(cfg.no_pull_normal, 0);
  assert_int_equal(cfg.lone_ambient, 0);
  assert_true(cfg.lone_fraction == 0.35);
  assert_int_equal(cfg.wall_vertex_mass_density, 0);
  assert_int_equal(cfg.list_rebuild, SPH_LISTS_WHEN_NEEDED);
  assert_true(cfg.cfl == 0.3 && cfg.output_interval == 0.025 && isinf(cfg.dt_max));
  assert_true(isnan(cfg.free_surface));
  assert_true(cfg.density_band[0] == 0.5 && cfg.density_band[1] == 1.5);
  assert_int_equal(cfg.wall_impedance, SPH_IMPEDANCE_CONTACT);
  assert_true(cfg.wall_impedance_reach == 1.0);
  assert_true(cfg.settle == 0.0 && cfg.layer_equilibrium == 0);
  assert_int_equal(
      read_case("gravity: [0, -9.81]\nforces: [{name: right, wall: 1, edges: [2, 3]}]\n"
                "probes: {pressure: [[0.5, 0.5]], gauges: [[0.2, 0], [0.8, 0]]}\n",
                &cfg, msg, sizeof msg),
      0);
  assert_true(cfg.gravity[1] == -9.81 && cfg.nforces == 1 && cfg.forces[0].wall == 1);
  assert_true(cfg.forces[0].nedges == 2 && cfg.forces[0].edges[1] == 3);
  assert_true(cfg.nprobes == 1 && cfg.ngauges == 2 && cfg.gauges[1][0] == 0.8);
}

static void expect(const char *extra, const char *key, const char *what) {
  struct sph_config cfg;
  char msg[512];
  assert_int_equal(read_case(extra, &cfg, msg, sizeof msg), -1);
  print_message("%s\n", msg);
  assert_non_null(strstr(msg, "case.yaml"));
  if (!strstr(msg, key) || !strstr(msg, what)) fail_msg("'%s' lacks '%s' or '%s'", msg, key, what);
}

static void test_errors(void **state) {
  (void)state;
  expect("numerics: {cfll: 0.2}\n", "numerics.cfll", "");
  expect("numerics: {diffusion: laplace}\n", "numerics.diffusion", "ferrari");
  expect("numerics: {gradient_k: 3}\n", "numerics.gradient_k", "");
  expect("numerics: {artificial_viscosity: -0.01}\n", "numerics.artificial_viscosity", "");
  expect("repack: {steps: 100, perturbation: 0.3}\n", "repack.perturbation", "");
  expect("repack: {settle: -1}\n", "repack.settle", "");
  expect("repack: {layer_equilibrium: yes please}\n", "repack.layer_equilibrium", "");
  expect("repack: {layer_equilibrium: true}\n", "repack.layer_equilibrium", "non-zero gravity");
  expect("numerics: {open_gradient: diff}\n", "numerics.open_gradient", "symmetric, difference");
  expect("numerics: {no_pull: tangential}\n", "numerics.no_pull", "radial, normal");
  expect("numerics: {lone_particle: zero}\n", "numerics.lone_particle", "eos, ambient");
  expect("numerics: {lone_particle: ambient, lone_fraction: 1.5}\n", "numerics.lone_fraction", "");
  expect("numerics: {lone_fraction: 0.3}\n", "numerics.lone_fraction", "ambient only");
  expect("numerics: {wall_vertex_mass: fitted}\n", "numerics.wall_vertex_mass",
         "constant, density");
  expect("numerics: {list_rebuild: never}\n", "numerics.list_rebuild", "when_needed");
  expect("numerics: {density_band: [1.1, 1.5]}\n", "numerics.density_band", "0 < lo < 1 < hi");
  expect("numerics: {wall_impedance: rigid}\n", "numerics.wall_impedance",
         "none, acoustic, contact");
  expect("numerics: {wall_impedance_reach: 0}\n", "numerics.wall_impedance_reach", "");
  expect("numerics: {wall_impedance: acoustic, wall_impedance_reach: 2}\n",
         "numerics.wall_impedance_reach", "contact form only");
  expect("initial: {pressure: hydrostatic}\n", "initial.pressure", "gravity");
  expect("initial: {velocity: [1]}\n", "initial.velocity", "");
  expect("forces: [{name: a, wall: 2}]\n", "forces[0].wall", "");
  expect("forces: [{name: a, wall: 0}, {name: a, wall: 1}]\n", "forces[1].name", "duplicate");
  expect("probes: {pressure: [[1, 2, 3]]}\n", "probes.pressure[0]", "");
  expect("--set time.end=-1", "time.end", "positive");
  expect("--set fluid.xi=0.5", "fluid.xi", "");
  expect("--set fluid.c0=fast", "fluid.c0", "fast");
  expect("--set numerics.cfl=2", "numerics.cfl", "(0, 1]");
}

/* repack.settle: the case's own dynamics before t = 0, then the velocities zeroed and the clock at
 * 0: a 2D box of water with a free surface (a start that moves) */
#define SETTLE_CASE                                          \
  "geometry:\n"                                              \
  "  dimension: 2\n"                                         \
  "  dr: 0.025\n"                                            \
  "  h_over_dr: 2\n"                                         \
  "  first_row: 1\n"                                         \
  "  walls: [{type: box, lo: [0, 0], hi: [0.3, 0.3]}]\n"     \
  "  fluid: [{type: box, lo: [0, 0], hi: [0.3, 0.2]}]\n"     \
  "fluid: {rho0: 1000, c0: 20}\n"                            \
  "gravity: [0, -9.81]\n"                                    \
  "initial: {pressure: hydrostatic, free_surface: 0.2125}\n" \
  "time: {end: 1}\n"                                         \
  "%s"

/* The box of SETTLE_CASE as it is (*plain) and with the case text `extra` added (*with). */
static void box_pair(const char *extra, struct sph_solver **plain, struct sph_solver **with) {
  char text[2048];
  snprintf(text, sizeof text, SETTLE_CASE, "");
  *plain = fixture_solver_from_case(text);
  snprintf(text, sizeof text, SETTLE_CASE, extra);
  *with = fixture_solver_from_case(text);
  assert_int_equal((*plain)->sys.part[SPH_KIND_FLUID].n, (*with)->sys.part[SPH_KIND_FLUID].n);
}

static void test_settle(void **state) {
  (void)state;
  struct sph_solver *s0, *s1;
  box_pair("repack: {settle: 0.05}\n", &s0, &s1);
  const struct sph_parts *f0 = &s0->sys.part[SPH_KIND_FLUID], *f1 = &s1->sys.part[SPH_KIND_FLUID];
  assert_true(s0->settle_steps == 0 && s1->settle_steps > 10);
  assert_true(s1->time == 0.0 && s1->step == 0 && s1->settle_speed > 0.0);
  double moved = 0.0, vmax = 0.0;
  for (size_t a = 0; a < f1->n; a++)
    for (int c = 0; c < 2; c++) {
      moved = fmax(moved, fabs(f1->x[c][a] - f0->x[c][a]));
      vmax = fmax(vmax, fabs(f1->v[c][a]));
    }
  print_message("settled 0.05 s in %ld steps: largest displacement %.3g m, speed %.3g m/s\n",
                s1->settle_steps, moved, s1->settle_speed);
  assert_true(moved > 1e-6 && vmax == 0.0);
  fixture_solver_destroy(s0);
  fixture_solver_destroy(s1);
}

/* Each row's mean vertical acceleration / g of a 2D solver's fluid (rows by y/Δr rounded), after a
 * fresh evaluation; returns the largest |mean| and the number of rows in *nrow. */
static double row_means(struct sph_solver *sv, int *nrow) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  double sum[64] = {0.0}, cnt[64] = {0.0}, worst = 0.0;
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
  *nrow = 0;
  for (size_t a = 0; a < f->n; a++) {
    const long k = lround(f->x[1][a] / sv->sys.dr);
    assert_true(k >= 0 && k < 64);
    sum[k] += sv->acc[1][a] / 9.81;
    cnt[k] += 1.0;
  }
  for (int k = 0; k < 64; k++)
    if (cnt[k] > 0.0) {
      (*nrow)++;
      worst = fmax(worst, fabs(sum[k] / cnt[k]));
    }
  return worst;
}

/* repack.layer_equilibrium: the box of test_settle, each of its 8 rows moved as one along the
 * vertical to where its mean vertical acceleration is zero, densities hydrostatic where they are */
static void test_layer_equilibrium(void **state) {
  (void)state;
  struct sph_solver *s0, *s1;
  box_pair("repack: {layer_equilibrium: true}\n", &s0, &s1);
  const struct sph_parts *f0 = &s0->sys.part[SPH_KIND_FLUID], *f1 = &s1->sys.part[SPH_KIND_FLUID];
  assert_int_equal(s0->layer_count, 0);
  assert_int_equal(s1->layer_count, 8);
  assert_true(s1->layer_residual <= 1e-9);
  /* the lattice is not the scheme's equilibrium; the moved rows are */
  int n0, n1;
  const double before = row_means(s0, &n0), after = row_means(s1, &n1);
  print_message(
      "rows' largest mean vertical acceleration: %.3g g on the lattice, %.3g g after; "
      "highest rows moved by %+.4f, %+.4f dr\n",
      before, after, s1->layer_shift[0], s1->layer_shift[1]);
  assert_int_equal(n0, 8);
  assert_int_equal(n1, 8);
  assert_true(before > 1e-3 && after <= 1e-9);
  /* each row moved as one, vertically, by its shift (the highest first); hydrostatic densities */
  const double dr = s1->sys.dr;
  for (size_t a = 0; a < f1->n; a++) {
    const int k = 8 - (int)lround(f0->x[1][a] / dr);
    assert_true(fabs(f1->x[0][a] - f0->x[0][a]) <= 1e-15);
    assert_true(fabs(f1->x[1][a] - f0->x[1][a] - s1->layer_shift[k] * dr) <= 1e-12);
    const double p = sph_hydrostatic_pressure(&s1->eos, 9.81, 0.2125 - f1->x[1][a]);
    assert_true(fabs(f1->rho[a] - rmn_eos_density(&s1->eos, p)) <= 1e-9);
    assert_true(fabs(f1->mass[a] - f1->rho[a] * dr * dr) <= 1e-12);
  }
  fixture_solver_destroy(s0);
  fixture_solver_destroy(s1);
}

/* probes.gauges' level (sph_solver_level) on the lattice start (top row Δr/2 below H = 0.2125 m):
 * H within tol[0] Δr at 2h or more from the side walls, tol[1] Δr from h to 2h and tol[2] Δr
 * closer (the first column's line). The errors next to walls are the vertex layer's: its point
 * volumes stand for the Δr/2 slab the first row leaves (measured, fitted / geometric volumes:
 * 2D 0.0014 / −0.014 Δr at h, 0.042 / −0.032 Δr at Δr; 3D up to 0.0019 / −0.029 Δr at h,
 * 0.14 / −0.078 Δr on the corner column); without the vertex sum, 0.12 Δr low at h. The particle
 * gauge (sph_solver_gauge) reads H exactly. */
static void level_check(const char *text, const double (*at)[3], int n, const double tol[3]) {
  struct sph_solver *sv = fixture_solver_from_case(text);
  const double dr = sv->sys.dr, h = sv->sys.h, H = 0.2125;
  for (int i = 0; i < n; i++) {
    const double level = sph_solver_level(sv, at[i]), eta = sph_solver_gauge(sv, at[i]);
    double wall = INFINITY; /* distance to the nearest side wall (the box is [0, 0.3]) */
    for (int c = 0; c < sv->sys.dim - 1; c++) wall = fmin(wall, fmin(at[i][c], 0.3 - at[i][c]));
    print_message("%dD gauge at %.3f, %.3f (%.0f dr from a wall): level - H = %+.5f dr\n",
                  sv->sys.dim, at[i][0], at[i][1], wall / dr, (level - H) / dr);
    assert_true(fabs(eta - H) <= 1e-12);
    assert_true(fabs(level - H) <= tol[wall >= 2.0 * h - 1e-12 ? 0
                                       : wall >= h - 1e-12     ? 1
                                                               : 2] *
                                       dr);
  }
  fixture_solver_destroy(sv);
}

#define LEVEL_TANK                                               \
  "geometry:\n"                                                  \
  "  dimension: 3\n"                                             \
  "  dr: 0.025\n"                                                \
  "  h_over_dr: 2\n"                                             \
  "  first_row: 1\n"                                             \
  "  walls: [{type: box, lo: [0, 0, 0], hi: [0.3, 0.3, 0.3]}]\n" \
  "  fluid: [{type: box, lo: [0, 0, 0], hi: [0.3, 0.3, 0.2]}]\n" \
  "fluid: {rho0: 1000, c0: 20}\n"                                \
  "gravity: [0, 0, -9.81]\n"                                     \
  "initial: {pressure: hydrostatic, free_surface: 0.2125}\n"     \
  "time: {end: 1}\n"                                             \
  "%s"

static void test_level(void **state) {
  (void)state;
  const char *geometric = "numerics: {vertex_volume: geometric}\n";
  char text[2048];
  const double at2[][3] = {{0.025, 0.1, 0}, {0.05, 0, 0}, {0.075, 0, 0}, {0.15, 0, 0}};
  snprintf(text, sizeof text, SETTLE_CASE, "");
  level_check(text, at2, 4, (const double[3]){1e-3, 2e-3, 0.05});
  snprintf(text, sizeof text, SETTLE_CASE, geometric);
  level_check(text, at2, 4, (const double[3]){1e-3, 0.02, 0.04});
  const double at3[][3] = {
      {0.025, 0.15, 0}, {0.025, 0.025, 0}, {0.05, 0.15, 0}, {0.05, 0.05, 0}, {0.15, 0.15, 0}};
  snprintf(text, sizeof text, LEVEL_TANK, "");
  level_check(text, at3, 5, (const double[3]){1e-3, 3e-3, 0.16});
  snprintf(text, sizeof text, LEVEL_TANK, geometric);
  level_check(text, at3, 5, (const double[3]){1e-3, 0.035, 0.09});
  /* a column of water 3 Δr wide against the left wall: no level 2h beyond its side, and none
   * where only its side's particles are within 2h (their sum stays below 1/2) */
  snprintf(text, sizeof text, SETTLE_CASE, "");
  char *fluid = strstr(text, "hi: [0.3, 0.2]");
  assert_non_null(fluid);
  memcpy(fluid, "hi: [0.1, 0.2]", 14);
  struct sph_solver *sv = fixture_solver_from_case(text);
  const double beyond[3] = {0.25, 0, 0}, side[3] = {0.15, 0, 0}, inside[3] = {0.05, 0, 0};
  const double l_in = sph_solver_level(sv, inside);
  print_message("3-column water: level at x = 0.05 m: %+.4f dr from H\n", (l_in - 0.2125) / 0.025);
  assert_true(isnan(sph_solver_level(sv, beyond)) && isnan(sph_solver_gauge(sv, beyond)));
  assert_true(isnan(sph_solver_level(sv, side)) && isfinite(sph_solver_gauge(sv, side)));
  assert_true(fabs(l_in - 0.2125) <= 0.5 * sv->sys.dr);
  fixture_solver_destroy(sv);
}

static void test_missing(void **state) {
  (void)state;
  char err[512];
  struct cmn_case *c =
      cmn_case_parse("fluid: {rho0: 1000}\ntime: {end: 1}\n", "case.yaml", err, sizeof err);
  cmn_case_set_fatal(c, 0);
  struct sph_config cfg;
  assert_int_equal(sph_config_read(&cfg, c, 2), -1);
  assert_non_null(strstr(cmn_case_error(c), "fluid.c0"));
  cmn_case_free(c);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_defaults),          cmocka_unit_test(test_errors),
      cmocka_unit_test(test_missing),           cmocka_unit_test(test_settle),
      cmocka_unit_test(test_layer_equilibrium), cmocka_unit_test(test_level),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
