/*
 * Boundary-corrected operators (docs/sph-solver.md §2): Grad^{γ,k} M(37), Div^{γ,k} M(38),
 * Lap^γ J(8) against exact derivatives of linear and quadratic fields on a 2D lattice.
 *
 * Away from walls (γ = 1) the continuous SPH operators are exact for quadratic fields (the kernel
 * is even), so the discrete error is the lattice quadrature error: small at h/Δr = 2 and ~100×
 * smaller at h/Δr = 4 (same h). Near a flat wall (channel periodic in x) the wall terms keep the
 * continuous operators exact; the discrete error is then dominated by the truncated quadrature
 * next to the wall and must drop by ≥ 3 from h/Δr = 2 to 4. Fields vanish on the wall so that the
 * zeroth-order defect Σ_b V_b ∇w_ab − ∇γ_a (measured separately) does not mask the first-order
 * terms. Tolerances are the measured errors with a margin of about 1.5.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "solver_fixture.h"
#include "testutil.h"

struct fields {
  double *f[SPH_NKINDS], *B[SPH_NKINDS][3], *U[SPH_NKINDS][3], *beta[SPH_NKINDS], *flux[3];
};

/* f = quadratic or linear scalar, B = vector field, U_x = Laplacian test field. */
struct field_def {
  double (*f)(const double *x, double *grad);
  void (*B)(const double *x, double *b, double *div);
  double (*U)(const double *x, double *lap, double *dudy);
};

static double f_lin(const double *x, double *g) {
  g[0] = 2.385;
  g[1] = -1.27;
  return 2.385 * x[0] - 1.27 * x[1] + 0.5;
}
static double f_quad(const double *x, double *g) {
  g[0] = 2 * x[0] + 2.385 * x[1];
  g[1] = 2.385 * x[0] - 1.4 * x[1];
  return x[0] * x[0] + 2.385 * x[0] * x[1] - 0.7 * x[1] * x[1];
}
static void b_quad(const double *x, double *b, double *div) {
  b[0] = 1.3 * x[0] + 0.4 * x[1] + 0.3 * x[0] * x[0];
  b[1] = -0.2 * x[0] + 0.9 * x[1] - 0.45 * x[1] * x[1] + x[0] * x[1];
  *div = 1.3 + 0.6 * x[0] + 0.9 - 0.9 * x[1] + x[0];
}
static double u_quad(const double *x, double *lap, double *dudy) {
  *lap = 2.0 * 0.81 - 2.0 * 0.37;
  *dudy = -0.74 * x[1] + 1.1 * x[0];
  return 0.81 * x[0] * x[0] - 0.37 * x[1] * x[1] + 1.1 * x[0] * x[1];
}
/* Near the wall y = 0: fields vanishing there, functions of y only (periodic in x). */
static double f_wall(const double *x, double *g) {
  g[0] = 0.0;
  g[1] = 2.385 + 2 * 1.7 * x[1];
  return 2.385 * x[1] + 1.7 * x[1] * x[1];
}
static void b_wall(const double *x, double *b, double *div) {
  b[0] = 0.4 * x[1];
  b[1] = 0.9 * x[1] - 0.6 * x[1] * x[1];
  *div = 0.9 - 1.2 * x[1];
}
static double f_wall_lin(const double *x, double *g) {
  g[0] = 0.0;
  g[1] = 2.385;
  return 2.385 * x[1];
}
static void b_wall_lin(const double *x, double *b, double *div) {
  b[0] = 0.4 * x[1];
  b[1] = 0.9 * x[1];
  *div = 0.9;
}
/* U = y²: zero wall flux, so the Laplacian's first-order terms are not masked by the
 * zeroth-order defect times ∂U/∂n (test_constant_defect). */
static double u_wall(const double *x, double *lap, double *dudy) {
  *lap = 2.0;
  *dudy = 2.0 * x[1];
  return x[1] * x[1];
}

static void fill(const struct sph_solver *sv, const struct field_def *d, struct fields *F) {
  memset(F, 0, sizeof *F);
  const struct sph_system *s = &sv->sys;
  for (int k = 0; k < SPH_NKINDS; k++) {
    size_t n = s->part[k].n + 1;
    F->f[k] = calloc(n, sizeof(double));
    F->beta[k] = calloc(n, sizeof(double));
    for (int c = 0; c < 3; c++) {
      F->B[k][c] = calloc(n, sizeof(double));
      F->U[k][c] = calloc(n, sizeof(double));
    }
    for (size_t i = 0; i < s->part[k].n; i++) {
      double x[3] = {s->part[k].x[0][i], s->part[k].x[1][i], 0.0}, g[3], b[3], div, lap, dudy;
      F->f[k][i] = d->f(x, g);
      d->B(x, b, &div);
      F->B[k][0][i] = b[0];
      F->B[k][1][i] = b[1];
      F->U[k][0][i] = d->U(x, &lap, &dudy);
      F->beta[k][i] = 1.0;
    }
  }
  /* Wall flux of J(8): β_s ∂U/∂n|_s + β_a ∂U/∂n|_a with n = (0, ±1) on the channel walls. */
  const struct sph_nlist *nl = &sv->nb.list[SPH_KIND_SEGMENT];
  const struct sph_parts *fl = &s->part[SPH_KIND_FLUID], *sg = &s->part[SPH_KIND_SEGMENT];
  for (int c = 0; c < 3; c++) F->flux[c] = calloc(sv->nb.cap_pairs + 1, sizeof(double));
  for (size_t a = 0; a < fl->n; a++)
    for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
      size_t j = nl->index[q];
      double xs[3] = {sg->x[0][j], sg->x[1][j], 0}, xa[3] = {fl->x[0][a], fl->x[1][a], 0};
      double lap, ds, da;
      d->U(xs, &lap, &ds);
      d->U(xa, &lap, &da);
      F->flux[0][q] = (ds + da) * sg->normal[1][j];
    }
}

static void release(struct fields *F) {
  for (int k = 0; k < SPH_NKINDS; k++) {
    free(F->f[k]);
    free(F->beta[k]);
    for (int c = 0; c < 3; c++) {
      free(F->B[k][c]);
      free(F->U[k][c]);
    }
  }
  for (int c = 0; c < 3; c++) free(F->flux[c]);
}

struct errors {
  double grad, div, lap;
};

/* Max relative errors over the fluid particles with lo ≤ distance-to-edge < hi (in units of h). */
static struct errors measure(const struct sph_solver *sv, const struct field_def *d, double k,
                             int walls, double lo, double hi) {
  struct fields F;
  fill(sv, d, &F);
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *fl = &s->part[SPH_KIND_FLUID];
  const struct sph_op op = {s, &sv->kernel, &sv->nb, 0};
  struct errors e = {0, 0, 0};
  for (size_t a = 0; a < fl->n; a++) {
    double x[3] = {fl->x[0][a], fl->x[1][a], 0.0};
    double dist = x[1];
    if (!walls) {
      for (int c = 0; c < 2; c++)
        dist = fmin(dist, fmin(x[c] - s->domain.lo[c], s->domain.hi[c] - x[c]));
    }
    if (dist < lo * s->h || dist >= hi * s->h) continue;
    double g[3], ge[3], b[3], dive, lape, dudy;
    d->f(x, ge);
    d->B(x, b, &dive);
    d->U(x, &lape, &dudy);
    sph_op_grad(&op, k, (const double *const *)F.f, a, g);
    double div = sph_op_div(&op, k, (const double *const(*)[3])F.B, a);
    double lap[3];
    sph_op_lap(&op, (const double *const *)F.beta, (const double *const(*)[3])F.U,
               walls ? (const double *const *)F.flux : NULL, a, lap);
    e.grad = fmax(e.grad, hypot(g[0] - ge[0], g[1] - ge[1]) / hypot(ge[0], ge[1]));
    e.div = fmax(e.div, fabs(div - dive) / fmax(fabs(dive), 0.5));
    e.lap = fmax(e.lap, fabs(lap[0] - lape) / fabs(lape));
  }
  release(&F);
  return e;
}

static void setup(struct sph_solver *sv, int n, double h_over_dr, enum fixture_walls walls) {
  struct sph_system s;
  fixture_lattice(&s, n, n, 1.0 / n, h_over_dr, walls);
  struct sph_config cfg;
  fixture_config(&cfg);
  sph_solver_init(sv, &cfg, &s, NULL, NULL);
  sph_system_free(&s);
}

static void test_interior(void **state) {
  (void)state;
  sabre_fp_traps_on();
  const struct field_def lin = {f_lin, b_quad, u_quad}, quad = {f_quad, b_quad, u_quad};
  struct sph_solver a, b;
  setup(&a, 24, 2.0, FIX_NONE);
  setup(&b, 48, 4.0, FIX_NONE); /* same h */
  for (int k = 0; k <= 1; k++) {
    struct errors e2 = measure(&a, &lin, k, 0, 2.2, 99), e4 = measure(&b, &lin, k, 0, 2.2, 99);
    struct errors q2 = measure(&a, &quad, k, 0, 2.2, 99), q4 = measure(&b, &quad, k, 0, 2.2, 99);
    print_message(
        "interior k=%d: h/dr=2 grad %.2e/%.2e div %.2e lap %.2e; h/dr=4 grad %.2e/%.2e "
        "div %.2e lap %.2e\n",
        k, e2.grad, q2.grad, e2.div, e2.lap, e4.grad, q4.grad, e4.div, e4.lap);
    assert_true(e2.grad < 1.2e-3 && q2.grad < 1.2e-3 && e2.div < 1.2e-3 && e2.lap < 1.5e-3);
    assert_true(e4.grad < 1e-5 && q4.grad < 1e-5 && e4.div < 1e-5 && e4.lap < 1.5e-5);
  }
  sph_solver_free(&a);
  sph_solver_free(&b);
}

static void test_flat_wall(void **state) {
  (void)state;
  sabre_fp_traps_on();
  const struct field_def lin = {f_wall_lin, b_wall_lin, u_wall};
  const struct field_def quad = {f_wall, b_wall, u_wall};
  struct sph_solver a, b, c;
  setup(&a, 24, 2.0, FIX_CHANNEL);
  setup(&b, 48, 4.0, FIX_CHANNEL); /* same h as a */
  setup(&c, 96, 4.0, FIX_CHANNEL); /* h / 2 */
  for (int k = 0; k <= 1; k++) {
    /* Linear fields (and the Laplacian of a quadratic): exact in the continuous form, the
     * discrete error is quadrature and drops with h/Δr. */
    struct errors e2 = measure(&a, &lin, k, 1, 0.0, 2.0);
    struct errors e4 = measure(&b, &lin, k, 1, 0.0, 2.0);
    print_message(
        "wall, linear, k=%d: h/dr=2 grad %.2e div %.2e lap %.2e; h/dr=4 grad %.2e div "
        "%.2e lap %.2e\n",
        k, e2.grad, e2.div, e2.lap, e4.grad, e4.div, e4.lap);
    assert_true(e2.grad < 0.04 && e2.div < 0.04 && e2.lap < 0.04);
    assert_true(e4.grad < e2.grad / 3 && e4.div < e2.div / 3 && e4.lap < e2.lap / 3);
    /* Quadratic fields: the truncated kernel averages ∇f off-centre, an O(h) error. */
    struct errors q1 = measure(&b, &quad, k, 1, 0.0, 2.0);
    struct errors q2 = measure(&c, &quad, k, 1, 0.0, 2.0);
    print_message("wall, quadratic, k=%d: h grad %.2e div %.2e; h/2 grad %.2e div %.2e\n", k,
                  q1.grad, q1.div, q2.grad, q2.div);
    assert_true(q1.grad < 0.08 && q1.div < 0.08);
    assert_true(q2.grad < 0.65 * q1.grad && q2.div < 0.65 * q1.div);
  }
  /* Without the wall terms the same operators are wrong by O(1) next to the wall. */
  struct fields F;
  fill(&a, &quad, &F);
  const struct sph_op op = {&a.sys, &a.kernel, &a.nb, 0};
  double lap[3];
  sph_op_lap(&op, (const double *const *)F.beta, (const double *const(*)[3])F.U, NULL, 0, lap);
  assert_true(fabs(lap[0] - 2.0) > 0.3);
  release(&F);
  sph_solver_free(&a);
  sph_solver_free(&b);
  sph_solver_free(&c);
}

/* Zeroth-order defect: Grad^{γ,0}(1) = (2/γ_a)(Σ_b V_b ∇w_ab − ∇γ_a) is not zero next to a wall
 * (the lattice quadrature of ∫∇w against the exact ∇γ); measured, and shown to shrink with h/Δr. */
static void test_constant_defect(void **state) {
  (void)state;
  sabre_fp_traps_on();
  double worst[2] = {0, 0};
  for (int r = 0; r < 2; r++) {
    struct sph_solver sv;
    setup(&sv, 24 * (r + 1), 2.0 * (r + 1), FIX_CHANNEL);
    const struct sph_parts *fl = &sv.sys.part[SPH_KIND_FLUID];
    double *one[SPH_NKINDS];
    for (int k = 0; k < SPH_NKINDS; k++) {
      one[k] = malloc((sv.sys.part[k].n + 1) * sizeof(double));
      for (size_t i = 0; i < sv.sys.part[k].n; i++) one[k][i] = 1.0;
    }
    const struct sph_op op = {&sv.sys, &sv.kernel, &sv.nb, 0};
    for (size_t a = 0; a < fl->n; a++) {
      double g[3];
      sph_op_grad(&op, 0.0, (const double *const *)one, a, g);
      worst[r] = fmax(worst[r], hypot(g[0], g[1]) * sv.sys.h);
      if (fl->gamma[a] == 1.0) assert_true(hypot(g[0], g[1]) * sv.sys.h < 1e-12);
    }
    for (int k = 0; k < SPH_NKINDS; k++) free(one[k]);
    sph_solver_free(&sv);
  }
  print_message("max |Grad(1)| h near the wall: h/dr=2 %.3e, h/dr=4 %.3e\n", worst[0], worst[1]);
  assert_true(worst[0] < 0.12 && worst[1] < worst[0] / 2);
}

/* The sign of that defect on the first row decides whether a wall attracts or repels fluid at
 * constant pressure: −Grad(p)/ρ must point into the fluid. First row at Δr/2 from the wall (vertex
 * layer fitted to φ ≈ −0.03): Grad^{γ,0}(1)·n > 0, the wall attracts the row (dam-break fronts sink
 * into the floor); first row at Δr (φ ≈ 0.6, the vertices carry the half cell next to the wall):
 * Grad·n < 0, the wall repels. docs/sph-solver.md §7. */
static void test_first_row_sign(void **state) {
  (void)state;
  sabre_fp_traps_on();
  for (int r = 0; r < 2; r++) {
    struct sph_system s;
    fixture_lattice_offset(&s, 24, 24, 1.0 / 24, 2.0, FIX_CHANNEL, r ? 1.0 : 0.5);
    struct sph_config cfg;
    fixture_config(&cfg);
    struct sph_solver sv;
    sph_solver_init(&sv, &cfg, &s, NULL, NULL);
    sph_system_free(&s);
    const struct sph_parts *fl = &sv.sys.part[SPH_KIND_FLUID];
    double *one[SPH_NKINDS];
    for (int k = 0; k < SPH_NKINDS; k++) {
      one[k] = malloc((sv.sys.part[k].n + 1) * sizeof(double));
      for (size_t i = 0; i < sv.sys.part[k].n; i++) one[k][i] = 1.0;
    }
    const struct sph_op op = {&sv.sys, &sv.kernel, &sv.nb, 0};
    double g[3];
    sph_op_grad(&op, 0.0, (const double *const *)one, 3, g); /* bottom row, n = +y */
    print_message("first row at %s: phi = %.3f, Grad(1).n h = %+.4f\n", r ? "dr" : "dr/2",
                  sv.vertex_phi, g[1] * sv.sys.h);
    assert_true(fl->x[1][3] < 1.01 * (r ? 1.0 : 0.5) / 24);
    if (r)
      assert_true(g[1] < 0.0 && sv.vertex_phi > 0.3);
    else
      assert_true(g[1] > 0.0 && sv.vertex_phi < 0.0);
    for (int k = 0; k < SPH_NKINDS; k++) free(one[k]);
    sph_solver_free(&sv);
  }
}

/* The operators with the cell lists equal those with the naive search (up to summation order). */
static void test_cells_vs_naive(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_solver sv;
  setup(&sv, 20, 2.0, FIX_CHANNEL);
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 20261122);
  struct sph_parts *fl = &sv.sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < fl->n; a++)
    for (int c = 0; c < 2; c++) fl->x[c][a] += sabre_rng_uniform(&rng, -0.2, 0.2) / 20.0;
  const struct field_def quad = {f_quad, b_quad, u_quad};
  struct fields F;
  struct sph_nbrs naive;
  memset(&naive, 0, sizeof naive);
  sph_nbrs_build(&sv.nb, &sv.sys, 0.1 * sv.sys.h);
  sph_nbrs_gamma(&sv.nb, &sv.sys, &sv.kernel);
  sph_nbrs_build_naive(&naive, &sv.sys, 0.1 * sv.sys.h);
  sph_nbrs_gamma(&naive, &sv.sys, &sv.kernel);
  sph_solver_sync(&sv);
  fill(&sv, &quad, &F);
  const struct sph_op o1 = {&sv.sys, &sv.kernel, &sv.nb, 0}, o2 = {&sv.sys, &sv.kernel, &naive, 0};
  for (size_t a = 0; a < fl->n; a++) {
    double g1[3], g2[3];
    sph_op_grad(&o1, 1.0, (const double *const *)F.f, a, g1);
    sph_op_grad(&o2, 1.0, (const double *const *)F.f, a, g2);
    for (int c = 0; c < 2; c++) assert_abs(g1[c], g2[c], 1e-11 * (1 + fabs(g2[c])));
    assert_abs(sph_op_div(&o1, 0.0, (const double *const(*)[3])F.B, a),
               sph_op_div(&o2, 0.0, (const double *const(*)[3])F.B, a), 1e-10);
  }
  release(&F);
  sph_nbrs_free(&naive);
  sph_solver_free(&sv);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_interior),        cmocka_unit_test(test_flat_wall),
      cmocka_unit_test(test_constant_defect), cmocka_unit_test(test_first_row_sign),
      cmocka_unit_test(test_cells_vs_naive),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
