/* Arbitrary-order Robin/Neumann vertex values, M(64–74), and the hydrostatic correction M(83):
 * exactness on polynomials that satisfy the Robin condition (random clouds, d = 1, 2, 3, m = 1..3,
 * random coefficients), m = 1 equals Shepard M(16–17), hydrostatic wall pressure including the
 * free-surface corner, and every status code. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "sabre/sph_robin.h"
#include "sabre/sph_walls.h"
#include "testutil.h"

#define NMAX 400

static const double H = 0.0237; /* smoothing length [m], deliberately not 1 */

struct cloud {
  int dim;
  size_t n;
  double xv[3], nv[3];
  double x[NMAX][3], f[NMAX], vol[NMAX], w[NMAX], rho[NMAX];
  double xn[NMAX]; /* x_a = r_av · n_v */
};

static void random_unit(struct sabre_rng *rng, int dim, double *n) {
  double nn;
  do {
    nn = 0.0;
    for (int k = 0; k < 3; k++) n[k] = k < dim ? sabre_rng_uniform(rng, -1.0, 1.0) : 0.0;
    for (int k = 0; k < dim; k++) nn += n[k] * n[k];
  } while (nn < 0.05 || nn > 1.0);
  for (int k = 0; k < dim; k++) n[k] /= sqrt(nn);
}

/* n fluid particles in the half ball of radius 2h on the fluid side of a random vertex; with
 * `behind` a few of them lie slightly behind the vertex plane (as near a convex corner). */
static void random_cloud(struct sabre_rng *rng, const struct sph_kernel *k, int dim, size_t n,
                         int behind, struct cloud *c) {
  memset(c, 0, sizeof *c);
  c->dim = dim;
  c->n = n;
  for (int d = 0; d < dim; d++) c->xv[d] = sabre_rng_uniform(rng, -1.3, 2.1);
  random_unit(rng, dim, c->nv);
  const double R = 2.0 * H;
  for (size_t a = 0; a < n; a++) {
    double r[3] = {0.0, 0.0, 0.0}, rr, xn;
    const double xmin = (behind && a % 7 == 3) ? -0.2 * R : 0.0;
    do {
      rr = 0.0;
      xn = 0.0;
      for (int d = 0; d < dim; d++) {
        r[d] = sabre_rng_uniform(rng, -R, R);
        rr += r[d] * r[d];
        xn += r[d] * c->nv[d];
      }
    } while (rr >= R * R || xn <= xmin || xn > R);
    for (int d = 0; d < dim; d++) c->x[a][d] = c->xv[d] + r[d];
    c->xn[a] = xn;
    c->w[a] = sph_kernel_w(k, sqrt(rr));
    c->vol[a] = pow(0.5 * H, dim) * sabre_rng_uniform(rng, 0.6, 1.4);
    c->rho[a] = 1000.0 * sabre_rng_uniform(rng, 0.97, 1.03);
  }
}

/* λ(x) = Σ_j p_j x^j with μ1 p0 + μ2 p1 = μ3, M(64); degree `deg`. */
static double poly(const double *p, int deg, double x) {
  double v = 0.0;
  for (int j = deg; j >= 0; j--) v = v * x + p[j];
  return v;
}

/* Exactness: any polynomial of degree ≤ m along the normal that satisfies the Robin condition is
 * reproduced, for random Robin coefficients. κL = μ1 L/μ2 ∈ [−1.7, 0.7] keeps the β1 column
 * 1 − κξ ≥ 0.3 on the cloud (ξ = x/L ≤ 1): where it nearly vanishes the fit amplifies round-off
 * (and vanishes exactly: test_singular). With the hydrostatic correction the
 * field may also vary linearly along the wall as ρ_a (r_av − x_a n)·g with per-particle ρ_a. */
static void exactness(int hydro) {
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 20130523u + (uint64_t)hydro);
  struct sph_robin_ws ws;
  static struct cloud c;
  double worst = 0.0, worst_eps = 0.0;
  for (int dim = 1; dim <= 3; dim++) {
    struct sph_kernel k;
    assert_int_equal(sph_kernel_init(&k, dim, H), 0);
    for (int m = 1; m <= 3; m++) {
      for (int trial = 0; trial < 40; trial++) {
        const size_t n = dim == 1 ? 3 + (size_t)trial % 5 : 12 + (size_t)trial * 3;
        random_cloud(&rng, &k, dim, n, trial % 2, &c);
        struct sph_robin_params p;
        sph_robin_params_init(&p, 2.0 * H);
        p.m = m;
        p.mu2 = sabre_rng_uniform(&rng, 0.4, 2.7) * (trial % 3 == 0 ? -1.0 : 1.0);
        p.mu1 = trial % 5 == 0 ? 0.0 : sabre_rng_uniform(&rng, -1.7, 0.7) * p.mu2 / p.length;
        p.mu3 = sabre_rng_uniform(&rng, -3.1, 3.1) / p.length;
        p.hydro = hydro;
        double g[3] = {0.0, 0.0, 0.0};
        for (int d = 0; d < dim; d++) g[d] = sabre_rng_uniform(&rng, -9.81, 9.81);
        memcpy(p.gravity, g, sizeof g);
        double coef[4];
        coef[0] = sabre_rng_uniform(&rng, -2.385, 3.17);
        coef[1] = (p.mu3 - p.mu1 * coef[0]) / p.mu2;
        for (int j = 2; j <= 3; j++) coef[j] = sabre_rng_uniform(&rng, -5.0, 5.0) / pow(H, j);
        const int deg = trial % 4 == 1 ? m - 1 : m; /* lower degrees are exact too */
        if (deg == 0) { /* a constant satisfies M(64) only with μ3 = μ1 p0 */
          p.mu3 = p.mu1 * coef[0];
          coef[1] = 0.0;
        }
        /* Round-off scale: the largest term of y_a = f_a − (μ3/μ2) x_a − ρ_a t_a·g, M(83). */
        double scale = fabs(coef[0]);
        for (size_t a = 0; a < c.n; a++) {
          c.f[a] = poly(coef, deg, c.xn[a]);
          double hyd = 0.0, hyd_terms = 0.0; /* ρ t·g and the size of the terms it is made of */
          if (hydro) {
            for (int d = 0; d < dim; d++) {
              hyd += c.rho[a] * (c.x[a][d] - c.xv[d] - c.xn[a] * c.nv[d]) * g[d];
              hyd_terms += c.rho[a] * (fabs(c.x[a][d] - c.xv[d]) + fabs(c.xn[a])) * fabs(g[d]);
            }
            c.f[a] += hyd;
          }
          scale = fmax(scale, fabs(c.f[a]) + fabs(p.mu3 / p.mu2 * c.xn[a]) + hyd_terms);
        }
        double fv;
        int st = sph_robin_vertex_value(&p, dim, c.xv, c.nv, c.n, (const double(*)[3])c.x, c.f,
                                        c.vol, c.w, c.rho, &ws, &fv);
        if (st != SPH_ROBIN_SUCCESS)
          print_error("d=%d m=%d trial=%d: %s\n", dim, m, trial, sph_robin_strerror(st));
        assert_int_equal(st, SPH_ROBIN_SUCCESS);
        /* Round-off of the normal equations grows like ε·cond(X^T Λ X) = ε/rcond: a clustered
         * 1D cloud of 3 particles for m = 3 has rcond ~ 1e-8. */
        const double err = fabs(fv - coef[0]) / scale;
        const double tol = 1e-13 + 16.0 * DBL_EPSILON / ws.rcond;
        worst = fmax(worst, err);
        worst_eps = fmax(worst_eps, err * ws.rcond / DBL_EPSILON);
        if (err > tol)
          print_error("d=%d m=%d trial=%d n=%zu rcond=%.3e err=%.3e scale=%g\n", dim, m, trial, c.n,
                      ws.rcond, err, scale);
        assert_abs(fv, coef[0], tol * scale);
      }
    }
  }
  print_message("exactness (hydro=%d): worst error / max|f| = %.2e (%.3f eps/rcond)\n", hydro,
                worst, worst_eps);
}

static void test_exact_polynomials(void **state) {
  (void)state;
  exactness(0);
}

static void test_exact_polynomials_hydro(void **state) {
  (void)state;
  exactness(1);
}

/* m = 1 with (μ1, μ2, μ3) = (0, 1, 0) is Shepard, M(16–17), for any field. */
static void test_m1_is_shepard(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 16u);
  struct sph_robin_ws ws;
  static struct cloud c;
  for (int dim = 1; dim <= 3; dim++) {
    struct sph_kernel k;
    assert_int_equal(sph_kernel_init(&k, dim, H), 0);
    for (int trial = 0; trial < 20; trial++) {
      random_cloud(&rng, &k, dim, 1 + (size_t)trial * 4, trial % 2, &c);
      double num = 0.0, alpha_v = 0.0;
      for (size_t a = 0; a < c.n; a++) {
        c.f[a] = sabre_rng_uniform(&rng, -7.3, 11.9);
        num += c.vol[a] * c.f[a] * c.w[a];
        alpha_v += c.vol[a] * c.w[a];
      }
      struct sph_robin_params p;
      sph_robin_params_init(&p, 2.0 * H);
      double fv;
      assert_int_equal(sph_robin_vertex_value(&p, dim, c.xv, c.nv, c.n, (const double(*)[3])c.x,
                                              c.f, c.vol, c.w, NULL, &ws, &fv),
                       SPH_ROBIN_SUCCESS);
      assert_rel(fv, num / alpha_v, 1e-14);
    }
  }
}

/* Accumulator (neighbour-loop form) and one-shot form agree bit for bit. */
static void test_accumulator_matches_arrays(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 73u);
  struct sph_kernel k;
  assert_int_equal(sph_kernel_init(&k, 2, H), 0);
  static struct cloud c;
  random_cloud(&rng, &k, 2, 40, 1, &c);
  for (size_t a = 0; a < c.n; a++) c.f[a] = sin(37.0 * c.x[a][0]) + c.x[a][1];
  struct sph_robin_params p;
  sph_robin_params_init(&p, 2.0 * H);
  p.m = 2;
  p.mu1 = -1.3;
  p.mu3 = 0.7;
  struct sph_robin_ws ws;
  double f1, f2;
  assert_int_equal(sph_robin_vertex_value(&p, 2, c.xv, c.nv, c.n, (const double(*)[3])c.x, c.f,
                                          c.vol, c.w, NULL, &ws, &f1),
                   SPH_ROBIN_SUCCESS);
  assert_true(ws.rcond > 0.0 && ws.rcond <= 1.0);
  assert_int_equal(sph_robin_begin(&ws, &p, 2, c.nv), SPH_ROBIN_SUCCESS);
  for (size_t a = 0; a < c.n; a++) {
    const double r[3] = {c.x[a][0] - c.xv[0], c.x[a][1] - c.xv[1], 0.0};
    sph_robin_add(&ws, r, c.f[a], c.vol[a] * c.w[a], 0.0);
  }
  assert_int_equal(sph_robin_finish(&ws, &f2), SPH_ROBIN_SUCCESS);
  assert_true(f1 == f2);
  assert_int_equal((int)ws.n_used, (int)c.n);
  assert_int_equal(ws.n_distinct, 2);
}

/* Still water in a 2D tank: p = ρ0 g (H − y), ∂p/∂n = ρ0 g·n on every wall. With M(83) the wall
 * pressure is exact for m = 1..3 at every vertex, including 0 where the vertical wall meets the
 * free surface; without it (M(82)) that corner vertex sees only positive fluid pressures and gets
 * a spurious positive value (M §7.2, Fig. 9). */
static void test_hydrostatic_tank(void **state) {
  (void)state;
  const double dr = 0.0123, depth = 12.0 * dr, rho0 = 998.2, gz = -9.81;
  const double h = 2.0 * dr; /* h = 2Δr as in the paper */
  struct sph_kernel k;
  assert_int_equal(sph_kernel_init(&k, 2, h), 0);
  static struct cloud c;
  memset(&c, 0, sizeof c);
  for (int i = 0; i < 20; i++)
    for (int j = 0; j < 12; j++) {
      size_t a = c.n++;
      c.x[a][0] = (i + 0.5) * dr;
      c.x[a][1] = (j + 0.5) * dr;
      c.f[a] = rho0 * (-gz) * (depth - c.x[a][1]);
      c.vol[a] = dr * dr;
      c.rho[a] = rho0;
    }
  const double s2 = sqrt(0.5);
  const struct {
    double x[2], n[2];
  } vert[] = {
      {{0.0, depth}, {1.0, 0.0}},        /* vertical wall at the free surface */
      {{0.0, 0.37 * depth}, {1.0, 0.0}}, /* vertical wall */
      {{0.0, 0.0}, {s2, s2}},            /* bottom corner: mean of the two segment normals */
      {{9.3 * dr, 0.0}, {0.0, 1.0}},     /* bottom */
  };
  const double pscale = rho0 * (-gz) * depth;
  struct sph_robin_ws ws;
  for (size_t iv = 0; iv < sizeof vert / sizeof vert[0]; iv++) {
    for (size_t a = 0; a < c.n; a++)
      c.w[a] = sph_kernel_w(&k, hypot(c.x[a][0] - vert[iv].x[0], c.x[a][1] - vert[iv].x[1]));
    const double exact = rho0 * (-gz) * (depth - vert[iv].x[1]);
    for (int m = 1; m <= 3; m++) {
      struct sph_robin_params p;
      sph_robin_params_init(&p, 2.0 * h);
      p.m = m;
      p.mu3 = rho0 * gz * vert[iv].n[1]; /* ∂p/∂n = ρ g·n */
      p.hydro = 1;
      p.gravity[1] = gz;
      double pv;
      assert_int_equal(
          sph_robin_vertex_value(&p, 2, vert[iv].x, vert[iv].n, c.n, (const double(*)[3])c.x, c.f,
                                 c.vol, c.w, c.rho, &ws, &pv),
          SPH_ROBIN_SUCCESS);
      assert_abs(pv, exact, 1e-12 * pscale);
      if (iv == 0) {
        /* Without M(83): clearly positive at the free-surface corner. */
        p.hydro = 0;
        assert_int_equal(
            sph_robin_vertex_value(&p, 2, vert[iv].x, vert[iv].n, c.n, (const double(*)[3])c.x, c.f,
                                   c.vol, c.w, c.rho, &ws, &pv),
            SPH_ROBIN_SUCCESS);
        print_message("free-surface corner, m=%d: p_v/(rho g H) = %.3e without M(83)\n", m,
                      pv / pscale);
        assert_true(pv > 0.02 * pscale);
      }
    }
  }
}

/* SPH_ROBIN_ETOOFEW: fewer than m distinct distances with a positive weight. */
static void test_too_few_distances(void **state) {
  (void)state;
  struct sph_kernel k;
  assert_int_equal(sph_kernel_init(&k, 2, H), 0);
  const double xv[2] = {0.3, -0.2}, nv[2] = {0.0, 1.0};
  /* One row of particles parallel to the wall: one distance. */
  double x[9][3], f[9], vol[9], w[9];
  for (int a = 0; a < 9; a++) {
    x[a][0] = xv[0] + (a - 4) * 0.4 * H;
    x[a][1] = xv[1] + 0.7 * H;
    x[a][2] = 0.0;
    f[a] = 2.385 + a;
    vol[a] = 0.25 * H * H;
    w[a] = sph_kernel_w(&k, hypot(x[a][0] - xv[0], x[a][1] - xv[1]));
  }
  struct sph_robin_params p;
  sph_robin_params_init(&p, 2.0 * H);
  struct sph_robin_ws ws;
  double fv;
  p.m = 1;
  assert_int_equal(
      sph_robin_vertex_value(&p, 2, xv, nv, 9, (const double(*)[3])x, f, vol, w, NULL, &ws, &fv),
      SPH_ROBIN_SUCCESS);
  for (int m = 2; m <= 3; m++) {
    p.m = m;
    assert_int_equal(
        sph_robin_vertex_value(&p, 2, xv, nv, 9, (const double(*)[3])x, f, vol, w, NULL, &ws, &fv),
        SPH_ROBIN_ETOOFEW);
    assert_true(isnan(fv));
    assert_int_equal(ws.n_distinct, 1);
  }
  /* A second distance closer than dist_tol·L does not count ... */
  x[8][1] += 0.3e-6 * p.length;
  p.m = 2;
  assert_int_equal(
      sph_robin_vertex_value(&p, 2, xv, nv, 9, (const double(*)[3])x, f, vol, w, NULL, &ws, &fv),
      SPH_ROBIN_ETOOFEW);
  /* ... nor does one outside the kernel support (zero weight) ... */
  x[8][1] = xv[1] + 2.5 * H;
  w[8] = sph_kernel_w(&k, hypot(x[8][0] - xv[0], x[8][1] - xv[1]));
  assert_true(w[8] == 0.0);
  assert_int_equal(
      sph_robin_vertex_value(&p, 2, xv, nv, 9, (const double(*)[3])x, f, vol, w, NULL, &ws, &fv),
      SPH_ROBIN_ETOOFEW);
  /* ... but one inside does. */
  x[8][1] = xv[1] + 1.1 * H;
  w[8] = sph_kernel_w(&k, hypot(x[8][0] - xv[0], x[8][1] - xv[1]));
  assert_int_equal(
      sph_robin_vertex_value(&p, 2, xv, nv, 9, (const double(*)[3])x, f, vol, w, NULL, &ws, &fv),
      SPH_ROBIN_SUCCESS);
  /* No fluid neighbour at all. */
  p.m = 1;
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 0, NULL, NULL, NULL, NULL, NULL, &ws, &fv),
                   SPH_ROBIN_ETOOFEW);
  assert_int_equal(ws.n_distinct, 0);
}

/* SPH_ROBIN_ESINGULAR: m distinct distances that are all roots of a polynomial of the fitted
 * family c1 (1 − κξ) + c2 ξ² + ... (possible only with μ1 ≠ 0). */
static void test_singular(void **state) {
  (void)state;
  const double xv[1] = {0.0}, nv[1] = {1.0}, L = 2.0 * H;
  struct sph_robin_params p;
  sph_robin_params_init(&p, L);
  struct sph_robin_ws ws;
  double fv;
  /* m = 1: the only particle sits at x = μ2/μ1, where the β1 column vanishes. */
  p.mu1 = 1.0 / (0.6 * L);
  double x1[1][3] = {{0.6 * L, 0.0, 0.0}}, f1[1] = {1.0}, v1[1] = {1.0}, w1[1] = {1.0};
  assert_int_equal(
      sph_robin_vertex_value(&p, 1, xv, nv, 1, (const double(*)[3])x1, f1, v1, w1, NULL, &ws, &fv),
      SPH_ROBIN_ESINGULAR);
  assert_true(isnan(fv));
  /* m = 2: ξ = 0.3, 0.6 are the roots of ξ² − 0.18/0.9 ... with κ = (ξ1 + ξ2)/(ξ1 ξ2) = 5. */
  p.m = 2;
  p.mu1 = 5.0 / L;
  double x2[2][3] = {{0.3 * L, 0.0, 0.0}, {0.6 * L, 0.0, 0.0}}, f2[2] = {1.0, 2.0},
         v2[2] = {1.0, 1.0}, w2[2] = {0.8, 0.3};
  assert_int_equal(
      sph_robin_vertex_value(&p, 1, xv, nv, 2, (const double(*)[3])x2, f2, v2, w2, NULL, &ws, &fv),
      SPH_ROBIN_ESINGULAR);
  assert_true(ws.rcond < 1e-13);
  /* Any other κ is fine. */
  p.mu1 = 4.0 / L;
  assert_int_equal(
      sph_robin_vertex_value(&p, 1, xv, nv, 2, (const double(*)[3])x2, f2, v2, w2, NULL, &ws, &fv),
      SPH_ROBIN_SUCCESS);
}

static void test_bad_input(void **state) {
  (void)state;
  const double xv[3] = {0.0, 0.0, 0.0}, nv[3] = {0.0, 1.0, 0.0}, L = 2.0 * H;
  double x[2][3] = {{0.0, 0.3 * L, 0.0}, {0.1 * L, 0.7 * L, 0.0}};
  double f[2] = {1.0, 2.0}, vol[2] = {1.0, 1.0}, w[2] = {0.5, 0.25}, rho[2] = {1.0, 1.0};
  const double(*cx)[3] = (const double(*)[3])x;
  struct sph_robin_params p;
  sph_robin_params_init(&p, L);
  struct sph_robin_ws ws;
  double fv = 0.0;
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, vol, w, NULL, &ws, &fv), 0);
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, vol, w, NULL, NULL, &fv),
                   SPH_ROBIN_EINVAL);
  assert_true(isnan(fv));
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, vol, w, NULL, &ws, NULL),
                   SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_vertex_value(NULL, 2, xv, nv, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_vertex_value(&p, 0, xv, nv, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_vertex_value(&p, 4, xv, nv, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_vertex_value(&p, 2, NULL, nv, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, NULL, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, NULL, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, NULL, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, NULL, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, vol, NULL, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  struct sph_robin_params q;
#define EXPECT_BAD_PARAM(...)                                                                \
  do {                                                                                       \
    q = p;                                                                                   \
    __VA_ARGS__;                                                                             \
    assert_int_equal(sph_robin_vertex_value(&q, 2, xv, nv, 2, cx, f, vol, w, rho, &ws, &fv), \
                     SPH_ROBIN_EINVAL);                                                      \
    assert_int_equal(ws.status, SPH_ROBIN_EINVAL);                                           \
  } while (0)
  EXPECT_BAD_PARAM(q.m = 0);
  EXPECT_BAD_PARAM(q.m = SPH_ROBIN_M_MAX + 1);
  EXPECT_BAD_PARAM(q.mu2 = 0.0);
  EXPECT_BAD_PARAM(q.mu1 = NAN);
  EXPECT_BAD_PARAM(q.mu3 = INFINITY);
  EXPECT_BAD_PARAM(q.length = 0.0);
  EXPECT_BAD_PARAM(q.length = -L);
  EXPECT_BAD_PARAM(q.length = NAN);
  EXPECT_BAD_PARAM(q.dist_tol = -1e-6);
  EXPECT_BAD_PARAM(q.rcond_min = 1.0);
  EXPECT_BAD_PARAM(q.rcond_min = -1e-12);
  EXPECT_BAD_PARAM((q.hydro = 1, q.gravity[1] = NAN));
  EXPECT_BAD_PARAM(q.mu1 = 1e300, q.mu2 = 1e-300); /* μ1/μ2 overflows */
#undef EXPECT_BAD_PARAM
  /* hydro needs ρ */
  p.hydro = 1;
  p.gravity[1] = -9.81;
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, vol, w, rho, &ws, &fv), 0);
  p.hydro = 0;
  /* normal not unit; NaN normal */
  const double n_long[3] = {0.0, 1.001, 0.0}, n_nan[3] = {NAN, 1.0, 0.0};
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, n_long, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  sabre_fp_traps_off(); /* NaN inputs on purpose */
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, n_nan, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  /* negative weight or volume, NaN value, NaN position */
  w[1] = -0.25;
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  w[1] = 0.25;
  vol[0] = -1.0;
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  vol[0] = 1.0;
  f[0] = NAN;
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  f[0] = 1.0;
  x[1][1] = NAN;
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv, nv, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  x[1][1] = 0.7 * L;
  const double xv_nan[3] = {NAN, 0.0, 0.0};
  assert_int_equal(sph_robin_vertex_value(&p, 2, xv_nan, nv, 2, cx, f, vol, w, NULL, &ws, &fv),
                   SPH_ROBIN_EINVAL);
  sabre_fp_traps_on();
  /* Errors are sticky: a failed begin turns add/finish into no-ops returning the error. */
  p.m = 0;
  assert_int_equal(sph_robin_begin(&ws, &p, 2, nv), SPH_ROBIN_EINVAL);
  sph_robin_add(&ws, x[0], 1.0, 1.0, 1.0);
  assert_int_equal(sph_robin_finish(&ws, &fv), SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_begin(NULL, &p, 2, nv), SPH_ROBIN_EINVAL);
  assert_int_equal(sph_robin_finish(NULL, &fv), SPH_ROBIN_EINVAL);
}

static void test_status_names(void **state) {
  (void)state;
  const int codes[] = {SPH_ROBIN_SUCCESS, SPH_ROBIN_EINVAL, SPH_ROBIN_ETOOFEW, SPH_ROBIN_ESINGULAR};
  for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++) {
    assert_non_null(strstr(sph_robin_status_name(codes[i]), "SPH_ROBIN_"));
    assert_string_not_equal(sph_robin_strerror(codes[i]), "unknown status");
  }
  assert_non_null(strstr(sph_robin_strerror(SPH_ROBIN_ETOOFEW), "fewer than m distinct"));
  assert_string_equal(sph_robin_status_name(SPH_ROBIN_ETOOFEW), "SPH_ROBIN_ETOOFEW");
  assert_string_equal(sph_robin_strerror(-7), "unknown status");
  assert_string_equal(sph_robin_status_name(99), "SPH_ROBIN_UNKNOWN");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_exact_polynomials), cmocka_unit_test(test_exact_polynomials_hydro),
      cmocka_unit_test(test_m1_is_shepard),     cmocka_unit_test(test_accumulator_matches_arrays),
      cmocka_unit_test(test_hydrostatic_tank),  cmocka_unit_test(test_too_few_distances),
      cmocka_unit_test(test_singular),          cmocka_unit_test(test_bad_input),
      cmocka_unit_test(test_status_names),
  };
  return cmocka_run_group_tests(tests, sabre_setup_gsl_traps, NULL);
}
