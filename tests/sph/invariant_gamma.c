/*
 * Slower checks of the wall integrals (label `invariant`):
 *  - large random sweeps of gamma_term and ∇γ_as against brute-force GSL quadrature (1e-10);
 *  - γ_a from sph_gamma_eval against the definition J(2), γ_a = ∫_{Ω ∩ B(a)} w dV, integrated by
 *    brute force in polar (2D) or spherical (3D) coordinates around a, for random polygons and
 *    tetrahedra, with a inside, near the walls, and on edges and vertices (solid-angle limit).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sabre/sph_walls.h"
#include "test_gamma_ref.h"
#include "testutil.h"

static const double H = 0.0237;

static void test_sweep_segments(void **state) {
  (void)state;
  ref_sweep_segments(3000, 201, H);
}

static void test_sweep_triangles(void **state) {
  (void)state;
  ref_sweep_triangles(400, 203, H);
}

/* W_d(t) = ∫_0^min(t, 2h) w r^(d−1) dr, one 21-point Gauss–Kronrod rule (exact: polynomial). */
static double radial(const struct sph_kernel *k, double t) {
  struct ref_radial rr = {k, k->dim - 1};
  gsl_function F = {ref_radial_integrand, &rr};
  double result, abserr, resabs, resasc;
  gsl_integration_qk21(&F, 0.0, fmin(t, 2.0 * k->h), &result, &abserr, &resabs, &resasc);
  return result;
}

/* ---- 2D: polygons --------------------------------------------------------------------------- */

struct polygon {
  int n;
  double p[12][2]; /* counter-clockwise */
};

static int inside_polygon(const struct polygon *P, double x, double y) {
  int in = 0;
  for (int i = 0, j = P->n - 1; i < P->n; j = i++) {
    const double *a = P->p[i], *b = P->p[j];
    if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0]) in = !in;
  }
  return in;
}

struct ray2 {
  const struct sph_kernel *k;
  const struct polygon *P;
  const double *a;
};

/* Radial integral of w r along the ray at angle th: sum over the parts of [0, 2h] inside Ω. */
static double ray2_integrand(double th, void *p) {
  const struct ray2 *c = p;
  const double ux = cos(th), uy = sin(th), R = 2.0 * c->k->h;
  double t[32];
  int nt = 0;
  t[nt++] = 0.0;
  for (int i = 0; i < c->P->n; i++) {
    const double *p0 = c->P->p[i], *p1 = c->P->p[(i + 1) % c->P->n];
    const double ex = p1[0] - p0[0], ey = p1[1] - p0[1];
    const double den = ux * ey - uy * ex;
    if (fabs(den) < 1e-300) continue;
    const double wx = p0[0] - c->a[0], wy = p0[1] - c->a[1];
    const double tt = (wx * ey - wy * ex) / den, s = (wx * uy - wy * ux) / den;
    if (tt > 0.0 && tt < R && s >= 0.0 && s <= 1.0) t[nt++] = tt;
  }
  t[nt++] = R;
  for (int i = 1; i < nt; i++)
    for (int j = i; j > 0 && t[j - 1] > t[j]; j--) {
      const double x = t[j];
      t[j] = t[j - 1];
      t[j - 1] = x;
    }
  double sum = 0.0;
  for (int i = 0; i + 1 < nt; i++) {
    const double mid = 0.5 * (t[i] + t[i + 1]);
    if (t[i + 1] > t[i] && inside_polygon(c->P, c->a[0] + mid * ux, c->a[1] + mid * uy))
      sum += radial(c->k, t[i + 1]) - radial(c->k, t[i]);
  }
  return sum;
}

static double gamma_polygon_ref(const struct sph_kernel *k, const struct polygon *P,
                                const double *a, gsl_integration_workspace *ws) {
  struct ray2 c = {k, P, a};
  double brk[64];
  int nb = 0;
  const double R = 2.0 * k->h;
  for (int i = 0; i < P->n; i++) {
    const double *p0 = P->p[i], *p1 = P->p[(i + 1) % P->n];
    const double dx = p0[0] - a[0], dy = p0[1] - a[1];
    if (hypot(dx, dy) > 1e-14 * k->h) brk[nb++] = fmod(atan2(dy, dx) + 2.0 * REF_PI, 2.0 * REF_PI);
    /* where the edge crosses the support circle */
    const double ex = p1[0] - p0[0], ey = p1[1] - p0[1];
    const double A = ex * ex + ey * ey, B = 2.0 * (dx * ex + dy * ey),
                 C = dx * dx + dy * dy - R * R;
    const double disc = B * B - 4.0 * A * C;
    if (disc > 0.0)
      for (int sgn = -1; sgn <= 1; sgn += 2) {
        const double s = (-B + sgn * sqrt(disc)) / (2.0 * A);
        if (s > 0.0 && s < 1.0)
          brk[nb++] = fmod(atan2(dy + s * ey, dx + s * ex) + 2.0 * REF_PI, 2.0 * REF_PI);
      }
  }
  gsl_function F = {ray2_integrand, &c};
  return ref_quad(&F, 0.0, 2.0 * REF_PI, brk, nb, 1e-13, 1e-13, ws);
}

static void test_polygons(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 211);
  struct sph_kernel k;
  sph_kernel_init(&k, 2, H);
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(4000);
  double max_err = 0.0;
  for (int trial = 0; trial < 12; trial++) {
    struct polygon P;
    P.n = 5 + trial % 6;
    for (int j = 0; j < P.n; j++) { /* star-shaped about the origin, possibly non-convex */
      const double t = 2.0 * REF_PI * (j + sabre_rng_uniform(&rng, -0.3, 0.3)) / P.n;
      const double r = sabre_rng_uniform(&rng, 0.8, 3.0) * H;
      P.p[j][0] = r * cos(t);
      P.p[j][1] = r * sin(t);
    }
    struct sph_wall_element e[12];
    for (int j = 0; j < P.n; j++)
      e[j] = ref_seg(P.p[j][0], P.p[j][1], P.p[(j + 1) % P.n][0], P.p[(j + 1) % P.n][1]);
    for (int i = 0; i < 14; i++) {
      double a[3] = {0.0, 0.0, 0.0};
      if (i < 3) { /* on a vertex */
        a[0] = P.p[i][0];
        a[1] = P.p[i][1];
      } else if (i < 5) { /* on an edge */
        const double s = sabre_rng_uniform(&rng, 0.1, 0.9);
        for (int c = 0; c < 2; c++) a[c] = (1.0 - s) * P.p[i][c] + s * P.p[(i + 1) % P.n][c];
      } else {
        do {
          a[0] = sabre_rng_uniform(&rng, -3.0, 3.0) * H;
          a[1] = sabre_rng_uniform(&rng, -3.0, 3.0) * H;
        } while (!inside_polygon(&P, a[0], a[1]));
      }
      double gamma, g[3];
      assert_int_equal(sph_gamma_eval(&k, a, (size_t)P.n, e, &gamma, g), 0);
      const double ref = gamma_polygon_ref(&k, &P, a, ws);
      max_err = fmax(max_err, fabs(gamma - ref));
      assert_abs(gamma, ref, 1e-10);
    }
  }
  printf("2D polygons: max |γ − J(2) quadrature| = %.2e\n", max_err);
  gsl_integration_workspace_free(ws);
}

/* ---- 3D: tetrahedra ------------------------------------------------------------------------- */

struct tet {
  double v[4][3];
  double n[4][3]; /* outward unit normal of the face opposite v[i] */
  double d[4];    /* face: n·x = d */
};

static void tet_setup(struct tet *T) {
  for (int i = 0; i < 4; i++) {
    const double *p0 = T->v[(i + 1) % 4], *p1 = T->v[(i + 2) % 4], *p2 = T->v[(i + 3) % 4];
    double u[3], w[3];
    for (int c = 0; c < 3; c++) {
      u[c] = p1[c] - p0[c];
      w[c] = p2[c] - p0[c];
    }
    double nn[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                    u[0] * w[1] - u[1] * w[0]};
    const double len = sqrt(dot3r(nn, nn));
    for (int c = 0; c < 3; c++) nn[c] /= len;
    double r[3];
    for (int c = 0; c < 3; c++) r[c] = T->v[i][c] - p0[c];
    if (dot3r(nn, r) > 0.0)
      for (int c = 0; c < 3; c++) nn[c] = -nn[c];
    memcpy(T->n[i], nn, sizeof nn);
    T->d[i] = dot3r(nn, p0);
  }
}

struct ray3 {
  const struct sph_kernel *k;
  const struct tet *T;
  const double *a;
  double phi;
  const double (*planes)[3];
  int nplanes;
  gsl_integration_workspace *inner;
};

static double ray3_mu_integrand(double mu, void *p) {
  const struct ray3 *c = p;
  const double st = sqrt(fmax(0.0, 1.0 - mu * mu));
  const double u[3] = {st * cos(c->phi), st * sin(c->phi), mu};
  double t = 2.0 * c->k->h;
  for (int f = 0; f < 4; f++) {
    const double un = dot3r(c->T->n[f], u);
    if (un > 0.0) t = fmin(t, fmax(0.0, (c->T->d[f] - dot3r(c->T->n[f], c->a)) / un));
  }
  return radial(c->k, t);
}

static double ray3_phi_integrand(double phi, void *p) {
  struct ray3 *c = p;
  c->phi = phi;
  double brk[16];
  int nb = 0;
  for (int i = 0; i < c->nplanes; i++) { /* directions in a plane through a: kinks or jumps */
    const double *nu = c->planes[i];
    const double A = nu[0] * cos(phi) + nu[1] * sin(phi);
    if (fabs(nu[2]) > 1e-14) brk[nb++] = -A * (nu[2] > 0.0 ? 1.0 : -1.0) / hypot(A, nu[2]);
  }
  gsl_function F = {ray3_mu_integrand, c};
  return ref_quad(&F, -1.0, 1.0, brk, nb, 1e-14, 1e-13, c->inner);
}

static double gamma_tet_ref(const struct sph_kernel *k, const struct tet *T, const double *a,
                            gsl_integration_workspace *wo, gsl_integration_workspace *wi) {
  double planes[10][3];
  int np = 0;
  for (int i = 0; i < 4; i++)
    for (int j = i + 1; j < 4; j++) { /* the plane through a and each edge */
      double r0[3], r1[3];
      for (int c = 0; c < 3; c++) {
        r0[c] = T->v[i][c] - a[c];
        r1[c] = T->v[j][c] - a[c];
      }
      double nn[3] = {r0[1] * r1[2] - r0[2] * r1[1], r0[2] * r1[0] - r0[0] * r1[2],
                      r0[0] * r1[1] - r0[1] * r1[0]};
      const double len = sqrt(dot3r(nn, nn));
      if (len > 1e-12 * H * H) {
        for (int c = 0; c < 3; c++) planes[np][c] = nn[c] / len;
        np++;
      }
    }
  for (int f = 0; f < 4; f++) /* faces through a */
    if (fabs(dot3r(T->n[f], a) - T->d[f]) < 1e-13 * H)
      memcpy(planes[np++], T->n[f], 3 * sizeof(double));
  double brk[8];
  int nb = 0;
  for (int i = 0; i < 4; i++) {
    const double dx = T->v[i][0] - a[0], dy = T->v[i][1] - a[1];
    if (hypot(dx, dy) > 1e-13 * H) brk[nb++] = fmod(atan2(dy, dx) + 2.0 * REF_PI, 2.0 * REF_PI);
  }
  struct ray3 c = {k, T, a, 0.0, (const double(*)[3])planes, np, wi};
  gsl_function F = {ray3_phi_integrand, &c};
  return ref_quad(&F, 0.0, 2.0 * REF_PI, brk, nb, 1e-12, 1e-12, wo);
}

static void test_tetrahedra(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 223);
  struct sph_kernel k;
  sph_kernel_init(&k, 3, H);
  gsl_integration_workspace *wo = gsl_integration_workspace_alloc(4000);
  gsl_integration_workspace *wi = gsl_integration_workspace_alloc(4000);
  double max_err = 0.0;
  for (int trial = 0; trial < 4; trial++) {
    struct tet T;
    double vol;
    do {
      for (int i = 0; i < 4; i++)
        for (int c = 0; c < 3; c++) T.v[i][c] = sabre_rng_uniform(&rng, -2.0, 2.0) * H;
      double u[3], v[3], w[3];
      for (int c = 0; c < 3; c++) {
        u[c] = T.v[1][c] - T.v[0][c];
        v[c] = T.v[2][c] - T.v[0][c];
        w[c] = T.v[3][c] - T.v[0][c];
      }
      vol = fabs(u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                 u[2] * (v[0] * w[1] - v[1] * w[0])) /
            6.0;
    } while (vol < 1.0 * H * H * H);
    tet_setup(&T);
    struct sph_wall_element e[4];
    for (int f = 0; f < 4; f++) {
      e[f] = ref_tri(T.v[(f + 1) % 4], T.v[(f + 2) % 4], T.v[(f + 3) % 4]);
      if (dot3r(e[f].normal, T.n[f]) > 0.0) /* walls' normals point into the fluid */
        e[f] = ref_tri(T.v[(f + 1) % 4], T.v[(f + 3) % 4], T.v[(f + 2) % 4]);
    }
    for (int i = 0; i < 4; i++) {
      double a[3];
      double b[4];
      if (i == 0) { /* a vertex */
        memcpy(a, T.v[trial % 4], sizeof a);
      } else if (i == 1) { /* on an edge */
        const double s = sabre_rng_uniform(&rng, 0.2, 0.8);
        for (int c = 0; c < 3; c++) a[c] = (1.0 - s) * T.v[0][c] + s * T.v[1][c];
      } else { /* on a face, then inside */
        double sum = 0.0;
        for (int j = 0; j < 4; j++) sum += (b[j] = sabre_rng_uniform(&rng, 0.05, 1.0));
        if (i == 2) sum -= b[3], b[3] = 0.0;
        for (int c = 0; c < 3; c++) {
          a[c] = 0.0;
          for (int j = 0; j < 4; j++) a[c] += b[j] / sum * T.v[j][c];
        }
      }
      double gamma, g[3];
      assert_int_equal(sph_gamma_eval(&k, a, 4, e, &gamma, g), 0);
      const double ref = gamma_tet_ref(&k, &T, a, wo, wi);
      max_err = fmax(max_err, fabs(gamma - ref));
      assert_abs(gamma, ref, 1e-10);
    }
  }
  printf("3D tetrahedra: max |γ − J(2) quadrature| = %.2e\n", max_err);
  gsl_integration_workspace_free(wo);
  gsl_integration_workspace_free(wi);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_sweep_segments),
      cmocka_unit_test(test_sweep_triangles),
      cmocka_unit_test(test_polygons),
      cmocka_unit_test(test_tetrahedra),
  };
  return cmocka_run_group_tests(tests, sabre_setup_gsl_traps, NULL);
}
