/*
 * Fluid at rest stays at rest (docs/sph-solver.md §8): closed tanks filled with fluid at a uniform
 * pressure, no gravity, inviscid, with the geometric vertex volumes and the initial repacking, run
 * for 20 acoustic times 20 L/c0 (L the largest side): max |ρ/ρ0 − 1| ≤ 1e-3 and max |u| ≤ 1e-3 c0
 * at every step. Four walls: a 2D box (faces and right-angled corners), a 2D box with a 45° wall
 * (135° corners, a lattice cut by the slanted wall), the dam-break wedge's 60° convex apex, and a
 * 3D tank (faces, edges, corners). The same tanks with the fitted vertex layer and no repacking
 * move at 3.5–17 times the bound and compress by up to 25 times as much (printed, not asserted).
 * The operator's behaviour on a constant field next to faces, edges and corners: the zeroth-order
 * defect |Grad^{γ,1}(1)| h/2 at t = 0 is printed per class of particle and must be ≤ 1e-3 after
 * the repacking (on the start lattice it is 0.01–0.13). docs/figures/wall_defect.png shows it.
 * Over seconds, not only 20 L/c0: the 3D tank at 2000 Pa for 2.944 s, the same bounds (the density
 * against its value at t = 0), which needs a repacking that has converged (4000 steps; 1000 leave
 * it moving at 0.04 m/s by the end).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geometry/geometry.h"
#include "solver_fixture.h"
#include "testutil.h"

/* The zeroth-order defect of the solver's operator at the start, |Grad^{γ,1}_a(1)| h / 2 =
 * |Σ_{b∈F∪V} V_b ∇w_ab − ∇γ_a| h / γ_a (uniform ρ), per particle class: the number of box faces
 * (lo/hi in each direction, `box` != NULL) within 2h of the particle, 0 (bulk), 1 (face), 2 (edge
 * or 2D corner), 3 (3D corner); without a box every particle counts as class 1. With the
 * environment variable SABRE_TEST_OUTPUT set, the particles' positions and defects are appended
 * to $SABRE_TEST_OUTPUT/wall_defect_<tag>.csv (docs/figures/wall_defect.py draws them). */
static void defect(const struct sph_solver *sv, const double (*box)[3], const char *tag,
                   double out[4]) {
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  double *one[SPH_NKINDS];
  for (int k = 0; k < SPH_NKINDS; k++) {
    one[k] = malloc((s->part[k].n + 1) * sizeof(double));
    for (size_t i = 0; i < s->part[k].n; i++) one[k][i] = 1.0;
  }
  const struct sph_op op = {s, &sv->kernel, &sv->nb, 0};
  FILE *csv = NULL;
  const char *dir = getenv("SABRE_TEST_OUTPUT");
  if (dir) {
    char path[1024];
    snprintf(path, sizeof path, "%s/wall_defect_%s.csv", dir, tag);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "x,y,z,class,defect\n");
  }
  for (int c = 0; c < 4; c++) out[c] = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    double g[3];
    sph_op_grad(&op, 1.0, (const double *const *)one, a, g);
    const double d = 0.5 * s->h * sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    int cls = 1;
    if (box) {
      cls = 0;
      for (int c = 0; c < s->dim; c++)
        cls += (f->x[c][a] - box[0][c] < 2.0 * s->h) + (box[1][c] - f->x[c][a] < 2.0 * s->h);
      if (cls > 3) cls = 3;
    }
    out[cls] = fmax(out[cls], d);
    if (csv) fprintf(csv, "%.9g,%.9g,%.9g,%d,%.6g\n", f->x[0][a], f->x[1][a], f->x[2][a], cls, d);
  }
  if (csv) fclose(csv);
  for (int k = 0; k < SPH_NKINDS; k++) free(one[k]);
}

/* Run the case text to time.end; return the largest max|u| and max|ρ/ρ_ref − 1| over the steps
 * (ρ_ref = ρ0, or with `from_start` each particle's density at t = 0), and the defect at the start
 * per class (defect()). */
static void run_ref(const char *text, const char *extra, const double (*box)[3], const char *tag,
                    int from_start, double dstart[4], double *umax, double *dmax) {
  char buf[4096], err[512];
  snprintf(buf, sizeof buf, "%s%s", text, extra);
  struct cmn_case *c = cmn_case_parse(buf, "rest.yaml", err, sizeof err);
  if (c == NULL) fail_msg("%s", err);
  struct sph_geometry g;
  sph_geometry_read(&g, c);
  struct sph_system s;
  sph_system_from_geometry(&s, &g);
  struct sph_config cfg;
  assert_int_equal(sph_config_read(&cfg, c, s.dim), 0);
  struct sph_solver *sv = calloc(1, sizeof *sv);
  sph_solver_init(sv, &cfg, &s, NULL, NULL);
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  sph_solver_evaluate(sv);
  if (cfg.repack_steps > 0)
    print_message("  %s: repacking, %ld steps: largest defect x h %.3g -> %.3g\n", tag,
                  cfg.repack_steps, sv->repack_residual[0], sv->repack_residual[1]);
  defect(sv, box, tag, dstart);
  double *rho_ref = calloc(f->n + 1, sizeof *rho_ref);
  for (size_t a = 0; a < f->n; a++) rho_ref[a] = from_start ? f->rho[a] : cfg.rho0;
  *umax = *dmax = 0.0;
  char msg[1024];
  while (sv->time < cfg.t_end * (1.0 - 1e-12)) {
    if (sph_solver_step(sv, cfg.t_end - sv->time, msg, sizeof msg) != 0) fail_msg("%s", msg);
    for (size_t a = 0; a < f->n; a++) {
      const double u =
          sqrt(f->v[0][a] * f->v[0][a] + f->v[1][a] * f->v[1][a] + f->v[2][a] * f->v[2][a]);
      *umax = fmax(*umax, u);
      *dmax = fmax(*dmax, fabs(f->rho[a] / rho_ref[a] - 1.0));
    }
  }
  free(rho_ref);
  sph_solver_free(sv);
  free(sv);
  sph_system_free(&s);
  sph_geometry_free(&g);
  cmn_case_free(c);
}

static void run(const char *text, const char *extra, const double (*box)[3], const char *tag,
                double dstart[4], double *umax, double *dmax) {
  run_ref(text, extra, box, tag, 0, dstart, umax, dmax);
}

/* Fluid: c0 = 20 m/s, uniform p = 200 Pa (ρ/ρ0 − 1 = 5.0e-4). */
#define FLUID                                                                     \
  "fluid:\n  rho0: 1000\n  c0: 20\n  xi: 7\n  nu: 0\ninitial:\n  pressure: 200\n" \
  "time:\n  output_interval: 1\n"
#define REST "numerics:\n  vertex_volume: geometric\nrepack:\n  steps: 1000\n"
#define OLD "numerics:\n  vertex_volume: fitted\n"

/* Run with the geometric volumes and the repacking, and as before (fitted layer, no repacking);
 * assert rest and a small defect at the start on every class (the operator's behaviour on a
 * constant field next to faces, edges and corners, printed). */
static void check(const char *name, const char *tag, const char *text, const double (*box)[3],
                  double c0) {
  double u, d, u_old, d_old, ds[4], ds_old[4];
  char tag_new[64], tag_old[64];
  snprintf(tag_new, sizeof tag_new, "%s_repacked", tag);
  snprintf(tag_old, sizeof tag_old, "%s_lattice", tag);
  run(text, REST, box, tag_new, ds, &u, &d);
  run(text, OLD, box, tag_old, ds_old, &u_old, &d_old);
  print_message(
      "%s: max|u|/c0 %.3g, max|rho/rho0 - 1| %.3g (fitted layer, no repacking: %.3g, "
      "%.3g)\n",
      name, u / c0, d, u_old / c0, d_old);
  static const char *const cls[4] = {"bulk", "face", "edge/2D corner", "3D corner"};
  for (int c = 0; c < 4; c++)
    if (ds[c] > 0.0 || ds_old[c] > 0.0)
      print_message("  defect |sum V grad w - grad gamma| h / gamma, %s: %.3g (before %.3g)\n",
                    box ? cls[c] : "near walls", ds[c], ds_old[c]);
  assert_true(u <= 1e-3 * c0);
  assert_true(d <= 1e-3);
  for (int c = 0; c < 4; c++) assert_true(ds[c] <= 1e-3);
}

/* 2D box 1 × 1.5 m, Δr = 0.05 m, h = 2Δr, the first row Δr from the walls: 20 L/c0 = 1.5 s. */
static void test_box_2d(void **state) {
  (void)state;
  static const double box[2][3] = {{0, 0, 0}, {1, 1.5, 0}};
  check("2D box", "box2d",
        "geometry:\n  dimension: 2\n  dr: 0.05\n  h_over_dr: 2\n  first_row: 1\n  walls:\n"
        "    - type: box\n      lo: [0, 0]\n      hi: [1, 1.5]\n  fluid:\n    - type: box\n"
        "      lo: [0, 0]\n      hi: [1, 1.5]\n" FLUID "  end: 1.5\n",
        box, 20.0);
}

/* 2D box 1 × 1 m with its upper right corner cut by a 45° wall from (1, 0.6) to (0.6, 1): the
 * lattice points closer than 0.8Δr to a wall are dropped. 20 L/c0 = 1 s. */
static void test_slanted_2d(void **state) {
  (void)state;
  check("2D box with a 45 degree wall", "slanted2d",
        "geometry:\n  dimension: 2\n  dr: 0.05\n  h_over_dr: 2\n  first_row: 1\n"
        "  min_wall_distance: 0.04\n  walls:\n    - type: polygon\n"
        "      points: [[0, 0], [1, 0], [1, 0.6], [0.6, 1.0], [0, 1.0]]\n  fluid:\n"
        "    - type: box\n      lo: [0, 0]\n      hi: [1, 1]\n" FLUID "  end: 1.0\n",
        NULL, 20.0);
}

/* The dam-break wedge (equilateral, side 0.25 m, apex 0.2165 m above the floor) in a closed tank
 * 1 × 0.6 m, Δr = 0.025 m. 20 L/c0 = 1 s. */
static void test_wedge_2d(void **state) {
  (void)state;
  check("2D wedge apex", "wedge2d",
        "geometry:\n  dimension: 2\n  dr: 0.025\n  h_over_dr: 2\n  first_row: 1\n"
        "  min_wall_distance: 0.02\n  walls:\n    - type: polygon\n"
        "      points: [[0, 0], [0.35, 0], [0.475, 0.21650635094610965], [0.6, 0], [1.0, 0],\n"
        "               [1.0, 0.6], [0, 0.6]]\n  fluid:\n    - type: box\n      lo: [0, 0]\n"
        "      hi: [1, 0.6]\n" FLUID "  end: 1.0\n",
        NULL, 20.0);
}

/* 3D tank 0.2 × 0.2 × 0.3 m, Δr = 0.025 m, h = 2Δr (539 particles), c0 = 15 m/s, p = 100 Pa:
 * 20 L/c0 = 0.4 s. */
static void test_tank_3d(void **state) {
  (void)state;
  static const double box[2][3] = {{0, 0, 0}, {0.2, 0.2, 0.3}};
  check("3D tank", "tank3d",
        "geometry:\n  dimension: 3\n  dr: 0.025\n  h_over_dr: 2\n  first_row: 1\n  walls:\n"
        "    - type: box\n      lo: [0, 0, 0]\n      hi: [0.2, 0.2, 0.3]\n  fluid:\n"
        "    - type: box\n      lo: [0, 0, 0]\n      hi: [0.2, 0.2, 0.3]\n"
        "fluid:\n  rho0: 1000\n  c0: 15\n  xi: 7\n  nu: 0\ninitial:\n  pressure: 100\n"
        "time:\n  output_interval: 1\n  end: 0.4\n",
        box, 15.0);
}

/* The 3D tank closed at 0.2 m (343 particles) at 2000 Pa, the bottom pressure of
 * still_water_tank_3d, for 2.944 s (that case's run, 220 L/c0): the repulsion's stiffness grows
 * with p, and an arrangement the repacking has not brought to rest moves on over seconds. With
 * 1000 repacking steps (defect 2.2e-5 × 1/h) the kinetic energy grows from 1.8e-7 to 7.2e-4 J
 * (max|u| 0.038 m/s); with 4000 (defect ~1e-6) it stays at rest (docs/sph-solver.md §7.1). The
 * density is measured against each particle's own at t = 0 (at 2000 Pa ρ/ρ0 − 1 = 8.9e-3). */
static void test_tank_3d_seconds(void **state) {
  (void)state;
  static const double box[2][3] = {{0, 0, 0}, {0.2, 0.2, 0.2}};
  double u, d, ds[4];
  run_ref(
      "geometry:\n  dimension: 3\n  dr: 0.025\n  h_over_dr: 2\n  first_row: 1\n  walls:\n"
      "    - type: box\n      lo: [0, 0, 0]\n      hi: [0.2, 0.2, 0.2]\n  fluid:\n"
      "    - type: box\n      lo: [0, 0, 0]\n      hi: [0.2, 0.2, 0.2]\n"
      "fluid:\n  rho0: 1000\n  c0: 15\n  xi: 7\n  nu: 0\ninitial:\n  pressure: 2000\n"
      "time:\n  output_interval: 10\n  end: 2.944\n",
      "numerics:\n  vertex_volume: geometric\nrepack:\n  steps: 4000\n", box, "tank3d_2kPa", 1, ds,
      &u, &d);
  print_message("3D tank at 2000 Pa for 2.944 s: max|u|/c0 %.3g, max|rho/rho(0) - 1| %.3g\n",
                u / 15.0, d);
  assert_true(u <= 1e-3 * 15.0);
  assert_true(d <= 1e-3);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_box_2d),          cmocka_unit_test(test_slanted_2d),
      cmocka_unit_test(test_wedge_2d),        cmocka_unit_test(test_tank_3d),
      cmocka_unit_test(test_tank_3d_seconds),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
