/*
 * A wall does not pull a particle that moves towards it (docs/sph-solver.md §4,
 * operators/pressure.h):
 * - in a closed tank at a uniform pressure p (no gravity), the first column Δr from a side wall is
 *   pushed away from it when p > 0 (the zeroth-order defect of §2 times 2p) and, with the plain
 *   Grad^{γ,k} of M(37), pulled into it when p < 0; the momentum equation's pressure gradient
 *   leaves out the wall pairs with a negative pressure sum while the particle does not move away
 *   from the element, so that the column at rest is not pulled, a receding one is held back as
 *   M(37) holds it, and the result equals M(37) to the last bit where no wall sum is negative;
 * - what is left out never does negative work: for any velocities, v_a·(a_a − a_a^M37) ≤ 0 at
 *   every particle (fixed walls), so the rule adds no kinetic energy to M(37)'s;
 * - the contact line of a collapsing viscous column (the reproducer of issue 5, coarser): the
 *   particle at the top of the column next to the wall, in slight tension and held by the wall
 *   shear stress M(19–20), drifted into the wall and the run stopped (ρ/ρ0 < 0.5); it now stays
 *   about Δr from the wall.
 */
#include <math.h>
#include <stdlib.h>

#include "operators/pressure.h"
#include "solver_fixture.h"
#include "testutil.h"

/* Closed box [0, W] × [0, HB] with nx × ny fluid particles at ((i + 1) dr, (j + 1) dr). */
static void box(struct sph_solver *sv, const struct sph_config *cfg, double dr, double W, double HB,
                int nx, int ny) {
  struct sph_system s;
  fixture_tank(&s, W, HB, dr, nx, ny);
  sph_solver_init(sv, cfg, &s, NULL, NULL);
  sph_system_free(&s);
}

enum { NX = 19, NY = 10 };

/* The box of NX × NY particles, Δr = 0.01 m, inviscid and without diffusion, filled at the uniform
 * pressure p0 [Pa] and evaluated (no gravity). */
static void uniform_box(struct sph_solver *sv, struct sph_config *cfg, double p0) {
  fixture_config(cfg);
  cfg->diffusion = SPH_DIFFUSION_NONE;
  box(sv, cfg, 0.01, 0.2, 0.2, NX, NY);
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < f->n; a++) f->rho[a] = rmn_eos_density(&sv->eos, p0);
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
}

static void test_uniform_pressure(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_config cfg;
  for (int sign = -1; sign <= 1; sign += 2) {
    struct sph_solver sv;
    const double p0 = sign * 412.5; /* Pa */
    uniform_box(&sv, &cfg, p0);
    struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
    const double *pk[SPH_NKINDS] = {sv.sys.part[0].p, sv.sys.part[1].p, sv.sys.part[2].p};
    const struct sph_op op = {&sv.sys, &sv.kernel, &sv.nb, 0};
    /* the first column (next to the left wall, n = +x), rows 2 .. NY − 3 (off the corners) */
    for (int j = 2; j < NY - 2; j++) {
      const size_t a = (size_t)(j * NX);
      assert_true(fabs(f->x[0][a] - 0.01) < 1e-12);
      double g[3], gp[3];
      sph_op_grad(&op, cfg.grad_k, pk, a, g);
      sph_op_grad_pressure(&op, cfg.grad_k, pk, a, NULL, 0, NULL, gp);
      const double ax_plain = -g[0] / f->rho[a], ax = sv.acc[0][a];
      assert_rel(ax, -gp[0] / f->rho[a], 1e-12);
      if (j == NY / 2)
        print_message("p = %+g Pa: a_x of the first column at rest: M(37) %+.4f, no pull %+.4f\n",
                      p0, ax_plain, ax);
      if (sign > 0) {
        /* No negative wall sum: the same bits as M(37); the defect pushes off the wall. */
        for (int c = 0; c < 3; c++) assert_true(g[c] == gp[c]);
        assert_true(ax > 0.5);
      } else {
        assert_true(ax_plain < -0.5); /* M(37): pulled into the wall by 2p times the defect */
        assert_true(ax > 0.5);        /* at rest: pulled towards its fluid neighbours */
        /* moving away from the wall (rows out of the floor's reach): held back as M(37) holds
         * it, the same bits */
        f->v[0][a] = 0.2;
        sph_op_grad_pressure(&op, cfg.grad_k, pk, a, NULL, 0, NULL, gp);
        if (j >= 4)
          for (int c = 0; c < 3; c++) assert_true(g[c] == gp[c]);
        /* moving towards it: not pulled */
        f->v[0][a] = -0.2;
        sph_op_grad_pressure(&op, cfg.grad_k, pk, a, NULL, 0, NULL, gp);
        assert_true(-gp[0] / f->rho[a] > 0.5);
        f->v[0][a] = 0.0;
      }
    }
    sph_solver_free(&sv);
  }
}

/* The pulls left out never do negative work: at a uniform negative pressure with random
 * velocities, v_a·(a_a − a_a^M37) ≤ 0 at every particle and < 0 at some; particles next to a wall
 * that move straight away from it keep M(37) to the last bit. normal: numerics.no_pull: normal
 * (sph_op.no_pull_normal), else radial. */
static void no_pull_power(int normal) {
  sabre_fp_traps_on();
  struct sph_config cfg;
  struct sph_solver sv;
  uniform_box(&sv, &cfg, -412.5);
  struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
  unsigned rng = 12345u;
  for (size_t a = 0; a < f->n; a++)
    for (int c = 0; c < 2; c++) {
      rng = rng * 1664525u + 1013904223u;
      f->v[c][a] = 0.3 * ((double)(rng >> 8) / (double)(1u << 24) - 0.5);
    }
  /* the first column out of the floor's and the lid's reach moves straight away from its wall */
  for (int j = 4; j < NY - 4; j++) {
    f->v[0][(size_t)(j * NX)] = 0.2;
    f->v[1][(size_t)(j * NX)] = 0.0;
  }
  const double *pk[SPH_NKINDS] = {sv.sys.part[0].p, sv.sys.part[1].p, sv.sys.part[2].p};
  const struct sph_op op = {&sv.sys, &sv.kernel, &sv.nb, normal};
  int cut = 0, kept = 0;
  double least = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    double g[3], gp[3];
    sph_op_grad(&op, cfg.grad_k, pk, a, g);
    sph_op_grad_pressure(&op, cfg.grad_k, pk, a, NULL, 0, NULL, gp);
    /* power of the difference of the accelerations −(gp − g)/ρ_a on v_a */
    double pw = 0.0;
    for (int c = 0; c < 3; c++) pw -= (gp[c] - g[c]) * f->v[c][a] / f->rho[a];
    const int walls =
        sv.nb.list[SPH_KIND_SEGMENT].offset[a + 1] > sv.nb.list[SPH_KIND_SEGMENT].offset[a];
    assert_true(pw <= 1e-12 * fabs(g[0] * f->v[0][a] + g[1] * f->v[1][a]) / f->rho[a]);
    if (pw < 0.0) cut++;
    if (walls && g[0] == gp[0] && g[1] == gp[1]) kept++;
    least = fmin(least, pw);
  }
  print_message(
      "no pull (%s): %d of %zu particles lose power (least %.3g W/kg), %d next to a wall "
      "keep M(37) exactly\n",
      normal ? "normal" : "radial", cut, f->n, least, kept);
  assert_true(cut > 10);
  assert_true(kept >= NY - 8);
  sph_solver_free(&sv);
}

static void test_no_pull_power(void **state) {
  (void)state;
  no_pull_power(0);
}

static void test_no_pull_power_normal(void **state) {
  (void)state;
  no_pull_power(1);
}

/* Flow along a wall in tension (docs/sph-solver.md §4, "Flow along a wall", item 3): with
 * numerics.no_pull: normal only the pull's part along each vertex's normal is left out, so a
 * first-column particle moving along the wall keeps M(37)'s tangential component to the last bit
 * (the side wall's vertex normals are ±x exactly) and is still not pulled into the wall; the
 * radial rule (the default) leaves out the vertices ahead of it, and the ones behind push it
 * back: its tangential acceleration opposes the motion. */
static void test_no_pull_tangential(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_config cfg;
  struct sph_solver sv;
  uniform_box(&sv, &cfg, -412.5);
  struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
  const double *pk[SPH_NKINDS] = {sv.sys.part[0].p, sv.sys.part[1].p, sv.sys.part[2].p};
  const struct sph_op normal = {&sv.sys, &sv.kernel, &sv.nb, 1};
  const struct sph_op radial = {&sv.sys, &sv.kernel, &sv.nb, 0};
  for (int j = 4; j < NY - 4; j++) { /* out of the floor's and the lid's reach */
    const size_t a = (size_t)(j * NX);
    for (int sign = -1; sign <= 1; sign += 2) {
      f->v[1][a] = sign * 0.2;
      double g[3], gn[3], gr[3];
      sph_op_grad(&normal, cfg.grad_k, pk, a, g);
      sph_op_grad_pressure(&normal, cfg.grad_k, pk, a, NULL, 0, NULL, gn);
      sph_op_grad_pressure(&radial, cfg.grad_k, pk, a, NULL, 0, NULL, gr);
      assert_true(gn[1] == g[1]);            /* along the wall: M(37) */
      assert_true(-gn[0] / f->rho[a] > 0.5); /* across it: not pulled in */
      assert_true(-gr[0] / f->rho[a] > 0.5);
      assert_true(sign * (-gr[1] + g[1]) / f->rho[a] < -0.1); /* radial: dragged */
      if (j == NY / 2 && sign > 0)
        print_message(
            "moving along the wall at -412.5 Pa: a_y normal %+.3g, radial %+.3g (M37 %+.3g), "
            "a_x normal %+.3f\n",
            -gn[1] / f->rho[a], -gr[1] / f->rho[a], -g[1] / f->rho[a], -gn[0] / f->rho[a]);
    }
    f->v[1][a] = 0.0;
  }
  sph_solver_free(&sv);
}

/* A viscous column collapsing in a tank (issue 5, at 2Δr): the top particles next to the left
 * wall must stay off it. */
static void test_contact_line(void **state) {
  (void)state;
  sabre_fp_traps_on();
  const double dr = 0.04;
  struct sph_config cfg;
  fixture_config(&cfg);
  cfg.c0 = 40.0;
  cfg.nu = 0.01;
  cfg.gravity[1] = -9.81;
  cfg.hydrostatic = 1;
  cfg.t_end = 0.5;
  struct sph_solver sv;
  box(&sv, &cfg, dr, 2.2, 1.2, 12, 25);
  const struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
  char msg[512];
  double xmin = INFINITY;
  int rc = 0;
  while (sv.time < cfg.t_end * (1 - 1e-12) && rc == 0) {
    rc = sph_solver_step(&sv, cfg.t_end - sv.time, msg, sizeof msg);
    for (size_t a = 0; a < f->n; a++)
      if (f->x[1][a] > 0.5) xmin = fmin(xmin, f->x[0][a]);
  }
  print_message(
      "contact line: t = %.4f s after %ld steps, closest approach to the left wall "
      "above y = 0.5 m: %.3f dr%s%s\n",
      sv.time, sv.step, xmin / dr, rc ? ": " : "", rc ? msg : "");
  assert_int_equal(rc, 0);
  assert_true(xmin > 0.6 * dr);
  sph_solver_free(&sv);
}

/* numerics.wall_impedance: the pressure gradient with the impedance equals the plain one with
 * every wall value of the particle's pairs raised by Z_a max(0, −u_n) (u_n its normal velocity
 * relative to that element); at rest, or moving along the walls, it is the same bits as without;
 * an approaching particle is pushed off harder, a receding one sees no change. */
/* The NX × NY box, Δr = 0.01 m, inviscid, without diffusion, at rest under gravity with the
 * hydrostatic pressure and the wall impedance of the given form, evaluated. */
static void impedance_box(struct sph_solver *sv, struct sph_config *cfg, int form) {
  fixture_config(cfg);
  cfg->diffusion = SPH_DIFFUSION_NONE;
  cfg->gravity[1] = -9.81;
  cfg->hydrostatic = 1;
  cfg->wall_impedance = form;
  box(sv, cfg, 0.01, 0.2, 0.2, NX, NY);
  sph_solver_evaluate(sv);
}

static void test_wall_impedance(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_config cfg;
  struct sph_solver sv;
  impedance_box(&sv, &cfg, SPH_IMPEDANCE_ACOUSTIC);
  struct sph_system *s = &sv.sys;
  struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const struct sph_op op = {s, &sv.kernel, &sv.nb, 0};
  const double *pk[SPH_NKINDS] = {s->part[0].p, s->part[1].p, s->part[2].p};
  const size_t a = (size_t)(4 * NX); /* first column, fifth row: sees the left wall only */
  const struct sph_wall_impedance imp = {sv.impedance, 0.0}; /* the acoustic form */
  double g0[3], g1[3];
  /* at rest */
  sph_op_grad_pressure(&op, cfg.grad_k, pk, a, NULL, 0, NULL, g0);
  sph_op_grad_pressure(&op, cfg.grad_k, pk, a, &imp, 0, NULL, g1);
  for (int c = 0; c < 3; c++) assert_true(g0[c] == g1[c]);
  /* along the wall (n = +x): no change */
  f->v[1][a] = 0.3;
  sph_op_grad_pressure(&op, cfg.grad_k, pk, a, &imp, 0, NULL, g1);
  for (int c = 0; c < 3; c++) assert_true(g0[c] == g1[c]);
  /* receding from it: no change */
  f->v[0][a] = 0.2;
  sph_op_grad_pressure(&op, cfg.grad_k, pk, a, &imp, 0, NULL, g1);
  for (int c = 0; c < 3; c++) assert_true(g0[c] == g1[c]);
  /* approaching it obliquely: the identity with raised wall values, and a harder push */
  f->v[0][a] = -0.2;
  sph_op_grad_pressure(&op, cfg.grad_k, pk, a, &imp, 0, NULL, g1);
  double *praised[SPH_NKINDS];
  for (int k = 0; k < SPH_NKINDS; k++) {
    const size_t n = s->part[k].n;
    praised[k] = malloc((n + 1) * sizeof(double));
    for (size_t i = 0; i < n; i++) praised[k][i] = s->part[k].p[i];
  }
  for (int k = SPH_KIND_VERTEX; k <= SPH_KIND_SEGMENT; k++) {
    const struct sph_parts *pw = &s->part[k];
    const struct sph_nlist *nl = &sv.nb.list[k];
    for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
      const size_t j = nl->index[q];
      double un = 0.0, nn = 0.0;
      for (int c = 0; c < 3; c++) {
        un += (f->v[c][a] - pw->v[c][j]) * pw->normal[c][j];
        nn += pw->normal[c][j] * pw->normal[c][j];
      }
      un /= sqrt(nn);
      assert_true(fabs(un + 0.2) < 1e-12); /* the left wall's elements only */
      praised[k][j] = s->part[k].p[j] - sv.impedance[a] * un;
    }
  }
  const double *pr[SPH_NKINDS] = {praised[0], praised[1], praised[2]};
  double g2[3];
  sph_op_grad_pressure(&op, cfg.grad_k, pr, a, NULL, 0, NULL, g2);
  for (int c = 0; c < 2; c++) assert_rel(g1[c], g2[c], 1e-13);
  const double push0 = -g0[0] / f->rho[a], push1 = -g1[0] / f->rho[a];
  print_message(
      "wall impedance: a_x of a particle Δr from the wall at rest %+.3f m/s², "
      "approaching at 0.2 m/s %+.3f m/s² (Z = %.4g kg/m²/s)\n",
      push0, push1, sv.impedance[a]);
  assert_true(push1 > push0 + 100.0);
  for (int k = 0; k < SPH_NKINDS; k++) free(praised[k]);
  sph_solver_free(&sv);
}

/* numerics.wall_impedance: contact. The term acts on a particle closing in on an element within
 * reach, weighted by ω = 1 − d/reach (d its distance from the element's plane): with the default
 * reach Δr the first column (Δr from the left wall, at the reach) gets the plain result (to
 * 10⁻¹², the weight 0 up to round-off), the second and third the same bits; with a reach of 4Δr
 * columns 1–3 get 3/4, 1/2 and 1/4 of the acoustic form's raise (the pressure gradient is linear in
 * the raised wall values: g = g_plain + ω (g_acoustic − g_plain)). */
static void test_wall_impedance_contact(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_config cfg;
  struct sph_solver sv;
  impedance_box(&sv, &cfg, SPH_IMPEDANCE_CONTACT);
  assert_true(cfg.wall_impedance_reach == 1.0); /* as the case file's default (fixture) */
  struct sph_system *s = &sv.sys;
  struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const double dr = s->dr;
  const struct sph_op op = {s, &sv.kernel, &sv.nb, 0};
  const double *pk[SPH_NKINDS] = {s->part[0].p, s->part[1].p, s->part[2].p};
  const struct sph_wall_impedance acoustic = {sv.impedance, 0.0};
  const struct sph_wall_impedance near = {sv.impedance, cfg.wall_impedance_reach * dr};
  const struct sph_wall_impedance far = {sv.impedance, 4.0 * dr};
  for (int col = 0; col < 3; col++) { /* fifth row, columns 1–3, approaching the left wall */
    const size_t a = (size_t)(4 * NX + col);
    f->v[0][a] = -0.2;
    double g0[3], ga[3], gn[3], gf[3];
    sph_op_grad_pressure(&op, cfg.grad_k, pk, a, NULL, 0, NULL, g0);
    sph_op_grad_pressure(&op, cfg.grad_k, pk, a, &acoustic, 0, NULL, ga);
    sph_op_grad_pressure(&op, cfg.grad_k, pk, a, &near, 0, NULL, gn);
    sph_op_grad_pressure(&op, cfg.grad_k, pk, a, &far, 0, NULL, gf);
    assert_true(fabs(ga[0] - g0[0]) > 1e-3 * fabs(g0[0])); /* the acoustic form acts on each */
    const double omega = 0.75 - 0.25 * col, scale = fabs(ga[0] - g0[0]);
    for (int c = 0; c < 2; c++) {
      if (col == 0) assert_true(fabs(gn[c] - g0[c]) <= 1e-12 * scale);
      if (col > 0) assert_true(gn[c] == g0[c]);
      assert_true(fabs(gf[c] - (g0[c] + omega * (ga[c] - g0[c]))) <= 1e-12 * scale);
    }
    print_message(
        "contact impedance, column %d: a_x plain %+.3f, acoustic %+.3f, reach "
        "dr %+.3f, reach 4 dr %+.3f m/s^2\n",
        col + 1, -g0[0] / f->rho[a], -ga[0] / f->rho[a], -gn[0] / f->rho[a], -gf[0] / f->rho[a]);
    f->v[0][a] = 0.0;
  }
  /* Behind an element's plane the weight is 0: with the segments' plane distances of a pair list
   * negated, the first column approaching obliquely gets the raise of its vertex pairs only,
   * each by ω = 1 − d/reach of its own plane distance (the identity with raised vertex values). */
  const size_t a = (size_t)(4 * NX);
  f->v[0][a] = -0.2;
  f->v[1][a] = 0.1;
  const struct sph_nlist *ls = &sv.nb.list[SPH_KIND_SEGMENT], *lv = &sv.nb.list[SPH_KIND_VERTEX];
  for (size_t q = ls->offset[a]; q < ls->offset[a + 1]; q++) sv.nb.dist_as[q] *= -1.0;
  double gb[3], g2[3];
  sph_op_grad_pressure(&op, cfg.grad_k, pk, a, &far, 0, NULL, gb);
  for (size_t q = ls->offset[a]; q < ls->offset[a + 1]; q++) sv.nb.dist_as[q] *= -1.0;
  const struct sph_parts *pv = &s->part[SPH_KIND_VERTEX];
  double *raised = malloc((pv->n + 1) * sizeof(double));
  for (size_t i = 0; i < pv->n; i++) raised[i] = pv->p[i];
  int weighted = 0;
  for (size_t q = lv->offset[a]; q < lv->offset[a + 1]; q++) {
    const size_t j = lv->index[q];
    double un = 0.0, d = 0.0, nn = 0.0;
    for (int c = 0; c < 3; c++) {
      un += (f->v[c][a] - pv->v[c][j]) * pv->normal[c][j];
      d += (f->x[c][a] - pv->x[c][j]) * pv->normal[c][j];
      nn += pv->normal[c][j] * pv->normal[c][j];
    }
    un /= sqrt(nn);
    d /= sqrt(nn);
    const double w = d > 0.0 ? fmax(0.0, 1.0 - d / far.reach) : 0.0;
    if (un < 0.0 && w > 0.0 && w < 1.0) weighted++;
    if (un < 0.0) raised[j] -= w * sv.impedance[a] * un;
  }
  assert_true(weighted >= 3);
  const double *pr[SPH_NKINDS] = {pk[SPH_KIND_FLUID], raised, pk[SPH_KIND_SEGMENT]};
  sph_op_grad_pressure(&op, cfg.grad_k, pr, a, NULL, 0, NULL, g2);
  for (int c = 0; c < 2; c++) assert_rel(gb[c], g2[c], 1e-13);
  print_message(
      "contact impedance behind the segments' planes: a = (%+.3f, %+.3f) m/s^2, %d "
      "vertex pairs weighted\n",
      -gb[0] / f->rho[a], -gb[1] / f->rho[a], weighted);
  free(raised);
  sph_solver_free(&sv);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_uniform_pressure),       cmocka_unit_test(test_no_pull_power),
      cmocka_unit_test(test_no_pull_power_normal),   cmocka_unit_test(test_no_pull_tangential),
      cmocka_unit_test(test_contact_line),           cmocka_unit_test(test_wall_impedance),
      cmocka_unit_test(test_wall_impedance_contact),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
