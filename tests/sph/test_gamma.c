/*
 * γ_a and ∇γ_a, J(2)–J(4), against exact results (docs/theory.md §3.1): far field, distance to a
 * plane (the cumulative kernel marginal), the solid-angle limit on walls, corners and edges,
 * independence of how a flat wall is cut, ∇γ_a = finite difference of γ_a, the dynamic form M(4),
 * error codes. Geometry is moved by random rigid motions so nothing relies on axis-aligned walls.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sabre/sph.h"
#include "sabre/sph_walls.h"
#include "test_gamma_ref.h"
#include "testutil.h"
#include "walls/gamma_impl.h"

static const double H = 0.0237; /* smoothing length [m] */

static double eval(const struct sph_kernel *k, const double *a, size_t n,
                   const struct sph_wall_element *e, double grad[3]) {
  double gamma, g[3];
  assert_int_equal(sph_gamma_eval(k, a, n, e, &gamma, g), 0);
  if (grad != NULL) memcpy(grad, g, sizeof g);
  return gamma;
}

static void move_all(const struct ref_motion *m, size_t n, struct sph_wall_element *e) {
  for (size_t i = 0; i < n; i++) ref_apply_element(m, &e[i]);
}

/* ---- far field ----------------------------------------------------------------------------- */

static void test_far_field(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 11);
  struct sph_kernel k1, k2, k3;
  sph_kernel_init(&k1, 1, H);
  sph_kernel_init(&k2, 2, H);
  sph_kernel_init(&k3, 3, H);
  double g[3];
  const double origin[3] = {0.31 * H, -0.17 * H, 0.05 * H};
  assert_true(eval(&k3, origin, 0, NULL, g) == 1.0);
  assert_true(g[0] == 0.0 && g[1] == 0.0 && g[2] == 0.0);

  /* 1D: walls just beyond the support on both sides */
  struct sph_wall_element w1[2];
  memset(w1, 0, sizeof w1);
  w1[0].x[0][0] = origin[0] - 2.0000001 * H;
  w1[0].normal[0] = 1.0;
  w1[1].x[0][0] = origin[0] + 2.0000001 * H;
  w1[1].normal[0] = -1.0;
  assert_true(eval(&k1, origin, 2, w1, g) == 1.0);
  assert_true(g[0] == 0.0);

  /* 2D: a square box of side 4.2h around the point, rotated; lines of two of its sides pass
   * within the support but the segments do not */
  for (int trial = 0; trial < 20; trial++) {
    const double L = 2.1 * H;
    struct sph_wall_element b[4] = {ref_seg(-L, -L, L, -L), ref_seg(L, -L, L, L),
                                    ref_seg(L, L, -L, L), ref_seg(-L, L, -L, -L)};
    const double off = sabre_rng_uniform(&rng, -0.0999, 0.0999) * H;
    double a[3] = {off, off, 0.0};
    struct ref_motion m = ref_motion_random(&rng, 2, 5.0 * H);
    move_all(&m, 4, b);
    ref_apply(&m, a, a);
    assert_true(eval(&k2, a, 4, b, g) == 1.0);
    assert_true(g[0] == 0.0 && g[1] == 0.0 && g[2] == 0.0);
  }
  /* 3D: triangles whose planes cut the support but which lie outside it */
  for (int trial = 0; trial < 20; trial++) {
    const double p0[3] = {2.05 * H, 0.3 * H, -1.0 * H}, p1[3] = {5.0 * H, 0.2 * H, -0.9 * H},
                 p2[3] = {2.5 * H, -3.0 * H, 0.7 * H}, q0[3] = {0.0, 0.0, 2.0001 * H},
                 q1[3] = {9.0 * H, 0.0, 2.0001 * H}, q2[3] = {0.0, 9.0 * H, 2.0001 * H};
    struct sph_wall_element t[2] = {ref_tri(p0, p1, p2), ref_tri(q0, q2, q1)};
    double a[3] = {0.0, 0.0, 0.0};
    struct ref_motion m = ref_motion_random(&rng, 3, 5.0 * H);
    move_all(&m, 2, t);
    ref_apply(&m, a, a);
    assert_true(eval(&k3, a, 2, t, g) == 1.0);
    assert_true(g[0] == 0.0 && g[1] == 0.0 && g[2] == 0.0);
  }
}

/* ---- distance to a plane ------------------------------------------------------------------- */

/* Flat wall through the origin with normal +y (2D) or +z (3D), wider than the support, cut into a
 * few elements. */
static size_t plane_wall(int dim, struct sph_wall_element *e) {
  memset(e, 0, 4 * sizeof *e);
  if (dim == 1) {
    e[0].normal[0] = 1.0;
    return 1;
  }
  if (dim == 2) {
    e[0] = ref_seg(-7.3 * H, 0.0, -0.4 * H, 0.0);
    e[1] = ref_seg(-0.4 * H, 0.0, 1.1 * H, 0.0);
    e[2] = ref_seg(1.1 * H, 0.0, 6.9 * H, 0.0);
    return 3;
  }
  const double p[4][3] = {{-6.1 * H, -5.7 * H, 0},
                          {6.3 * H, -5.9 * H, 0},
                          {5.8 * H, 6.2 * H, 0},
                          {-6.4 * H, 6.0 * H, 0}};
  const double c[3] = {0.4 * H, -0.3 * H, 0.0};
  for (int j = 0; j < 4; j++) e[j] = ref_tri(c, p[j], p[(j + 1) % 4]);
  return 4;
}

/* γ(δ) = 1/2 + ∫_0^δ P_d and ∇γ = P_d(δ) n (P_d the kernel marginal, by GSL quadrature). */
static void test_plane_distance(void **state) {
  (void)state;
  gsl_integration_workspace *w1 = gsl_integration_workspace_alloc(500);
  gsl_integration_workspace *w2 = gsl_integration_workspace_alloc(500);
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 23);
  const double fixed[] = {0.0, 1e-9, 1e-4, 0.1, 0.5, 1.0, 1.3, 1.7, 1.99, 1.9999999, 2.0, 2.3};
  const int nfixed = (int)(sizeof fixed / sizeof fixed[0]);
  for (int dim = 1; dim <= 3; dim++) {
    double max_err = 0.0, max_err_grad = 0.0;
    struct sph_kernel k;
    sph_kernel_init(&k, dim, H);
    struct sph_wall_element e[4];
    const size_t n = plane_wall(dim, e);
    struct ref_motion m = ref_motion_random(&rng, dim, 3.0 * H);
    if (dim == 1)
      memset(&m, 0, sizeof m), m.R[0][0] = m.R[1][1] = m.R[2][2] = 1.0, m.t[0] = 0.37 * H;
    move_all(&m, n, e);
    double nrm[3] = {0.0, 0.0, 0.0};
    nrm[dim == 1 ? 0 : dim - 1] = 1.0;
    ref_apply_vec(&m, nrm, nrm);
    for (int i = 0; i < nfixed + 12; i++) {
      const double delta = (i < nfixed ? fixed[i] : sabre_rng_uniform(&rng, 0.0, 2.0)) * H;
      double a[3] = {0.0, 0.0, 0.0};
      if (dim >= 2) a[0] = sabre_rng_uniform(&rng, -0.5, 0.5) * H;
      if (dim == 3) a[1] = sabre_rng_uniform(&rng, -0.5, 0.5) * H;
      a[dim == 1 ? 0 : dim - 1] = delta;
      ref_apply(&m, a, a);
      double g[3];
      const double gamma = eval(&k, a, n, e, g);
      const double ref = ref_gamma_plane(&k, delta, w1, w2);
      max_err = fmax(max_err, fabs(gamma - ref));
      assert_abs(gamma, ref, 1e-12);
      const double p = ref_marginal(&k, delta, w2);
      for (int c = 0; c < 3; c++) {
        max_err_grad = fmax(max_err_grad, fabs(g[c] - p * nrm[c]) * H);
        assert_abs(g[c] * H, p * nrm[c] * H, 1e-12);
      }
    }
    printf("plane wall, %dD: max |γ − 1/2 − ∫P| = %.1e, max h|∇γ − P n| = %.1e\n", dim, max_err,
           max_err_grad);
  }
  gsl_integration_workspace_free(w1);
  gsl_integration_workspace_free(w2);
}

/* ---- solid-angle limit: walls, corners, edges ---------------------------------------------- */

/* γ at b, a point of the fluid 1e-6 h from a point a on the walls, equals γ(a) + ∇γ(a)·(b − a)
 * up to O(|b − a|²) and the round-off of positions relative to far vertices (~1e-16 L/|b − a|). */
static void assert_continuous(const struct sph_kernel *k, const double *a, const double *b,
                              size_t n, const struct sph_wall_element *e) {
  double ga[3];
  const double gamma_a = eval(k, a, n, e, ga);
  const double taylor =
      gamma_a + ga[0] * (b[0] - a[0]) + ga[1] * (b[1] - a[1]) + ga[2] * (b[2] - a[2]);
  assert_abs(eval(k, b, n, e, NULL), taylor, 1e-8);
}

/* 2D corner of interior angle theta at the origin: arms of length 6h along (1, 0) and
 * (cos θ, sin θ), the fluid inside the angle. */
static void corner2d(double theta, struct sph_wall_element e[2]) {
  const double L = 6.0 * H, c = cos(theta), s = sin(theta);
  e[0] = ref_seg(0.0, 0.0, L, 0.0); /* fluid on the left: inside */
  e[1] = ref_seg(L * c, L * s, 0.0, 0.0);
}

static void test_on_wall_2d(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 31);
  struct sph_kernel k;
  sph_kernel_init(&k, 2, H);
  double g[3];
  for (int trial = 0; trial < 10; trial++) {
    /* flat wall: interior of a segment and a vertex shared by two collinear segments */
    struct sph_wall_element e[4];
    const size_t n = plane_wall(2, e);
    struct ref_motion m = ref_motion_random(&rng, 2, 3.0 * H);
    move_all(&m, n, e);
    double a[3] = {0.3 * H, 0.0, 0.0};
    ref_apply(&m, a, a);
    assert_abs(eval(&k, a, n, e, g), 0.5, 1e-14);
    assert_abs(eval(&k, e[1].x[0], n, e, g), 0.5, 1e-14);
    assert_abs(eval(&k, e[1].x[1], n, e, g), 0.5, 1e-14);
    /* corners, convex and re-entrant: Θ/(2π) at the vertex, continuous from inside */
    const double angles[] = {REF_PI / 2.0, REF_PI / 3.0, 0.75 * REF_PI, 1.5 * REF_PI, 1.9 * REF_PI};
    for (int i = 0; i < 5; i++) {
      struct sph_wall_element c[2];
      corner2d(angles[i], c);
      move_all(&m, 2, c);
      assert_abs(eval(&k, c[0].x[0], 2, c, g), angles[i] / (2.0 * REF_PI), 1e-14);
      /* approaching along the bisector */
      double b[3] = {1e-6 * H * cos(0.5 * angles[i]), 1e-6 * H * sin(0.5 * angles[i]), 0.0};
      ref_apply(&m, b, b);
      assert_continuous(&k, c[0].x[0], b, 2, c);
      /* within the plane tolerance of both arms but not of the vertex: moved onto the vertex */
      double t[3] = {1.2e-12 * H * cos(0.5 * angles[i]), 1.2e-12 * H * sin(0.5 * angles[i]), 0.0};
      ref_apply(&m, t, t);
      assert_abs(eval(&k, t, 2, c, g), angles[i] / (2.0 * REF_PI), 1e-10);
      /* 1e-12 h from the line of one arm, 1e-8 h beyond its end (in the fluid of re-entrant
       * corners): that arm is then evaluated in closed form, not as on the wall */
      if (angles[i] > REF_PI) {
        double x[3] = {-1e-8 * H, 0.5e-12 * H, 0.0};
        ref_apply(&m, x, x);
        assert_continuous(&k, c[0].x[0], x, 2, c);
      }
      /* on one arm, away from the corner but within its support */
      double on[3] = {0.7 * H, 0.0, 0.0}, near[3] = {0.7 * H, 1e-6 * H, 0.0};
      ref_apply(&m, on, on);
      ref_apply(&m, near, near);
      assert_continuous(&k, on, near, 2, c);
    }
  }
}

/* 3D: the fan of K triangles around c on the plane z = 0 (radius 5h). */
static size_t fan(double cx, double cy, struct sph_wall_element *e) {
  const int K = 7;
  const double c[3] = {cx, cy, 0.0};
  for (int j = 0; j < K; j++) {
    const double t0 = 2.0 * REF_PI * j / K + 0.1, t1 = 2.0 * REF_PI * (j + 1) / K + 0.1;
    const double p0[3] = {5.0 * H * cos(t0), 5.0 * H * sin(t0), 0.0};
    const double p1[3] = {5.0 * H * cos(t1), 5.0 * H * sin(t1), 0.0};
    e[j] = ref_tri(c, p0, p1);
  }
  return (size_t)K;
}

/* Dihedral wedge of interior angle θ along the x axis: half-plane y ≥ 0 of z = 0 and the
 * half-plane in direction (0, cos θ, sin θ); the fluid between them. Each face is 2 triangles. */
static size_t wedge3d(double theta, int split, struct sph_wall_element *e) {
  const double L = 6.0 * H, c = cos(theta), s = sin(theta);
  const double a0[3] = {-L, 0, 0}, a1[3] = {L, 0, 0}, b0[3] = {-L, L, 0}, b1[3] = {L, L, 0};
  const double d0[3] = {-L, L * c, L * s}, d1[3] = {L, L * c, L * s};
  if (split) {
    e[0] = ref_tri(a0, a1, b1);
    e[1] = ref_tri(a0, b1, b0);
    e[2] = ref_tri(a0, d1, a1);
    e[3] = ref_tri(a0, d0, d1);
  } else {
    e[0] = ref_tri(a0, a1, b0);
    e[1] = ref_tri(a1, b1, b0);
    e[2] = ref_tri(a0, d0, a1);
    e[3] = ref_tri(a1, d0, d1);
  }
  return 4;
}

/* Box corner: the three quarter-planes of x, y, z = 0 around the origin, fluid in the octant. */
static size_t box_corner(int split, struct sph_wall_element *e) {
  const double L = 6.0 * H;
  const double o[3] = {0, 0, 0};
  size_t n = 0;
  for (int f = 0; f < 3; f++) {
    const int i = f, j = (f + 1) % 3; /* face spanned by axes i and j; normal is the third axis */
    double pi[3] = {0, 0, 0}, pj[3] = {0, 0, 0}, pij[3] = {0, 0, 0};
    pi[i] = L;
    pj[j] = L;
    pij[i] = L;
    pij[j] = 0.9 * L;
    if (split) {
      e[n++] = ref_tri(o, pi, pij);
      e[n++] = ref_tri(o, pij, pj);
    } else {
      e[n++] = ref_tri(o, pi, pj);
      e[n++] = ref_tri(pi, pij, pj);
    }
  }
  /* ref_tri orients by vertex order; make every normal point into the octant */
  for (size_t s = 0; s < n; s++) {
    const double sum = e[s].normal[0] + e[s].normal[1] + e[s].normal[2];
    if (sum < 0.0) {
      for (int c = 0; c < 3; c++) e[s].normal[c] = -e[s].normal[c];
    }
  }
  return n;
}

static void test_on_wall_3d(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 37);
  struct sph_kernel k;
  sph_kernel_init(&k, 3, H);
  double g[3];
  for (int trial = 0; trial < 10; trial++) {
    struct ref_motion m = ref_motion_random(&rng, 3, 3.0 * H);
    /* flat wall: at a vertex shared by 7 triangles, on a shared edge, inside a triangle */
    struct sph_wall_element e[8];
    const size_t n = fan(0.2 * H, -0.1 * H, e);
    move_all(&m, n, e);
    assert_abs(eval(&k, e[0].x[0], n, e, g), 0.5, 1e-14);
    double mid[3], in[3];
    for (int c = 0; c < 3; c++) {
      mid[c] = 0.5 * (e[2].x[0][c] + e[2].x[1][c]);
      in[c] = (0.2 * e[4].x[0][c] + 0.5 * e[4].x[1][c] + 0.3 * e[4].x[2][c]);
    }
    assert_abs(eval(&k, mid, n, e, g), 0.5, 1e-14);
    assert_abs(eval(&k, in, n, e, g), 0.5, 1e-14);
    /* dihedral edges: Θ/(2π) on the edge (1/4 for a right angle), both triangulations */
    const double angles[] = {REF_PI / 2.0, REF_PI / 3.0, 1.5 * REF_PI};
    for (int i = 0; i < 3; i++) {
      for (int split = 0; split < 2; split++) {
        struct sph_wall_element w[4];
        wedge3d(angles[i], split, w);
        move_all(&m, 4, w);
        double a[3] = {0.3 * H, 0.0, 0.0};
        ref_apply(&m, a, a);
        assert_abs(eval(&k, a, 4, w, g), angles[i] / (2.0 * REF_PI), 1e-14);
        double b[3] = {0.3 * H, 1e-6 * H * cos(0.5 * angles[i]), 1e-6 * H * sin(0.5 * angles[i])};
        ref_apply(&m, b, b);
        assert_continuous(&k, a, b, 4, w);
        if (angles[i] > REF_PI) { /* 1e-12 h from the plane of a face, 1e-6 h beyond its edge */
          double x[3] = {0.3 * H, -1e-6 * H, 0.5e-12 * H};
          ref_apply(&m, x, x);
          assert_continuous(&k, a, x, 4, w);
        }
        /* within the plane tolerance of both faces but not of the edge: moved onto the edge */
        double t[3] = {0.3 * H, 1.2e-12 * H * cos(0.5 * angles[i]),
                       1.2e-12 * H * sin(0.5 * angles[i])};
        ref_apply(&m, t, t);
        assert_abs(eval(&k, t, 4, w, g), angles[i] / (2.0 * REF_PI), 1e-10);
      }
    }
    /* box corner: 1/8 at the corner (both triangulations); continuous along its edges */
    for (int split = 0; split < 2; split++) {
      struct sph_wall_element b[6];
      box_corner(split, b);
      move_all(&m, 6, b);
      const double o[3] = {0, 0, 0};
      double a[3];
      ref_apply(&m, o, a);
      assert_abs(eval(&k, a, 6, b, g), 0.125, 1e-14);
      double near[3] = {1e-6 * H, 1.3e-6 * H, 0.7e-6 * H};
      ref_apply(&m, near, near);
      assert_continuous(&k, a, near, 6, b);
      /* on an edge and on a face of the box, within the support of the corner */
      double on[3] = {0.0, 0.0, 0.6 * H}, in_[3] = {1e-6 * H, 0.8e-6 * H, 0.6 * H};
      ref_apply(&m, on, on);
      ref_apply(&m, in_, in_);
      assert_continuous(&k, on, in_, 6, b);
      double face[3] = {0.3 * H, 0.0, 0.4 * H}, above[3] = {0.3 * H, 1e-6 * H, 0.4 * H};
      ref_apply(&m, face, face);
      ref_apply(&m, above, above);
      assert_continuous(&k, face, above, 6, b);
    }
  }
}

/* ---- cutting a flat wall ------------------------------------------------------------------- */

static void test_cut_independence_2d(void **state) {
  (void)state;
  double max_err = 0.0;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 41);
  struct sph_kernel k;
  sph_kernel_init(&k, 2, H);
  for (int trial = 0; trial < 10; trial++) {
    const double L = 6.0 * H;
    struct sph_wall_element coarse = ref_seg(-L, 0.0, L, 0.0), fine[10];
    double cuts[11];
    cuts[0] = -L;
    cuts[10] = L;
    for (int i = 1; i < 10; i++)
      cuts[i] = -L + 2.0 * L * (i + sabre_rng_uniform(&rng, -0.4, 0.4)) / 10.0;
    for (int i = 0; i < 10; i++) fine[i] = ref_seg(cuts[i], 0.0, cuts[i + 1], 0.0);
    struct ref_motion m = ref_motion_random(&rng, 2, 4.0 * H);
    ref_apply_element(&m, &coarse);
    move_all(&m, 10, fine);
    for (int i = 0; i < 40; i++) {
      double a[3] = {sabre_rng_uniform(&rng, -3.0, 3.0) * H, 0.0, 0.0};
      if (i < 10) {
        a[0] = cuts[3 + i % 5]; /* on a cut */
      } else if (i >= 20) {
        a[1] = sabre_rng_uniform(&rng, 0.0, 2.2) * H;
      }
      if (i >= 35) a[1] = pow(10.0, -sabre_rng_uniform(&rng, 3.0, 11.0)) * H;
      ref_apply(&m, a, a);
      double gc[3], gf[3];
      const double yc = eval(&k, a, 1, &coarse, gc), yf = eval(&k, a, 10, fine, gf);
      max_err = fmax(max_err, fabs(yf - yc));
      assert_abs(yf, yc, 1e-12);
      for (int c = 0; c < 3; c++) assert_abs(gf[c] * H, gc[c] * H, 1e-12);
    }
  }
  printf("flat wall cut 1 vs 10 segments: max |Δγ| = %.1e\n", max_err);
}

static void test_cut_independence_3d(void **state) {
  (void)state;
  double max_err = 0.0;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 43);
  struct sph_kernel k;
  sph_kernel_init(&k, 3, H);
  enum { N = 4 };
  for (int trial = 0; trial < 4; trial++) {
    const double L = 5.0 * H;
    const double c00[3] = {-L, -L, 0}, c10[3] = {L, -L, 0}, c11[3] = {L, L, 0}, c01[3] = {-L, L, 0};
    struct sph_wall_element coarse[2] = {ref_tri(c00, c10, c11), ref_tri(c00, c11, c01)};
    /* N×N grid with jittered interior nodes and random diagonals */
    double node[N + 1][N + 1][3];
    for (int i = 0; i <= N; i++)
      for (int j = 0; j <= N; j++) {
        const int interior = i > 0 && i < N && j > 0 && j < N;
        const double ji = interior ? sabre_rng_uniform(&rng, -0.3, 0.3) : 0.0;
        const double jj = interior ? sabre_rng_uniform(&rng, -0.3, 0.3) : 0.0;
        node[i][j][0] = -L + 2.0 * L * (i + ji) / N;
        node[i][j][1] = -L + 2.0 * L * (j + jj) / N;
        node[i][j][2] = 0.0;
      }
    struct sph_wall_element fine[2 * N * N];
    size_t nf = 0;
    for (int i = 0; i < N; i++)
      for (int j = 0; j < N; j++) {
        if (sabre_rng_uniform(&rng, 0.0, 1.0) < 0.5) {
          fine[nf++] = ref_tri(node[i][j], node[i + 1][j], node[i + 1][j + 1]);
          fine[nf++] = ref_tri(node[i][j], node[i + 1][j + 1], node[i][j + 1]);
        } else {
          fine[nf++] = ref_tri(node[i][j], node[i + 1][j], node[i][j + 1]);
          fine[nf++] = ref_tri(node[i + 1][j], node[i + 1][j + 1], node[i][j + 1]);
        }
      }
    struct ref_motion m = ref_motion_random(&rng, 3, 4.0 * H);
    move_all(&m, 2, coarse);
    move_all(&m, nf, fine);
    for (int i = 0; i < 30; i++) {
      double a[3];
      if (i < 6) { /* on an interior node of the fine mesh */
        memcpy(a, node[1 + i % 3][1 + (i / 3) % 3], sizeof a);
        a[2] = 0.0;
      } else if (i < 10) { /* on the middle of a fine edge */
        for (int c = 0; c < 3; c++) a[c] = 0.5 * (node[2][1 + i % 3][c] + node[2][2 + i % 2][c]);
        a[2] = 0.0;
      } else {
        a[0] = sabre_rng_uniform(&rng, -2.5, 2.5) * H;
        a[1] = sabre_rng_uniform(&rng, -2.5, 2.5) * H;
        a[2] = (i < 25 ? sabre_rng_uniform(&rng, 0.0, 2.2)
                       : pow(10.0, -sabre_rng_uniform(&rng, 3.0, 11.0))) *
               H;
      }
      ref_apply(&m, a, a);
      double gc[3], gf[3];
      const double yc = eval(&k, a, 2, coarse, gc), yf = eval(&k, a, nf, fine, gf);
      max_err = fmax(max_err, fabs(yf - yc));
      assert_abs(yf, yc, 1e-12);
      for (int c = 0; c < 3; c++) assert_abs(gf[c] * H, gc[c] * H, 1e-12);
    }
  }
  printf("flat wall cut 2 vs 32 triangles: max |Δγ| = %.1e\n", max_err);
}

/* ---- ∇γ_a = finite difference of γ_a ------------------------------------------------------- */

/* Closed star-shaped polygon (2D) or octahedron (3D) around the origin, all within the support of
 * its interior points, normals inward. Returns the element count. */
static size_t closed_wall(struct sabre_rng *rng, int dim, struct sph_wall_element *e,
                          double *radius) {
  if (dim == 1) {
    memset(e, 0, 2 * sizeof *e);
    e[0].x[0][0] = -sabre_rng_uniform(rng, 0.5, 1.5) * H;
    e[0].normal[0] = 1.0;
    e[1].x[0][0] = sabre_rng_uniform(rng, 0.5, 1.5) * H;
    e[1].normal[0] = -1.0;
    *radius = fmin(-e[0].x[0][0], e[1].x[0][0]);
    return 2;
  }
  if (dim == 2) {
    const int K = 9;
    double p[9][2];
    *radius = INFINITY;
    for (int j = 0; j < K; j++) {
      const double t = 2.0 * REF_PI * (j + sabre_rng_uniform(rng, -0.3, 0.3)) / K;
      const double r = sabre_rng_uniform(rng, 1.2, 2.5) * H;
      p[j][0] = r * cos(t);
      p[j][1] = r * sin(t);
    }
    for (int j = 0; j < K; j++) { /* counter-clockwise: the inside is on the left */
      e[j] = ref_seg(p[j][0], p[j][1], p[(j + 1) % K][0], p[(j + 1) % K][1]);
      const double d = -(p[j][0] * e[j].normal[0] + p[j][1] * e[j].normal[1]);
      *radius = fmin(*radius, d); /* distance of the origin from the edge's line */
    }
    return (size_t)K;
  }
  double v[6][3];
  memset(v, 0, sizeof v);
  for (int j = 0; j < 6; j++)
    v[j][j / 2] = (j % 2 ? -1.0 : 1.0) * sabre_rng_uniform(rng, 1.0, 2.0) * H;
  size_t n = 0;
  *radius = INFINITY;
  for (int sx = 0; sx < 2; sx++)
    for (int sy = 0; sy < 2; sy++)
      for (int sz = 0; sz < 2; sz++) {
        e[n] = ref_tri(v[sx], v[2 + sy], v[4 + sz]);
        const double d = e[n].normal[0] * v[sx][0] + e[n].normal[1] * v[sx][1] +
                         e[n].normal[2] * v[sx][2]; /* n·x on the face */
        if (d > 0.0) { /* outward: flip to point into the fluid (towards the origin) */
          for (int c = 0; c < 3; c++) e[n].normal[c] = -e[n].normal[c];
        }
        *radius = fmin(*radius, fabs(d));
        n++;
      }
  return n;
}

static void test_gradient_fd(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 47);
  double max_err = 0.0;
  for (int dim = 1; dim <= 3; dim++) {
    struct sph_kernel k;
    sph_kernel_init(&k, dim, H);
    for (int trial = 0; trial < 8; trial++) {
      struct sph_wall_element e[9];
      double radius;
      const size_t n = closed_wall(&rng, dim, e, &radius);
      for (int i = 0; i < 5; i++) {
        /* inside the inscribed ball, within 0.02 h .. of the walls for some */
        double a[3] = {0, 0, 0}, nn = 0.0;
        for (int c = 0; c < dim; c++) {
          a[c] = sabre_rng_uniform(&rng, -1.0, 1.0);
          nn += a[c] * a[c];
        }
        const double r = radius * sabre_rng_uniform(&rng, 0.0, 0.98) / sqrt(nn);
        for (int c = 0; c < dim; c++) a[c] *= r;
        double g[3];
        eval(&k, a, n, e, g);
        const double eps = 1e-5 * H;
        for (int c = 0; c < dim; c++) {
          double ap[3], am[3];
          memcpy(ap, a, sizeof ap);
          memcpy(am, a, sizeof am);
          ap[c] += eps;
          am[c] -= eps;
          const double fd = (eval(&k, ap, n, e, NULL) - eval(&k, am, n, e, NULL)) / (2.0 * eps);
          max_err = fmax(max_err, fabs(g[c] - fd) * H);
          assert_abs(g[c] * H, fd * H, 1e-8);
        }
      }
    }
  }
  printf("∇γ vs central differences (step 1e-5 h): max h|Δ| = %.1e\n", max_err);
}

/* ---- dynamic γ, M(4) ----------------------------------------------------------------------- */

/* A particle moving straight at the wall: trapezoidal integration of v·∇γ converges at 2nd order
 * to the geometric γ. */
static void test_dynamic(void **state) {
  (void)state;
  for (int dim = 1; dim <= 3; dim++) {
    struct sph_kernel k;
    sph_kernel_init(&k, dim, H);
    struct sph_wall_element e[4];
    const size_t n = plane_wall(dim, e);
    const int axis = dim == 1 ? 0 : dim - 1;
    const double T = 0.37, v[3] = {0.11 * H / T, 0.0, -1.6 * H / T}; /* from δ = 1.9h to 0.3h */
    double vel[3] = {0, 0, 0};
    vel[axis] = v[2];
    if (dim >= 2) vel[0] = v[0];
    double err[2];
    for (int level = 0; level < 2; level++) {
      const int steps = 100 << level;
      const double dt = T / steps;
      double a[3] = {0, 0, 0}, g_old[3], g_new[3];
      a[axis] = 1.9 * H;
      double gamma = eval(&k, a, n, e, g_old);
      for (int s = 0; s < steps; s++) {
        for (int c = 0; c < 3; c++) a[c] += vel[c] * dt;
        eval(&k, a, n, e, g_new);
        gamma = sph_gamma_dynamic_step(gamma, vel, g_old, vel, g_new, dim, dt);
        memcpy(g_old, g_new, sizeof g_old);
      }
      err[level] = fabs(gamma - eval(&k, a, n, e, NULL));
    }
    assert_true(err[0] < 1e-4);
    assert_true(err[1] < 1e-4);
    const double order = log2(err[0] / err[1]);
    assert_true(order > 1.8 && order < 2.2);
  }
  /* the formula itself: γ + dt/2 (v_old·∇γ_old + v_new·∇γ_new) */
  const double vo[3] = {1.5, -2.0, 0.25}, go[3] = {0.5, 0.125, -4.0}, vn[3] = {1.0, 3.0, -0.5},
               gn[3] = {2.0, 0.25, 1.0};
  assert_rel(sph_gamma_dynamic_step(0.75, vo, go, vn, gn, 3, 0.1), 0.75 + 0.05 * (-0.5 + 2.25),
             1e-15);
  assert_rel(sph_gamma_dynamic_step(0.75, vo, go, vn, gn, 2, 0.1), 0.75 + 0.05 * (0.5 + 2.75),
             1e-15);
}

/* ---- error codes --------------------------------------------------------------------------- */

static void expect_error(const struct sph_kernel *k, const double *a, size_t n,
                         const struct sph_wall_element *e) {
  double gamma = 0.0, g[3] = {0, 0, 0};
  assert_int_equal(sph_gamma_eval(k, a, n, e, &gamma, g), -1);
  assert_true(isnan(gamma) && isnan(g[0]) && isnan(g[1]) && isnan(g[2]));
}

static void test_errors(void **state) {
  (void)state;
  struct sph_kernel k2, k3, bad;
  sph_kernel_init(&k2, 2, H);
  sph_kernel_init(&k3, 3, H);
  memset(&bad, 0, sizeof bad);
  const double a[3] = {0.1 * H, 0.5 * H, 0.2 * H};
  struct sph_wall_element s = ref_seg(-H, 0, H, 0);
  double gamma, g[3];
  assert_int_equal(sph_gamma_eval(NULL, a, 1, &s, &gamma, g), -1);
  assert_int_equal(sph_gamma_eval(&k2, NULL, 1, &s, &gamma, g), -1);
  assert_int_equal(sph_gamma_eval(&k2, a, 1, &s, NULL, g), -1);
  assert_int_equal(sph_gamma_eval(&k2, a, 1, &s, &gamma, NULL), -1);
  expect_error(&k2, a, 1, NULL);
  expect_error(&bad, a, 1, &s);
  const double anan[3] = {NAN, 0.0, 0.0};
  expect_error(&k2, anan, 1, &s);
  struct sph_wall_element t = s;
  t.normal[1] = 0.9; /* not unit */
  expect_error(&k2, a, 1, &t);
  t = s;
  t.normal[0] = sin(1e-3), t.normal[1] = cos(1e-3); /* not perpendicular */
  expect_error(&k2, a, 1, &t);
  t = s;
  t.x[1][0] = t.x[0][0], t.x[1][1] = t.x[0][1]; /* zero length */
  expect_error(&k2, a, 1, &t);
  t = s;
  t.x[1][0] = INFINITY;
  expect_error(&k2, a, 1, &t);
  /* a zero-thickness plate: on it, no direction leads into the fluid on both sides */
  struct sph_wall_element plate[2] = {ref_seg(-H, 0, H, 0), ref_seg(H, 0, -H, 0)};
  const double on[3] = {0.3 * H, 0.0, 0.0};
  expect_error(&k2, on, 2, plate);
  double off[3] = {0.3 * H, 0.2 * H, 0.0};
  assert_int_equal(sph_gamma_eval(&k2, off, 2, plate, &gamma, g), 0);
  /* 3D: collinear vertices, normal not perpendicular; 1D: normal not ±1 */
  const double p0[3] = {0, 0, 0}, p1[3] = {H, 0, 0}, p2[3] = {0, H, 0}, p3[3] = {2 * H, 0, 0};
  struct sph_wall_element tri = ref_tri(p0, p1, p2);
  assert_int_equal(sph_gamma_eval(&k3, a, 1, &tri, &gamma, g), 0);
  struct sph_wall_element col = tri;
  memcpy(col.x[2], p3, sizeof p3);
  expect_error(&k3, a, 1, &col);
  col = tri;
  col.normal[0] = sin(1e-3), col.normal[2] = cos(1e-3);
  expect_error(&k3, a, 1, &col);
  struct sph_kernel k1;
  sph_kernel_init(&k1, 1, H);
  struct sph_wall_element p;
  memset(&p, 0, sizeof p);
  p.normal[0] = 0.5;
  expect_error(&k1, a, 1, &p);
}

/* ---- the solver's one-pass 3D pair path -------------------------------------------------- */

/* sph_gamma3d_pair (the frame's axes computed once per element, then term, ∇γ_as, the distance to
 * the triangle and to its plane from one frame) against sph_gamma_element and sph_element_distance
 * at random points around random triangles: near the plane, on it, beyond the support, over the
 * interior, edges and vertices; and sph_gamma3d_pair_offset against sph_gamma3d_pair: the same
 * term, ∇γ_as and plane distance, and the distance by sph_gamma3d_offset_distance; the lower
 * bound sph_gamma3d_offset_bound, equal to the plane distance where a faces the triangle. */
static void test_pair_path_3d(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 23);
  struct sph_kernel k;
  sph_kernel_init(&k, 3, H);
  double worst_term = 0.0, worst_grad = 0.0, worst_dist = 0.0, worst_off = 0.0;
  double worst_offset = 0.0, worst_bound = -INFINITY;
  int inside = 0, beyond = 0, by_offset = 0, on_plane = 0, sharp = 0, loose = 0;
  for (int trial = 0; trial < 400; trial++) {
    struct sph_wall_element e;
    double c[3];
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3; i++) e.x[j][i] = sabre_rng_uniform(&rng, -1.5 * H, 1.5 * H);
    double u[3], v[3];
    for (int m = 0; m < 3; m++) {
      u[m] = e.x[1][m] - e.x[0][m];
      v[m] = e.x[2][m] - e.x[0][m];
    }
    c[0] = u[1] * v[2] - u[2] * v[1];
    c[1] = u[2] * v[0] - u[0] * v[2];
    c[2] = u[0] * v[1] - u[1] * v[0];
    const double cn = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (cn < 0.05 * H * H) continue; /* a sliver: not what a mesh check lets through */
    const double sgn = trial % 2 ? 1.0 : -1.0;
    for (int i = 0; i < 3; i++) e.normal[i] = sgn * c[i] / cn;
    struct sph_tri_axes ax;
    sph_gamma3d_axes(&e, &ax);
    for (int t = 0; t < 10; t++) {
      /* a point of the triangle (barycentric, sometimes beyond an edge) lifted off its plane */
      double b1 = sabre_rng_uniform(&rng, -0.3, 1.0), b2 = sabre_rng_uniform(&rng, -0.3, 1.0);
      const double lift =
          t == 9 ? 0.0 : (t % 3 == 0 ? 1e-6 : 1.0) * sabre_rng_uniform(&rng, -2.6 * H, 2.6 * H);
      double a[3];
      for (int i = 0; i < 3; i++)
        a[i] = e.x[0][i] + b1 * (e.x[1][i] - e.x[0][i]) + b2 * (e.x[2][i] - e.x[0][i]) +
               lift * e.normal[i];
      double term, grad[3], dist, off, term0, grad0[3], q[3];
      sph_gamma3d_pair(&k, a, &e, &ax, NULL, &term, grad, &dist, &off);
      /* the solver's path from the offset to the first vertex: the same to round-off, except
       * on the plane, which it leaves to sph_gamma3d_pair */
      double d[3], term1, grad1[3], off1;
      for (int i = 0; i < 3; i++) d[i] = a[i] - ax.x0[i];
      if (sph_gamma3d_pair_offset(&k, d, &ax, NULL, &term1, grad1, &off1) == 0) {
        /* Both paths see the point's position in the plane to round-off, ~1e-16 H; within |δ| of
         * an edge the term (a solid angle) varies by O(1) over O(|δ|) in the plane, so the
         * paths may differ by ~1e-16 H/|δ|: the differences are scaled by min(1, |δ|/H). */
        const double cond = fmin(1.0, fabs(off) / H);
        const double exact1 = sph_gamma3d_offset_distance(d, &ax);
        const double bound1 = sph_gamma3d_offset_bound(d, &ax);
        double dmax = fmax(fabs(term1 - term), fmax(fabs(exact1 - dist), fabs(off1 - off)) / H);
        /* the bound: never above the distance, and equal to it (the plane distance) when the
         * point faces the triangle */
        worst_bound = fmax(worst_bound, (bound1 - dist) / H);
        if (b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0) {
          assert_true(bound1 == fabs(off1));
          sharp++;
        }
        /* beyond the support exactly zero, the bound below 2h or not */
        if (dist >= 2.0 * H) {
          assert_true(term1 == 0.0);
          for (int i = 0; i < 3; i++) assert_true(grad1[i] == 0.0);
          if (bound1 < 2.0 * H) loose++;
        }
        for (int i = 0; i < 3; i++) dmax = fmax(dmax, H * fabs(grad1[i] - grad[i]));
        worst_offset = fmax(worst_offset, dmax * cond);
        by_offset++;
      } else {
        assert_true(fabs(off) <= SPH_GAMMA_PLANE_TOL * H);
        on_plane++;
      }
      sph_gamma_element(&k, a, &e, &term0, grad0);
      const double dist0 = sph_element_distance(3, (const double(*)[3])e.x, a, q);
      double off0 = 0.0;
      for (int i = 0; i < 3; i++) off0 += (a[i] - q[i]) * e.normal[i];
      if (dist0 < 2.0 * H) {
        worst_term = fmax(worst_term, fabs(term - term0));
        for (int i = 0; i < 3; i++) worst_grad = fmax(worst_grad, H * fabs(grad[i] - grad0[i]));
        inside++;
      } else {
        /* beyond the support both give exactly zero */
        assert_true(term == 0.0 && term0 == 0.0);
        for (int i = 0; i < 3; i++) assert_true(grad[i] == 0.0 && grad0[i] == 0.0);
        beyond++;
      }
      worst_dist = fmax(worst_dist, fabs(dist - dist0) / H);
      worst_off = fmax(worst_off, fabs(off - off0) / H);
    }
  }
  printf(
      "pair path vs element + distance: %d pairs in the support, %d beyond; |Δterm| %.1e, "
      "h|Δgrad| %.1e, |Δdist|/h %.1e, |Δoff|/h %.1e\n",
      inside, beyond, worst_term, worst_grad, worst_dist, worst_off);
  printf(
      "offset path vs pair path: %d points (%d on the plane left to the pair path), largest "
      "difference times min(1, |δ|/h): %.1e; its lower bound of the distance: at most %.1e h "
      "above it, equal to the plane distance at %d points facing the triangle, below 2h at %d "
      "points beyond the support (zero there)\n",
      by_offset, on_plane, worst_offset, worst_bound, sharp, loose);
  assert_true(by_offset > 2000 && on_plane > 100 && sharp > 500 && loose > 20);
  assert_true(worst_bound <= 1e-14);
  assert_true(worst_offset <= 1e-14);
  assert_true(inside > 1500 && beyond > 200);
  assert_true(worst_term <= 1e-14);
  assert_true(worst_grad <= 1e-14);
  assert_true(worst_dist <= 1e-14);
  assert_true(worst_off <= 1e-14);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_far_field),
      cmocka_unit_test(test_plane_distance),
      cmocka_unit_test(test_on_wall_2d),
      cmocka_unit_test(test_on_wall_3d),
      cmocka_unit_test(test_cut_independence_2d),
      cmocka_unit_test(test_cut_independence_3d),
      cmocka_unit_test(test_gradient_fd),
      cmocka_unit_test(test_dynamic),
      cmocka_unit_test(test_errors),
      cmocka_unit_test(test_pair_path_3d),
  };
  return cmocka_run_group_tests(tests, sabre_setup_gsl_traps, NULL);
}
