/*
 * Walls joined across a periodic boundary (docs/sph-geometry.md §3): in a channel periodic in x
 * with a 1D initial state, every lattice column must see the same walls, so every per-particle
 * quantity is the same in every column to round-off, the column on the periodic seam included:
 * γ_a, ∇γ_a, the fluid–segment rows and Σ_s ∇γ_as, the wall term of the pressure gradient
 * Σ_s (p_s + p_a) ∇γ_as, the vertex part of the density sum Σ_v m_v w_av, density, pressure and
 * acceleration; along each plate the vertex masses, pressures and densities and the segment values
 * are uniform, with one vertex and one segment per Δr of period (no duplicate at the seam). Built
 * through the case path (generator, periodic identification, fill with first_row = 1, which puts
 * a column on the seam itself), with the channel at the origin and shifted off it.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "operators/pair.h"
#include "sabre/common.h"
#include "sabre/sph_solver.h"
#include "testutil.h"

#define NX 12 /* columns: the period must exceed twice the search reach, 9.8 dr here */
#define TOL 1e-11

/* Channel of NX columns of dr = 0.05 m between plates 0.45 m apart, lower-left corner at lo. */
static void setup(double lo_x, double lo_y, struct sph_solver *sv) {
  const double dr = 0.05, len = NX * dr, height = 0.45;
  char text[2048], err[512];
  snprintf(text, sizeof text,
           "geometry:\n"
           "  dimension: 2\n"
           "  dr: %.17g\n"
           "  first_row: 1\n"
           "  periodic: [x]\n"
           "  walls: [{type: channel, lo: [%.17g, %.17g], hi: [%.17g, %.17g]}]\n"
           "  fluid: [{type: box, lo: [%.17g, %.17g], hi: [%.17g, %.17g]}]\n"
           "fluid: {rho0: 1000, c0: 10}\n"
           "numerics: {diffusion: none, gradient_k: 0}\n"
           "initial:\n"
           "  velocity: [0, 0.7*sin(2*pi*(y - %.17g)/%.17g)]\n"
           "  pressure: 150*cos(3.1*(y - %.17g))\n"
           "time: {end: 1}\n",
           dr, lo_x, lo_y, lo_x + len, lo_y + height, lo_x, lo_y, lo_x + len, lo_y + height, lo_y,
           height, lo_y);
  struct cmn_case *c = cmn_case_parse(text, "case.yaml", err, sizeof err);
  if (!c) fail_msg("%s", err);
  struct sph_geometry g;
  sph_geometry_read(&g, c);
  struct sph_config cfg;
  assert_int_equal(sph_config_read(&cfg, c, g.dim), 0);
  assert_int_equal(cmn_case_check_unused(c), 0);
  struct sph_system s;
  sph_system_from_geometry(&s, &g);
  sph_solver_init(sv, &cfg, &s, NULL, NULL);
  sph_system_free(&s);
  sph_geometry_free(&g);
  cmn_case_free(c);
}

/* Column and row of each fluid particle from its lattice position (call at t = 0: the solver
 * keeps the particles' order). */
static void lattice(const struct sph_solver *sv, int *col, int *row, int *nrow) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const struct sph_domain *d = &sv->sys.domain;
  const double dr = sv->sys.dr;
  *nrow = 0;
  for (size_t a = 0; a < f->n; a++) {
    long i = lround((f->x[0][a] - d->lo[0]) / dr - 1.0), j = lround((f->x[1][a] - d->lo[1]) / dr);
    col[a] = (int)(((i % NX) + NX) % NX);
    row[a] = (int)j;
    if ((int)j > *nrow) *nrow = (int)j;
  }
  assert_int_equal((size_t)NX * (size_t)*nrow, f->n);
}

enum {
  Q_GAMMA,
  Q_GGX,
  Q_GGY,
  Q_NSEG,
  Q_SUMG,
  Q_NVERT,
  Q_NFLUID,
  Q_WALLP,
  Q_VSUM,
  Q_RHO,
  Q_P,
  Q_AX,
  Q_AY,
  Q_Y,
  Q_VY,
  NQ
};
static const char *const qname[NQ] = {"gamma",
                                      "grad_gamma_x",
                                      "grad_gamma_y",
                                      "segment neighbours",
                                      "sum grad_gamma_as",
                                      "vertex neighbours",
                                      "fluid neighbours",
                                      "wall pressure term",
                                      "vertex density sum",
                                      "rho",
                                      "p",
                                      "acc_x",
                                      "acc_y",
                                      "y",
                                      "v_y"};

/* Every quantity of a particle equals that of the particle of the same row in column 0, to TOL
 * times the quantity's largest magnitude over all particles; x components are 0 to that. */
static void check_columns(struct sph_solver *sv, const int *col, const int *row, int nrow,
                          const char *when) {
  sph_solver_evaluate(sv);
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID], *v = &s->part[SPH_KIND_VERTEX];
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT];
  const struct sph_nbrs *nb = &sv->nb;
  const struct sph_nlist *ls = &nb->list[SPH_KIND_SEGMENT], *lv = &nb->list[SPH_KIND_VERTEX];
  const size_t n = f->n;
  const double pscale = sv->cfg.rho0 * sv->cfg.c0 * sv->cfg.c0;
  double(*q)[NQ] = calloc(n, sizeof *q), scale[NQ] = {0};
  size_t *ref = malloc((size_t)(nrow + 1) * sizeof *ref);
  for (size_t a = 0; a < n; a++) {
    double sumg = 0.0, wallp = 0.0, vsum = 0.0;
    for (size_t p = ls->offset[a]; p < ls->offset[a + 1]; p++) {
      for (size_t r = ls->offset[a]; r < p; r++)
        if (ls->index[r] == ls->index[p])
          fail_msg("%s: particle %zu sees a segment twice", when, a);
      sumg += nb->grad_gamma_as[1][p];
      wallp += (sg->p[ls->index[p]] + f->p[a]) * nb->grad_gamma_as[1][p];
    }
    for (size_t p = lv->offset[a]; p < lv->offset[a + 1]; p++) {
      struct sph_pair pr;
      if (sph_pair_eval(&sv->kernel, s, f, a, v, lv->index[p], &pr))
        vsum += v->mass[lv->index[p]] * pr.w;
    }
    const double vals[NQ] = {
        f->gamma[a],
        f->grad_gamma[0][a],
        f->grad_gamma[1][a],
        (double)(ls->offset[a + 1] - ls->offset[a]),
        sumg,
        (double)(lv->offset[a + 1] - lv->offset[a]),
        (double)(nb->list[SPH_KIND_FLUID].offset[a + 1] - nb->list[SPH_KIND_FLUID].offset[a]),
        wallp,
        vsum,
        f->rho[a],
        f->p[a],
        sv->acc[0][a],
        sv->acc[1][a],
        f->x[1][a],
        f->v[1][a]};
    memcpy(q[a], vals, sizeof vals);
    for (int k = 0; k < NQ; k++) scale[k] = fmax(scale[k], fabs(vals[k]));
    if (col[a] == 0) ref[row[a]] = a;
  }
  scale[Q_GGX] = scale[Q_GGY];
  scale[Q_AX] = scale[Q_AY];
  for (size_t a = 0; a < n; a++) {
    assert_rel(q[a][Q_SUMG], q[a][Q_GGY], 1e-13);
    for (int k = 0; k < NQ; k++) {
      const double expected = k == Q_GGX || k == Q_AX ? 0.0 : q[ref[row[a]]][k];
      if (!(fabs(q[a][k] - expected) <= TOL * scale[k]))
        fail_msg(
            "%s: %s of row %d, column %d (x = %.6f) is %.17g, expected %.17g (column 0 of the "
            "row; 0 for an x component; scale %g)",
            when, qname[k], row[a], col[a], f->x[0][a], q[a][k], expected, scale[k]);
    }
  }
  /* Each plate: NX vertices and NX segments, uniform values. */
  const double ymid = 0.5 * (s->domain.lo[1] + s->domain.hi[1]);
  for (int wall = 0; wall < 2; wall++) {
    size_t nv = 0, ns = 0, v0 = SIZE_MAX, s0 = SIZE_MAX;
    for (size_t i = 0; i < v->n; i++) {
      if ((v->x[1][i] > ymid) != wall) continue;
      nv++;
      if (v0 == SIZE_MAX) v0 = i;
      assert_rel(v->mass[i], v->mass[v0], TOL);
      assert_rel(v->rho[i], v->rho[v0], TOL);
      assert_abs(v->p[i], v->p[v0], TOL * pscale);
      assert_int_equal(nb->vf.offset[i + 1] - nb->vf.offset[i],
                       nb->vf.offset[v0 + 1] - nb->vf.offset[v0]);
    }
    for (size_t j = 0; j < sg->n; j++) {
      if ((sg->x[1][j] > ymid) != wall) continue;
      ns++;
      if (s0 == SIZE_MAX) s0 = j;
      assert_rel(sg->measure[j], s->dr, 1e-12);
      assert_rel(sg->rho[j], sg->rho[s0], TOL);
      assert_abs(sg->p[j], sg->p[s0], TOL * pscale);
    }
    assert_int_equal(nv, NX);
    assert_int_equal(ns, NX);
  }
  free(q);
  free(ref);
}

static void run_channel(double lo_x, double lo_y) {
  struct sph_solver sv;
  setup(lo_x, lo_y, &sv);
  const size_t n = sv.sys.part[SPH_KIND_FLUID].n;
  int *col = malloc(n * sizeof *col), *row = malloc(n * sizeof *row), nrow;
  lattice(&sv, col, row, &nrow);
  check_columns(&sv, col, row, nrow, "t = 0");
  char msg[1024], when[64];
  for (int step = 1; step <= 12; step++) {
    if (sph_solver_step(&sv, INFINITY, msg, sizeof msg) != 0) fail_msg("%s", msg);
    if (step % 4 == 0) {
      snprintf(when, sizeof when, "step %d", step);
      check_columns(&sv, col, row, nrow, when);
    }
  }
  free(col);
  free(row);
  sph_solver_free(&sv);
}

static void test_columns_at_origin(void **state) {
  (void)state;
  run_channel(0.0, 0.0);
}

static void test_columns_shifted(void **state) {
  (void)state;
  run_channel(0.3183, -0.127);
}

/* A whole row failing at once (what a 1D flow does) is reported as such: the message names the
 * lowest index and counts every failing particle. */
static void test_failure_counts_the_row(void **state) {
  (void)state;
  struct sph_solver sv;
  setup(0.0, 0.0, &sv);
  struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
  int *col = malloc(f->n * sizeof *col), *row = malloc(f->n * sizeof *row), nrow;
  lattice(&sv, col, row, &nrow);
  size_t lowest = SIZE_MAX;
  for (size_t a = 0; a < f->n; a++)
    if (row[a] == 3) {
      f->rho[a] *= 0.3;
      if (lowest == SIZE_MAX) lowest = a;
    }
  sph_solver_sync(&sv);
  char msg[1024], expect[128];
  assert_int_equal(sph_solver_step(&sv, INFINITY, msg, sizeof msg), -1);
  print_message("%s\n", msg);
  assert_non_null(strstr(msg, "density outside"));
  snprintf(expect, sizeof expect, "(index %zu)", lowest);
  assert_non_null(strstr(msg, expect));
  snprintf(expect, sizeof expect, "%d of %zu fluid particles fail", NX, f->n);
  assert_non_null(strstr(msg, expect));
  free(col);
  free(row);
  sph_solver_free(&sv);
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_columns_at_origin),
      cmocka_unit_test(test_columns_shifted),
      cmocka_unit_test(test_failure_counts_the_row),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
