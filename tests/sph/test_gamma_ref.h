/*
 * Shared helpers of the γ tests (test_gamma*.c, invariant_gamma.c): wall elements, rigid motions,
 * and brute-force references by GSL adaptive quadrature of the definitions, independent of the
 * closed forms in sph/src/walls/:
 *   ∇γ_as       = ∫_s w(|x − a|) dS n_s                       J(3)
 *   gamma_term  = ∫_s G_d(|x − a|) ((x − a)·n_s)/|x − a|^d dS  (docs/sph-gamma.md G1)
 *   G_d(r)      = ∫_0^r w ρ^(d−1) dρ − 1/ω_d
 *   P_d(z)      = ∫_{x_n = z} w dS   (marginal of the kernel across a plane)
 * Every helper is static: each test is one translation unit.
 */
#ifndef SABRE_TEST_GAMMA_REF_H
#define SABRE_TEST_GAMMA_REF_H

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/sph_walls.h"
#include "testutil.h"

#define REF_PI 3.14159265358979323846

/* ------------------------------------------------------------------------------------------ */
/* Elements and rigid motions                                                                 */

/** 2D segment x0 → x1 with the fluid on its left. */
static inline struct sph_wall_element ref_seg(double x0, double y0, double x1, double y1) {
  struct sph_wall_element e;
  memset(&e, 0, sizeof e);
  e.x[0][0] = x0;
  e.x[0][1] = y0;
  e.x[1][0] = x1;
  e.x[1][1] = y1;
  const double len = hypot(x1 - x0, y1 - y0);
  e.normal[0] = -(y1 - y0) / len;
  e.normal[1] = (x1 - x0) / len;
  return e;
}

/** 3D triangle p0, p1, p2 with the fluid on the side from which they turn counter-clockwise. */
static inline struct sph_wall_element ref_tri(const double *p0, const double *p1,
                                              const double *p2) {
  struct sph_wall_element e;
  memset(&e, 0, sizeof e);
  for (int i = 0; i < 3; i++) {
    e.x[0][i] = p0[i];
    e.x[1][i] = p1[i];
    e.x[2][i] = p2[i];
  }
  double u[3], v[3];
  for (int i = 0; i < 3; i++) {
    u[i] = p1[i] - p0[i];
    v[i] = p2[i] - p0[i];
  }
  double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double n = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  for (int i = 0; i < 3; i++) e.normal[i] = c[i] / n;
  return e;
}

/** Rigid motion x ↦ R x + t (rotation about z in 2D). */
struct ref_motion {
  double R[3][3];
  double t[3];
};

static inline struct ref_motion ref_motion_random(struct sabre_rng *rng, int dim, double shift) {
  struct ref_motion m;
  memset(&m, 0, sizeof m);
  if (dim == 3) {
    /* uniform unit quaternion */
    double q[4], n = 0.0;
    do {
      n = 0.0;
      for (int i = 0; i < 4; i++) {
        q[i] = sabre_rng_uniform(rng, -1.0, 1.0);
        n += q[i] * q[i];
      }
    } while (n > 1.0 || n < 1e-3);
    n = sqrt(n);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    memcpy(m.R, R, sizeof R);
  } else {
    const double th = sabre_rng_uniform(rng, 0.0, 2.0 * REF_PI);
    m.R[0][0] = cos(th);
    m.R[0][1] = -sin(th);
    m.R[1][0] = sin(th);
    m.R[1][1] = cos(th);
    m.R[2][2] = 1.0;
  }
  for (int i = 0; i < dim; i++) m.t[i] = sabre_rng_uniform(rng, -shift, shift);
  return m;
}

static inline void ref_apply(const struct ref_motion *m, const double *x, double *y) {
  double r[3];
  for (int i = 0; i < 3; i++) r[i] = m->R[i][0] * x[0] + m->R[i][1] * x[1] + m->R[i][2] * x[2];
  for (int i = 0; i < 3; i++) y[i] = r[i] + m->t[i];
}

static inline void ref_apply_vec(const struct ref_motion *m, const double *x, double *y) {
  double r[3];
  for (int i = 0; i < 3; i++) r[i] = m->R[i][0] * x[0] + m->R[i][1] * x[1] + m->R[i][2] * x[2];
  memcpy(y, r, sizeof r);
}

static inline void ref_apply_element(const struct ref_motion *m, struct sph_wall_element *e) {
  for (int j = 0; j < 3; j++) ref_apply(m, e->x[j], e->x[j]);
  ref_apply_vec(m, e->normal, e->normal);
}

/* ------------------------------------------------------------------------------------------ */
/* Quadrature                                                                                  */

/** Adaptive Gauss–Kronrod on [a, b] with optional interior breakpoints (sorted and filtered
 *  here); fails the test unless GSL reaches epsabs (exits on round-off are accepted when the
 *  summed error estimate is within max(100 epsabs, 1e-11 |result|)). */
static inline double ref_quad(gsl_function *F, double a, double b, const double *brk, int nbrk,
                              double epsabs, double epsrel, gsl_integration_workspace *ws) {
  double pts[32];
  int np = 0;
  pts[np++] = a;
  double sorted[30];
  int ns = 0;
  for (int i = 0; i < nbrk && ns < 30; i++)
    if (brk[i] > a && brk[i] < b && isfinite(brk[i])) sorted[ns++] = brk[i];
  for (int i = 1; i < ns; i++)
    for (int j = i; j > 0 && sorted[j - 1] > sorted[j]; j--) {
      const double t = sorted[j];
      sorted[j] = sorted[j - 1];
      sorted[j - 1] = t;
    }
  for (int i = 0; i < ns; i++)
    if (sorted[i] > pts[np - 1] + 1e-15 * (b - a)) pts[np++] = sorted[i];
  if (b > pts[np - 1]) pts[np++] = b;
  if (np < 2) return 0.0;
  /* adaptive bisection (no extrapolation: it misjudges the near-singular peaks) per piece */
  double result = 0.0, abserr_sum = 0.0;
  int status = GSL_SUCCESS;
  for (int i = 0; i + 1 < np; i++) {
    double r = 0.0, abserr = 0.0;
    const int st = gsl_integration_qag(F, pts[i], pts[i + 1], epsabs / (np - 1), epsrel, ws->limit,
                                       GSL_INTEG_GAUSS31, ws, &r, &abserr);
    if (st != GSL_SUCCESS) status = st;
    result += r;
    abserr_sum += abserr;
  }
  if (status != GSL_SUCCESS && abserr_sum > fmax(100.0 * epsabs, 1e-11 * fabs(result))) {
    fprintf(stderr, "ref_quad: GSL status %d (%s), abserr %.3e > %.3e on [%.17g, %.17g]\n", status,
            gsl_strerror(status), abserr_sum, epsabs, a, b);
    fail();
  }
  return result;
}

struct ref_radial {
  const struct sph_kernel *k;
  int power;
};

static inline double ref_radial_integrand(double r, void *p) {
  const struct ref_radial *rr = p;
  return sph_kernel_w(rr->k, r) * pow(r, rr->power);
}

/** G_d(r) = ∫_0^r w ρ^(d−1) dρ − 1/ω_d: one 21-point Gauss–Kronrod rule, exact for the degree-7
 *  polynomial integrand inside the support. */
static inline double ref_G(const struct sph_kernel *k, double r) {
  const double omega[4] = {0.0, 2.0, 2.0 * REF_PI, 4.0 * REF_PI};
  struct ref_radial rr = {k, k->dim - 1};
  gsl_function F = {ref_radial_integrand, &rr};
  double result, abserr, resabs, resasc;
  gsl_integration_qk21(&F, 0.0, fmin(r, 2.0 * k->h), &result, &abserr, &resabs, &resasc);
  return result - 1.0 / omega[k->dim];
}

/* 2D segment: integrand along the abscissa t ∈ [0, L]. */
struct ref_seg_ctx {
  const struct sph_kernel *k;
  const double *a;
  const struct sph_wall_element *e;
  double tan[2];
  int want_term;
};

static inline double ref_seg_integrand(double t, void *p) {
  const struct ref_seg_ctx *c = p;
  const double rx = c->e->x[0][0] + t * c->tan[0] - c->a[0];
  const double ry = c->e->x[0][1] + t * c->tan[1] - c->a[1];
  const double r = hypot(rx, ry);
  if (!c->want_term) return sph_kernel_w(c->k, r);
  if (r >= 2.0 * c->k->h) return 0.0;
  return ref_G(c->k, r) * (rx * c->e->normal[0] + ry * c->e->normal[1]) / (r * r);
}

/** Brute-force gamma_term and ∇γ_as for a 2D segment (abs. accuracy ~1e-13, 1e-13/h). */
static inline void ref_segment(const struct sph_kernel *k, const double *a,
                               const struct sph_wall_element *e, double *term, double grad[3],
                               gsl_integration_workspace *ws) {
  struct ref_seg_ctx c = {k, a, e, {0, 0}, 0};
  const double L = hypot(e->x[1][0] - e->x[0][0], e->x[1][1] - e->x[0][1]);
  c.tan[0] = (e->x[1][0] - e->x[0][0]) / L;
  c.tan[1] = (e->x[1][1] - e->x[0][1]) / L;
  const double tf = (a[0] - e->x[0][0]) * c.tan[0] + (a[1] - e->x[0][1]) * c.tan[1];
  const double delta =
      fabs((a[0] - e->x[0][0]) * e->normal[0] + (a[1] - e->x[0][1]) * e->normal[1]);
  const double h = k->h;
  double brk[16] = {tf};
  int nb = 1;
  for (double f = 1.0; f <= 1e6 && delta * f < h; f *= 10.0) { /* resolve the peak of width δ */
    brk[nb++] = tf - delta * f;
    brk[nb++] = tf + delta * f;
  }
  if (delta < 2.0 * h) {
    const double R = sqrt(4.0 * h * h - delta * delta);
    brk[nb++] = tf - R;
    brk[nb++] = tf + R;
  }
  gsl_function F = {ref_seg_integrand, &c};
  const double iw = ref_quad(&F, 0.0, L, brk, nb, 1e-14 / h, 1e-13, ws);
  c.want_term = 1;
  *term = ref_quad(&F, 0.0, L, brk, nb, 1e-13, 1e-13, ws);
  for (int i = 0; i < 3; i++) grad[i] = i < 2 ? iw * e->normal[i] : 0.0;
}

/* 3D triangle x0 + u d1 + v d2: inner over v ∈ [0, 1 − u], outer over u ∈ [0, 1]. */
struct ref_tri_ctx {
  const struct sph_kernel *k;
  const double *a;
  const struct sph_wall_element *e;
  double d1[3], d2[3], jac;
  double u;
  int want_term;
  gsl_integration_workspace *inner;
  double epsabs_inner;
};

static inline double ref_tri_inner_integrand(double v, void *p) {
  const struct ref_tri_ctx *c = p;
  double r[3];
  for (int i = 0; i < 3; i++) r[i] = c->e->x[0][i] + c->u * c->d1[i] + v * c->d2[i] - c->a[i];
  const double rn = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  if (!c->want_term) return sph_kernel_w(c->k, rn);
  if (rn >= 2.0 * c->k->h) return 0.0;
  const double rdotn = r[0] * c->e->normal[0] + r[1] * c->e->normal[1] + r[2] * c->e->normal[2];
  return ref_G(c->k, rn) * rdotn / (rn * rn * rn);
}

static inline double dot3r(const double *x, const double *y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

static inline double ref_tri_outer_integrand(double u, void *p) {
  struct ref_tri_ctx *c = p;
  c->u = u;
  const double h = c->k->h;
  double b[3];
  for (int i = 0; i < 3; i++) b[i] = c->e->x[0][i] + u * c->d1[i] - c->a[i];
  const double dd = dot3r(c->d2, c->d2), bd = dot3r(b, c->d2), bb = dot3r(b, b);
  double brk[16] = {-bd / dd};
  int nb = 1;
  const double dist = sqrt(fmax(bb - bd * bd / dd, 0.0)); /* from a to the inner line */
  for (double f = 1.0; f <= 1e6 && dist * f < h; f *= 10.0) {
    brk[nb++] = (-bd - dist * f * sqrt(dd)) / dd;
    brk[nb++] = (-bd + dist * f * sqrt(dd)) / dd;
  }
  const double disc = bd * bd - dd * (bb - 4.0 * h * h);
  if (disc > 0.0) {
    brk[nb++] = (-bd - sqrt(disc)) / dd;
    brk[nb++] = (-bd + sqrt(disc)) / dd;
  }
  gsl_function F = {ref_tri_inner_integrand, c};
  return ref_quad(&F, 0.0, 1.0 - u, brk, nb, c->epsabs_inner, 1e-13, c->inner) * c->jac;
}

/** Brute-force gamma_term and ∇γ_as for a 3D triangle by nested adaptive quadrature. */
static inline void ref_triangle(const struct sph_kernel *k, const double *a,
                                const struct sph_wall_element *e, double *term, double grad[3],
                                gsl_integration_workspace *ws_outer,
                                gsl_integration_workspace *ws_inner) {
  struct ref_tri_ctx c;
  memset(&c, 0, sizeof c);
  c.k = k;
  c.a = a;
  c.e = e;
  c.inner = ws_inner;
  for (int i = 0; i < 3; i++) {
    c.d1[i] = e->x[1][i] - e->x[0][i];
    c.d2[i] = e->x[2][i] - e->x[0][i];
  }
  const double cr[3] = {c.d1[1] * c.d2[2] - c.d1[2] * c.d2[1],
                        c.d1[2] * c.d2[0] - c.d1[0] * c.d2[2],
                        c.d1[0] * c.d2[1] - c.d1[1] * c.d2[0]};
  c.jac = sqrt(dot3r(cr, cr));
  const double h = k->h;
  /* outer breakpoints: the foot point, and the u where the inner line touches the support */
  double r0[3];
  for (int i = 0; i < 3; i++) r0[i] = a[i] - e->x[0][i];
  const double g11 = dot3r(c.d1, c.d1), g12 = dot3r(c.d1, c.d2), g22 = dot3r(c.d2, c.d2);
  const double b1 = dot3r(r0, c.d1), b2 = dot3r(r0, c.d2), det = g11 * g22 - g12 * g12;
  double brk[16] = {(b1 * g22 - b2 * g12) / det};
  int nb = 1;
  const double delta = fabs(dot3r(r0, e->normal));
  for (double f = 1.0; f <= 1e6 && delta * f < h; f *= 10.0) {
    brk[nb++] = brk[0] - delta * f / sqrt(g11);
    brk[nb++] = brk[0] + delta * f / sqrt(g11);
  }
  {
    /* the inner line {x0 + u d1 + v d2} is at distance 2h from a when |P(b0 + u d1)|² = 4h²,
     * b0 = x0 − a and P the projection orthogonal to d2 */
    double pb[3], pd[3];
    for (int i = 0; i < 3; i++) {
      pb[i] = -r0[i] + b2 / g22 * c.d2[i];
      pd[i] = c.d1[i] - g12 / g22 * c.d2[i];
    }
    const double A = dot3r(pd, pd), B = 2.0 * dot3r(pb, pd), C = dot3r(pb, pb) - 4.0 * h * h;
    const double disc = B * B - 4.0 * A * C;
    if (disc > 0.0) {
      brk[nb++] = (-B - sqrt(disc)) / (2.0 * A);
      brk[nb++] = (-B + sqrt(disc)) / (2.0 * A);
    }
  }
  gsl_function F = {ref_tri_outer_integrand, &c};
  c.epsabs_inner = 1e-14 / (h * h);
  const double iw = ref_quad(&F, 0.0, 1.0, brk, nb, 1e-13 / h, 1e-12, ws_outer);
  c.want_term = 1;
  c.epsabs_inner = 1e-14 / (h * h);
  *term = ref_quad(&F, 0.0, 1.0, brk, nb, 1e-13, 1e-12, ws_outer);
  for (int i = 0; i < 3; i++) grad[i] = iw * e->normal[i];
}

/* Marginal P_d(z) of the kernel across a plane, and 1/2 + ∫_0^δ P_d: γ at distance δ from an
 * infinite plane wall. */
struct ref_marginal {
  const struct sph_kernel *k;
  double z;
  gsl_integration_workspace *ws;
};

static inline double ref_marginal2_integrand(double t, void *p) {
  const struct ref_marginal *m = p;
  return 2.0 * sph_kernel_w(m->k, hypot(m->z, t));
}

static inline double ref_marginal3_integrand(double r, void *p) {
  const struct ref_marginal *m = p;
  return 2.0 * REF_PI * sph_kernel_w(m->k, r) * r;
}

/** P_d(z) [1/m]. */
static inline double ref_marginal(const struct sph_kernel *k, double z,
                                  gsl_integration_workspace *ws) {
  const double h = k->h;
  z = fabs(z);
  if (z >= 2.0 * h) return 0.0;
  struct ref_marginal m = {k, z, NULL};
  if (k->dim == 1) return sph_kernel_w(k, z);
  gsl_function F = {k->dim == 2 ? ref_marginal2_integrand : ref_marginal3_integrand, &m};
  if (k->dim == 2)
    return ref_quad(&F, 0.0, sqrt(4.0 * h * h - z * z), NULL, 0, 1e-14 / h, 1e-13, ws);
  return ref_quad(&F, z, 2.0 * h, NULL, 0, 1e-14 / h, 1e-13, ws);
}

static inline double ref_cumulative_integrand(double z, void *p) {
  struct ref_marginal *m = p;
  return ref_marginal(m->k, z, m->ws);
}

/** γ at distance δ ≥ 0 from an infinite plane wall: 1/2 + ∫_0^δ P_d(z) dz. */
static inline double ref_gamma_plane(const struct sph_kernel *k, double delta,
                                     gsl_integration_workspace *ws_outer,
                                     gsl_integration_workspace *ws_inner) {
  struct ref_marginal m = {k, 0.0, ws_inner};
  gsl_function F = {ref_cumulative_integrand, &m};
  return 0.5 + ref_quad(&F, 0.0, fmin(delta, 2.0 * k->h), NULL, 0, 1e-14, 1e-13, ws_outer);
}

/* ------------------------------------------------------------------------------------------ */
/* Random sweeps: segments and triangles, generic, clipped, nearly tangent, close to the plane */

/* Random point relative to an element with unit normal n and in-plane foot point f: kind selects
 * the regime. Returns the signed distance chosen. */
static inline double ref_random_delta(struct sabre_rng *rng, int kind, double H) {
  const double sgn = sabre_rng_uniform(rng, 0.0, 1.0) < 0.85 ? 1.0 : -1.0;
  switch (kind % 4) {
    case 0: /* generic */
      return sgn * sabre_rng_uniform(rng, 0.0, 2.05) * H;
    case 1: /* close to the plane */
      return sgn * pow(10.0, -sabre_rng_uniform(rng, 2.0, 6.0)) * H;
    case 2: /* nearly tangent: the support sphere just reaches the plane */
      return sgn * 2.0 * H * (1.0 - pow(10.0, -sabre_rng_uniform(rng, 2.0, 9.0)));
    default: /* moderate */
      return sgn * sabre_rng_uniform(rng, 0.5, 1.9) * H;
  }
}

static inline void ref_compare(double term, const double *grad, double ref_term,
                               const double *ref_grad, int dim, double H, double *max_err_term,
                               double *max_err_grad) {
  *max_err_term = fmax(*max_err_term, fabs(term - ref_term));
  assert_abs(term, ref_term, 1e-10);
  for (int c = 0; c < dim; c++) {
    *max_err_grad = fmax(*max_err_grad, fabs(grad[c] - ref_grad[c]) * H);
    assert_abs(grad[c] * H, ref_grad[c] * H, 1e-10);
  }
}

/** n random segments against ref_segment (asserts 1e-10); prints the largest errors. */
static inline void ref_sweep_segments(int n, uint64_t seed, double H) {
  struct sabre_rng rng;
  sabre_rng_seed(&rng, seed);
  double max_err_term = 0.0, max_err_grad = 0.0;
  struct sph_kernel k;
  sph_kernel_init(&k, 2, H);
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(2000);
  for (int i = 0; i < n; i++) {
    /* segment from (0, 0) to (L, 0) with the fluid above, then a random rigid motion */
    const double L = sabre_rng_uniform(&rng, 0.1, 6.0) * H;
    struct sph_wall_element e = ref_seg(0.0, 0.0, L, 0.0);
    const double delta = ref_random_delta(&rng, i, H);
    double a[3] = {sabre_rng_uniform(&rng, -2.5 * H, L + 2.5 * H), delta, 0.0};
    if (i % 5 == 4 && fabs(delta) < 2.0 * H) {
      /* clipped at an end, nearly tangent: the support circle just reaches x = 0 or x = L */
      const double R = sqrt(4.0 * H * H - delta * delta);
      const double gap = R * pow(10.0, -sabre_rng_uniform(&rng, 1.0, 8.0));
      a[0] = (i % 2 ? -R + gap : L + R - gap);
    }
    struct ref_motion m = ref_motion_random(&rng, 2, 3.0 * H);
    ref_apply_element(&m, &e);
    ref_apply(&m, a, a);
    double term, grad[3], rterm, rgrad[3];
    sph_gamma_element(&k, a, &e, &term, grad);
    if (getenv("SABRE_VERBOSE")) fprintf(stderr, "segment %d\n", i);
    ref_segment(&k, a, &e, &rterm, rgrad, ws);
    if (getenv("SABRE_VERBOSE"))
      printf("segment %d: delta/h %.3e term %.6e (error %.1e), h|∇γ_as| %.6e (error %.1e)\n", i,
             delta / H, term, term - rterm, hypot(grad[0], grad[1]) * H,
             hypot(grad[0] - rgrad[0], grad[1] - rgrad[1]) * H);
    ref_compare(term, grad, rterm, rgrad, 2, H, &max_err_term, &max_err_grad);
  }
  printf("2D, %d segments: max |Δ gamma_term| = %.2e, max h|Δ ∇γ_as| = %.2e\n", n, max_err_term,
         max_err_grad);
  gsl_integration_workspace_free(ws);
}

/** n random triangles against ref_triangle (asserts 1e-10); prints the largest errors. */
static inline void ref_sweep_triangles(int n, uint64_t seed, double H) {
  struct sabre_rng rng;
  sabre_rng_seed(&rng, seed);
  double max_err_term = 0.0, max_err_grad = 0.0;
  struct sph_kernel k;
  sph_kernel_init(&k, 3, H);
  gsl_integration_workspace *wo = gsl_integration_workspace_alloc(2000);
  gsl_integration_workspace *wi = gsl_integration_workspace_alloc(2000);
  for (int i = 0; i < n; i++) {
    /* triangle in z = 0 with random vertices (possibly larger than the support) */
    const double size = sabre_rng_uniform(&rng, 0.5, 6.0) * H;
    double p[3][3];
    for (int j = 0; j < 3; j++) {
      p[j][0] = sabre_rng_uniform(&rng, -1.0, 1.0) * size;
      p[j][1] = sabre_rng_uniform(&rng, -1.0, 1.0) * size;
      p[j][2] = 0.0;
    }
    struct sph_wall_element e = ref_tri(p[0], p[1], p[2]);
    if (e.normal[2] < 0.0) e = ref_tri(p[0], p[2], p[1]);
    double delta = ref_random_delta(&rng, i, H);
    if (i % 4 == 1) delta = (delta > 0.0 ? 1.0 : -1.0) * fmax(fabs(delta), 1e-5 * H);
    /* foot point inside the triangle or near it (barycentric coordinates in [−0.3, 1.3]) */
    double u = sabre_rng_uniform(&rng, -0.3, 1.0), v = sabre_rng_uniform(&rng, -0.3, 1.3 - u);
    if (i % 3 == 0) { /* inside */
      u = sabre_rng_uniform(&rng, 0.0, 1.0);
      v = sabre_rng_uniform(&rng, 0.0, 1.0 - u);
    }
    double a[3] = {p[0][0] + u * (p[1][0] - p[0][0]) + v * (p[2][0] - p[0][0]),
                   p[0][1] + u * (p[1][1] - p[0][1]) + v * (p[2][1] - p[0][1]), delta};
    if (i % 6 == 4 && fabs(delta) < 2.0 * H) {
      /* support disc nearly tangent to the edge p0 p1, from outside or inside */
      const double R = sqrt(4.0 * H * H - delta * delta);
      const double gap = pow(10.0, -sabre_rng_uniform(&rng, 1.0, 7.0)) * (i % 2 ? 1.0 : -1.0);
      const double ex = p[1][0] - p[0][0], ey = p[1][1] - p[0][1], len = hypot(ex, ey);
      const double s = sabre_rng_uniform(&rng, 0.2, 0.8);
      a[0] = p[0][0] + s * ex + R * (1.0 + gap) * ey / len;
      a[1] = p[0][1] + s * ey - R * (1.0 + gap) * ex / len;
    }
    if (i % 6 == 5 && fabs(delta) < 2.0 * H) {
      /* support disc nearly touching a vertex from outside or inside */
      const double R = sqrt(4.0 * H * H - delta * delta);
      const double gap = pow(10.0, -sabre_rng_uniform(&rng, 1.0, 7.0)) * (i % 2 ? 1.0 : -1.0);
      const double th = sabre_rng_uniform(&rng, 0.0, 2.0 * REF_PI);
      a[0] = p[0][0] + R * (1.0 + gap) * cos(th);
      a[1] = p[0][1] + R * (1.0 + gap) * sin(th);
    }
    struct ref_motion m = ref_motion_random(&rng, 3, 3.0 * H);
    ref_apply_element(&m, &e);
    ref_apply(&m, a, a);
    double term, grad[3], rterm, rgrad[3];
    sph_gamma_element(&k, a, &e, &term, grad);
    if (getenv("SABRE_VERBOSE")) fprintf(stderr, "triangle %d\n", i);
    ref_triangle(&k, a, &e, &rterm, rgrad, wo, wi);
    if (getenv("SABRE_VERBOSE"))
      printf("triangle %d: delta/h %.3e term %.6e (error %.1e), h∇γ_as·e_x %.6e (error %.1e)\n", i,
             delta / H, term, term - rterm, grad[0] * H, (grad[0] - rgrad[0]) * H);
    ref_compare(term, grad, rterm, rgrad, 3, H, &max_err_term, &max_err_grad);
  }
  printf("3D, %d triangles: max |Δ gamma_term| = %.2e, max h|Δ ∇γ_as| = %.2e\n", n, max_err_term,
         max_err_grad);
  gsl_integration_workspace_free(wo);
  gsl_integration_workspace_free(wi);
}

#endif
