/* Wave generators of sabre/sph_waves.h checked against the equations they solve, not against
 * stored output.
 *
 * Stokes fifth order (Fenton 1985): Laplace (div and curl of the velocity by finite differences),
 * the bed condition, the Euler equations with the Bernoulli pressure, the kinematic and dynamic
 * free-surface conditions with residuals falling like ε⁶ (the test that catches a wrong
 * coefficient), the volume flux, the mean Eulerian current, the height and mean depth, the Airy
 * limit, the dispersion solve from a period, deep water without overflow, and an independent
 * numerical solution of the full nonlinear problem (Fourier stream-function method, Rienecker and
 * Fenton 1981). Solitary wave J(42–47): closed form at points, depth-integrated mass conservation,
 * symmetry in θ, far field. Every status code on purpose. */
#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_multiroots.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/sph_waves.h"
#include "testutil.h"

/* ---------------------------------------------------------------------------------------------
 * Stokes helpers
 * ------------------------------------------------------------------------------------------- */

struct case_def {
  const char *name;
  double d, H, L, u_E;
};
/* J §IV.B (kd = 1.2566, H/L = 0.04); steeper (H/L = 0.06, half the breaking height); deep
 * (kd = 7.54); a following and an opposing current; a longer wave (L/d = 7.1, Ursell 14.4). */
static const struct case_def CASES[] = {
    {"J IV.B", 0.5, 0.1, 2.5, 0.0},       {"steep", 0.5, 0.15, 2.5, 0.0},
    {"deep", 3.0, 0.2, 2.5, 0.0},         {"current +", 0.5, 0.1, 2.5, 0.317},
    {"current -", 0.5, 0.1, 2.5, -0.283}, {"long", 0.7, 0.2, 4.97, 0.0},
};
#define NCASES (sizeof CASES / sizeof CASES[0])

static void make_stokes(struct sph_stokes5 *w, double d, double H, double L, double T, double u_E) {
  struct sph_stokes5_params p;
  sph_stokes5_params_init(&p);
  p.depth = d;
  p.height = H;
  p.length = L;
  p.period = T;
  p.current = u_E;
  char msg[512];
  const int status = sph_stokes5_init(w, &p, msg, sizeof msg);
  if (status != SPH_WAVE_SUCCESS) print_error("sph_stokes5_init: %s\n", msg);
  assert_int_equal(status, SPH_WAVE_SUCCESS);
}

static struct sph_wave_point at(const struct sph_stokes5 *w, double x, double z, double t) {
  struct sph_wave_point o;
  const int status = sph_stokes5_eval(w, x, z, t, &o);
  assert_true(status == SPH_WAVE_SUCCESS || status == SPH_WAVE_EOUTSIDE);
  return o;
}

/* Fourth-order central difference of component `c` of the Stokes point along axis a (0 x, 1 z,
 * 2 t) with step h. Components: 0 u, 1 w, 2 p, 3 eta. */
static double comp(const struct sph_wave_point *o, int c) {
  return c == 0 ? o->u : c == 1 ? o->w : c == 2 ? o->p : o->eta;
}
static double dstokes(const struct sph_stokes5 *w, const double r[3], int a, int c, double h) {
  double s[5] = {0};
  for (int m = -2; m <= 2; m++) {
    if (m == 0) continue;
    double q[3] = {r[0], r[1], r[2]};
    q[a] += m * h;
    const struct sph_wave_point o = at(w, q[0], q[1], q[2]);
    s[m + 2] = comp(&o, c);
  }
  return (-s[4] + 8.0 * s[3] - 8.0 * s[1] + s[0]) / (12.0 * h);
}

/* Max over one wave length of the kinematic residual (u − c) η_x − w and the dynamic residual
 * ½((u − c)² + w²) + g η − R on the surface, scaled by √(g/k) and g/k. */
static void surface_residuals(const struct sph_stokes5 *w, double *kin, double *dyn) {
  *kin = *dyn = 0.0;
  for (int i = 0; i < 256; i++) {
    const double x = w->L * (i + 0.37) / 256.0;
    const struct sph_wave_point s = at(w, x, 0.0, 0.0);
    const struct sph_wave_point o = at(w, x, s.eta, 0.0);
    const double ur = o.u - w->c;
    *kin = fmax(*kin, fabs(ur * o.eta_x - o.w) / sqrt(w->g / w->k));
    *dyn = fmax(*dyn, fabs(0.5 * (ur * ur + o.w * o.w) + w->g * o.eta - w->R) / (w->g / w->k));
  }
}

/* ---------------------------------------------------------------------------------------------
 * Stokes: field equations
 * ------------------------------------------------------------------------------------------- */

/* Laplace: div u = 0 and curl u = 0 by finite differences inside the water; w = 0 on the bed;
 * η_x and η_t against finite differences of η. */
static void test_stokes_laplace_bed(void **state) {
  (void)state;
  for (size_t n = 0; n < NCASES; n++) {
    const struct case_def *cd = &CASES[n];
    struct sph_stokes5 w;
    make_stokes(&w, cd->d, cd->H, cd->L, 0.0, cd->u_E);
    const double h = 1e-3 / w.k, scale = w.k * w.ubar * w.eps; /* k |u'| */
    const double trough = at(&w, 0.5 * w.L, 0.0, 0.0).eta;
    double worst_div = 0.0, worst_curl = 0.0, worst_eta = 0.0;
    for (int i = 0; i < 9; i++)
      for (int j = 1; j <= 5; j++) {
        const double r[3] = {w.L * (i + 0.21) / 9.0, trough * j / 6.0, 0.113 * w.T};
        const double ux = dstokes(&w, r, 0, 0, h), uz = dstokes(&w, r, 1, 0, h);
        const double wx = dstokes(&w, r, 0, 1, h), wz = dstokes(&w, r, 1, 1, h);
        worst_div = fmax(worst_div, fabs(ux + wz) / scale);
        worst_curl = fmax(worst_curl, fabs(uz - wx) / scale);
        const struct sph_wave_point o = at(&w, r[0], r[1], r[2]);
        const double ex = dstokes(&w, r, 0, 3, h), et = dstokes(&w, r, 2, 3, h / w.c);
        worst_eta = fmax(worst_eta, fabs(o.eta_x - ex) / (w.k * w.H));
        worst_eta = fmax(worst_eta, fabs(o.eta_t - et) / (w.k * w.H * w.c));
        assert_abs(o.eta_t, -w.c * o.eta_x, 1e-15 * w.c);
        assert_true(o.v == 0.0 && o.eta_y == 0.0);
        /* bed: w = 0 */
        const struct sph_wave_point b = at(&w, r[0], 0.0, r[2]);
        assert_abs(b.w, 0.0, 1e-15 * w.c);
      }
    print_message(
        "%-9s kd = %.4f eps = %.4f: |div u|, |curl u| <= %.1e, %.1e k|u'|; eta_x, "
        "eta_t vs FD %.1e\n",
        cd->name, w.kd, w.eps, worst_div, worst_curl, worst_eta);
    assert_true(worst_div < 1e-8 && worst_curl < 1e-8 && worst_eta < 1e-8);
  }
}

/* Euler: with the Bernoulli pressure, Du/Dt = −∇p/ρ0 − g ẑ holds (finite differences in x, z,
 * t), which checks the pressure's sign, frame and Bernoulli constant away from the surface. */
static void test_stokes_euler(void **state) {
  (void)state;
  for (size_t n = 0; n < NCASES; n++) {
    const struct case_def *cd = &CASES[n];
    struct sph_stokes5 w;
    make_stokes(&w, cd->d, cd->H, cd->L, 0.0, cd->u_E);
    const double h = 1e-3 / w.k, trough = at(&w, 0.5 * w.L, 0.0, 0.0).eta;
    double worst = 0.0;
    for (int i = 0; i < 7; i++)
      for (int j = 0; j <= 4; j++) {
        const double r[3] = {w.L * (i + 0.4) / 7.0, trough * j / 4.5, 0.29 * w.T};
        const struct sph_wave_point o = at(&w, r[0], r[1], r[2]);
        const double ut = dstokes(&w, r, 2, 0, h / w.c), wt = dstokes(&w, r, 2, 1, h / w.c);
        const double ux = dstokes(&w, r, 0, 0, h), uz = dstokes(&w, r, 1, 0, h);
        const double wx = dstokes(&w, r, 0, 1, h), wz = dstokes(&w, r, 1, 1, h);
        const double px = dstokes(&w, r, 0, 2, h), pz = dstokes(&w, r, 1, 2, h);
        const double ex = ut + o.u * ux + o.w * uz + px / w.rho0;
        const double ez = wt + o.u * wx + o.w * wz + pz / w.rho0 + w.g;
        worst = fmax(worst, fmax(fabs(ex), fabs(ez)) / w.g);
      }
    print_message("%-9s Euler residual with the Bernoulli pressure <= %.1e g\n", cd->name, worst);
    assert_true(worst < 1e-7);
  }
}

/* Kinematic and dynamic free-surface conditions: residuals O(ε⁶). At fixed kd the height is
 * halved four times from 0.4 of the breaking height; every log-log slope must be ≥ 5.5. */
static void test_stokes_free_surface_order(void **state) {
  (void)state;
  const double kds[] = {0.7854, 1.2566, 3.0};
  for (size_t a = 0; a < sizeof kds / sizeof kds[0]; a++) {
    const double d = 0.5, k = kds[a] / d, L = 2.0 * M_PI / k;
    const double Hb = SPH_WAVE_BREAKING * tanh(kds[a]) * L;
    double H_prev = 0, k_prev = 0, d_prev = 0, smin_k = INFINITY, smin_d = INFINITY;
    for (int m = 0; m < 5; m++) {
      const double H = 0.4 * Hb * pow(0.5, m);
      struct sph_stokes5 w;
      make_stokes(&w, d, H, L, 0.0, 0.0);
      double kin, dyn;
      surface_residuals(&w, &kin, &dyn);
      if (m > 0) {
        smin_k = fmin(smin_k, log(kin / k_prev) / log(H / H_prev));
        smin_d = fmin(smin_d, log(dyn / d_prev) / log(H / H_prev));
      }
      print_message("kd = %.4f H/Hb = %.4f eps = %.5f: kinematic %.3e, dynamic %.3e\n", kds[a],
                    H / Hb, w.eps, kin, dyn);
      H_prev = H;
      k_prev = kin;
      d_prev = dyn;
    }
    print_message("kd = %.4f: smallest log-log slopes: kinematic %.3f, dynamic %.3f\n", kds[a],
                  smin_k, smin_d);
    assert_true(smin_k >= 5.5 && smin_d >= 5.5);
  }
  /* J's wave itself */
  struct sph_stokes5 w;
  make_stokes(&w, 0.5, 0.1, 2.5, 0.0, 0.0);
  double kin, dyn;
  surface_residuals(&w, &kin, &dyn);
  print_message("J IV.B (eps = %.4f): kinematic %.2e sqrt(g/k), dynamic %.2e g/k\n", w.eps, kin,
                dyn);
  assert_true(kin < 1e-4 && dyn < 2e-5);
}

/* Volume flux: ∫_0^η (u − c) dz = −q at every section (steady flow in the frame of the wave), to
 * the order of the series: the worst relative difference falls like ε⁶ (log-log slope ≥ 5.5 as
 * the height halves at kd = 1.2566), which checks D2 and D4; and it is small in every case. */
static double flux_error(const struct sph_stokes5 *w, const gsl_integration_glfixed_table *gl) {
  double worst = 0.0;
  for (int i = 0; i < 16; i++) {
    const double x = w->L * (i + 0.3) / 16.0, eta = at(w, x, 0.0, 0.0).eta;
    double flux = 0.0;
    for (size_t m = 0; m < 40; m++) {
      double z, wt;
      gsl_integration_glfixed_point(0.0, eta, m, &z, &wt, gl);
      flux += wt * (at(w, x, z, 0.0).u - w->c);
    }
    worst = fmax(worst, fabs(flux + w->q) / w->q);
  }
  return worst;
}

static void test_stokes_flux(void **state) {
  (void)state;
  gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(40);
  assert_non_null(gl);
  for (size_t n = 0; n < NCASES; n++) {
    const struct case_def *cd = &CASES[n];
    struct sph_stokes5 w;
    make_stokes(&w, cd->d, cd->H, cd->L, 0.0, cd->u_E);
    const double err = flux_error(&w, gl);
    print_message("%-9s flux under the wave vs -q: %.1e relative (eps = %.4f)\n", cd->name, err,
                  w.eps);
    assert_true(err < 1e-3);
    assert_rel(w.u_mass, w.c - w.q / w.d, 1e-15);
  }
  const double d = 0.5, L = 2.5, Hb = SPH_WAVE_BREAKING * tanh(2.0 * M_PI * d / L) * L;
  double prev = 0.0, smin = INFINITY;
  for (int m = 0; m < 4; m++) {
    struct sph_stokes5 w;
    make_stokes(&w, d, 0.4 * Hb * pow(0.5, m), L, 0.0, 0.0);
    const double err = flux_error(&w, gl);
    if (m > 0) smin = fmin(smin, log(prev / err) / log(2.0));
    prev = err;
  }
  print_message("flux error vs height at kd = 1.2566: smallest log-log slope %.3f\n", smin);
  assert_true(smin >= 5.5);
  gsl_integration_glfixed_table_free(gl);
}

/* The mean Eulerian current: the time mean of u at a fixed point below the trough is u_E (the
 * mean of 64 samples is exact for the five harmonics). The mean of η over a wave is d, its range
 * is H. */
static void test_stokes_current_height_depth(void **state) {
  (void)state;
  for (size_t n = 0; n < NCASES; n++) {
    const struct case_def *cd = &CASES[n];
    struct sph_stokes5 w;
    make_stokes(&w, cd->d, cd->H, cd->L, 0.0, cd->u_E);
    const double trough = at(&w, 0.5 * w.L, 0.0, 0.0).eta;
    for (int j = 0; j <= 3; j++) {
      const double z = trough * j / 3.0;
      double mean = 0.0;
      for (int i = 0; i < 64; i++) mean += at(&w, 0.173 * w.L, z, w.T * i / 64.0).u / 64.0;
      assert_abs(mean, cd->u_E, 1e-14 * w.c);
    }
    double mean_eta = 0.0, lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < 64; i++) mean_eta += at(&w, w.L * i / 64.0, 0.0, 0.0).eta / 64.0;
    for (int i = 0; i <= 4096; i++) {
      const double eta = at(&w, w.L * i / 4096.0, 0.0, 0.0).eta;
      lo = fmin(lo, eta);
      hi = fmax(hi, eta);
    }
    assert_rel(mean_eta, cd->d, 1e-14);
    assert_rel(hi - lo, cd->H, 1e-13);
    /* crest at x = ct, trough half a wave length behind */
    assert_rel(at(&w, w.c * 0.37, 0.0, 0.37).eta, hi, 1e-14);
    assert_rel(at(&w, w.c * 0.37 - 0.5 * w.L, 0.0, 0.37).eta, lo, 1e-14);
  }
}

/* Small heights against Airy: the dispersion relation ω² = gk tanh kd (without current), and the
 * first-harmonic amplitudes of u and p at a fixed level, a ω cosh kz / sinh kd and ρ g a cosh kz /
 * cosh kd (a = H/2), all to relative O(ε²): the differences fall by 4 when ε halves (the second
 * order adds a mean and a second harmonic only). */
static void test_stokes_airy_limit(void **state) {
  (void)state;
  const double kds[] = {0.8, 1.2566, 3.0};
  for (size_t a = 0; a < sizeof kds / sizeof kds[0]; a++) {
    const double d = 0.5, k = kds[a] / d, L = 2.0 * M_PI / k, g = 9.81, rho = 1000.0;
    double prev[3] = {0};
    for (int m = 0; m < 3; m++) {
      const double eps = 0.02 * pow(0.5, m), H = 2.0 * eps / k, amp = 0.5 * H;
      struct sph_stokes5 w;
      make_stokes(&w, d, H, L, 0.0, 0.0);
      const double omega = sqrt(g * k * tanh(kds[a])), z = 0.37 * d;
      double u1 = 0.0, p1 = 0.0;
      for (int i = 0; i < 64; i++) {
        const struct sph_wave_point o = at(&w, L * i / 64.0, z, 0.0);
        u1 += o.u * cos(2.0 * M_PI * i / 64.0) / 32.0;
        p1 += o.p * cos(2.0 * M_PI * i / 64.0) / 32.0;
      }
      const double err[3] = {fabs(w.omega / omega - 1.0),
                             fabs(u1 / (amp * omega * cosh(k * z) / sinh(kds[a])) - 1.0),
                             fabs(p1 / (rho * g * amp * cosh(k * z) / cosh(kds[a])) - 1.0)};
      for (int e = 0; e < 3; e++) {
        assert_true(err[e] <= 10.0 * eps * eps);
        if (m > 0) {
          const double ratio = prev[e] / err[e];
          assert_true(ratio > 3.8 && ratio < 4.2);
        }
        prev[e] = err[e];
      }
      if (m == 2)
        print_message(
            "kd = %.4f eps = %.4f: omega, u_1, p_1 differ from Airy by %.2e, %.2e, "
            "%.2e (= %.3f, %.3f, %.3f eps^2)\n",
            kds[a], eps, err[0], err[1], err[2], err[0] / (eps * eps), err[1] / (eps * eps),
            err[2] / (eps * eps));
    }
  }
}

/* The period: T from L, then L from T (with and without current) to round-off. */
static void test_stokes_period(void **state) {
  (void)state;
  for (size_t n = 0; n < NCASES; n++) {
    const struct case_def *cd = &CASES[n];
    struct sph_stokes5 w, v;
    make_stokes(&w, cd->d, cd->H, cd->L, 0.0, cd->u_E);
    make_stokes(&v, cd->d, cd->H, 0.0, w.T, cd->u_E);
    assert_rel(v.L, cd->L, 1e-12);
    assert_rel(v.T, w.T, 1e-13);
    assert_rel(v.c, w.c, 1e-12);
    assert_rel(w.omega, w.k * w.c, 1e-15);
    assert_rel(w.T, 2.0 * M_PI / w.omega, 1e-15);
  }
  /* J's wave: T = 1.3557 s (the linear period would be 1.3723 s) */
  struct sph_stokes5 w;
  make_stokes(&w, 0.5, 0.1, 2.5, 0.0, 0.0);
  print_message("J IV.B: c = %.6f m/s, T = %.6f s, u_mass = %.3e m/s, R = %.6f m^2/s^2\n", w.c, w.T,
                w.u_mass, w.R);
}

/* Deep water: kd = 20 and kd = 2000 give the same wave (no overflow of sinh kd or cosh jkz: the
 * traps are on), and the deep-water phase speed √(g/k)(1 + ε²/2 + ε⁴/8) of C0 = 1, C2 = 1/2,
 * C4 = 1/8 at S = 0. */
static void test_stokes_deep(void **state) {
  (void)state;
  const double L = 2.5, H = 0.2, k = 2.0 * M_PI / L, eps = 0.5 * k * H;
  struct sph_stokes5 a, b;
  make_stokes(&a, 20.0 / k, H, L, 0.0, 0.0);
  make_stokes(&b, 2000.0 / k, H, L, 0.0, 0.0);
  assert_rel(a.c, b.c, 1e-15);
  assert_rel(a.c, sqrt(9.81 / k) * (1.0 + eps * eps / 2.0 + pow(eps, 4) / 8.0), 1e-15);
  for (int i = 0; i < 5; i++) {
    const double x = 0.31 * i, dz = -0.05 * i;
    const struct sph_wave_point pa = at(&a, x, a.d + dz, 0.7), pb = at(&b, x, b.d + dz, 0.7);
    assert_rel(pa.eta - a.d, pb.eta - b.d, 1e-12);
    assert_rel(pa.u, pb.u, 1e-12);
    assert_abs(pa.w, pb.w, 1e-12 * b.c);
    assert_rel(pa.p - 1000.0 * 9.81 * (a.d - (a.d + dz)), pb.p - 1000.0 * 9.81 * (b.d - (b.d + dz)),
               1e-9);
  }
  struct sph_stokes5 c;
  make_stokes(&c, b.d, H, 0.0, b.T, 0.0);
  assert_rel(c.L, L, 1e-12);
  const struct sph_wave_point bed = at(&b, 0.0, 0.0, 0.0);
  assert_true(bed.u == 0.0 && bed.w == 0.0);
}

/* ---------------------------------------------------------------------------------------------
 * Stokes: independent reference, the Fourier stream-function method (Rienecker & Fenton 1981)
 * In the frame of the wave, with X = x − ct, Y = z and everything scaled by k and g:
 *   ψ = −ū Y + Σ_{j=1..N} B_j sinh(jY)/cosh(j kd) cos jX,
 *   kinematic: ψ(X_m, η_m) = −Q;   dynamic: ½(ψ_Y² + ψ_X²) + η_m = R;   m = 0..N, X_m = mπ/N,
 *   mean depth: trapezoidal mean of η_m = kd;   height: η_0 − η_N = kH.
 * 2N + 4 equations for η_0..η_N, B_1..B_N, ū, Q, R, solved by GSL's hybrid method from Airy.
 * With no mean Eulerian current c = ū (the mean of ψ_Y below the trough is −ū).
 * ------------------------------------------------------------------------------------------- */

#define FOURIER_N 20

struct fourier {
  double kd, kH;
};

/* Residuals (f) and their Jacobian (J), either may be NULL. Unknowns: η_0..η_N, B_1..B_N, ū, Q, R.
 */
static void fourier_eval(const gsl_vector *x, const struct fourier *fp, gsl_vector *f,
                         gsl_matrix *J) {
  const int N = FOURIER_N;
  const size_t iu = (size_t)(2 * N + 1), iq = iu + 1, ir = iu + 2;
  const double ubar = gsl_vector_get(x, iu), Q = gsl_vector_get(x, iq), R = gsl_vector_get(x, ir);
  if (J != NULL) gsl_matrix_set_zero(J);
  double mean = 0.0;
  for (int m = 0; m <= N; m++) {
    const size_t rk = (size_t)m, rd = (size_t)(N + 1 + m);
    const double X = m * M_PI / N, Y = gsl_vector_get(x, (size_t)m);
    double psi = -ubar * Y + Q, U = -ubar, W = 0.0, U_y = 0.0, W_y = 0.0;
    for (int j = 1; j <= N; j++) {
      const double bj = gsl_vector_get(x, (size_t)(N + j)), ch = cosh(j * fp->kd);
      const double s = sinh(j * Y) / ch, c = cosh(j * Y) / ch, cx = cos(j * X), sx = sin(j * X);
      psi += bj * s * cx;
      U += j * bj * c * cx;
      W += j * bj * s * sx;
      U_y += j * j * bj * s * cx;
      W_y += j * j * bj * c * sx;
    }
    if (f != NULL) {
      gsl_vector_set(f, rk, psi);
      gsl_vector_set(f, rd, 0.5 * (U * U + W * W) + Y - R);
    }
    if (J != NULL) {
      for (int j = 1; j <= N; j++) {
        const double ch = cosh(j * fp->kd), s = sinh(j * Y) / ch, c = cosh(j * Y) / ch;
        const size_t col = (size_t)(N + j);
        gsl_matrix_set(J, rk, col, s * cos(j * X));
        gsl_matrix_set(J, rd, col, U * j * c * cos(j * X) + W * j * s * sin(j * X));
      }
      gsl_matrix_set(J, rk, (size_t)m, U); /* ∂ψ/∂Y */
      gsl_matrix_set(J, rk, iu, -Y);
      gsl_matrix_set(J, rk, iq, 1.0);
      gsl_matrix_set(J, rd, (size_t)m, U * U_y + W * W_y + 1.0);
      gsl_matrix_set(J, rd, iu, -U);
      gsl_matrix_set(J, rd, ir, -1.0);
      gsl_matrix_set(J, (size_t)(2 * N + 2), (size_t)m, (m == 0 || m == N ? 0.5 : 1.0) / N);
    }
    mean += (m == 0 || m == N ? 0.5 : 1.0) * Y / N;
  }
  if (f != NULL) {
    gsl_vector_set(f, (size_t)(2 * N + 2), mean - fp->kd);
    gsl_vector_set(f, (size_t)(2 * N + 3),
                   gsl_vector_get(x, 0) - gsl_vector_get(x, (size_t)N) - fp->kH);
  }
  if (J != NULL) {
    gsl_matrix_set(J, (size_t)(2 * N + 3), 0, 1.0);
    gsl_matrix_set(J, (size_t)(2 * N + 3), (size_t)N, -1.0);
  }
}
static int fourier_f(const gsl_vector *x, void *p, gsl_vector *f) {
  fourier_eval(x, p, f, NULL);
  return GSL_SUCCESS;
}
static int fourier_df(const gsl_vector *x, void *p, gsl_matrix *J) {
  fourier_eval(x, p, NULL, J);
  return GSL_SUCCESS;
}
static int fourier_fdf(const gsl_vector *x, void *p, gsl_vector *f, gsl_matrix *J) {
  fourier_eval(x, p, f, J);
  return GSL_SUCCESS;
}

static void test_stokes_fourier_reference(void **state) {
  (void)state;
  /* H/L = 0.04, kd = 1.2566 (J IV.B; within 5e-4 H in η and 5e-4 c in u, w), the same at half the
   * height (the η difference, relative to H, must fall like ε⁵: by ≥ 2^4.5), and a steeper wave
   * (H/L = 0.081, 0.6 of the breaking height) where the series is looser (5e-3 H, 1e-3 c). */
  const struct case_def refs[] = {
      {"J IV.B", 0.5, 0.1, 2.5, 0.0}, {"J/2", 0.5, 0.05, 2.5, 0.0}, {"steep", 0.6, 0.17, 2.1, 0.0}};
  const double tol_eta[] = {5e-4, 5e-4, 5e-3}, tol_u[] = {5e-4, 5e-4, 1e-3};
  double err_eta_ref[3];
  for (size_t n = 0; n < sizeof refs / sizeof refs[0]; n++) {
    const struct case_def *cd = &refs[n];
    const double g = 9.81, k = 2.0 * M_PI / cd->L;
    const int N = FOURIER_N;
    struct fourier fp = {k * cd->d, k * cd->H};
    gsl_vector *x = gsl_vector_alloc((size_t)(2 * N + 4));
    const double ubar0 = sqrt(tanh(fp.kd)), eps = 0.5 * fp.kH;
    gsl_vector_set_zero(x);
    for (int m = 0; m <= N; m++) gsl_vector_set(x, (size_t)m, fp.kd + eps * cos(m * M_PI / N));
    gsl_vector_set(x, (size_t)(N + 1), eps / ubar0);
    gsl_vector_set(x, (size_t)(2 * N + 1), ubar0);
    gsl_vector_set(x, (size_t)(2 * N + 2), ubar0 * fp.kd);
    gsl_vector_set(x, (size_t)(2 * N + 3), 0.5 * ubar0 * ubar0 + fp.kd);
    gsl_multiroot_function_fdf F = {fourier_f, fourier_df, fourier_fdf, (size_t)(2 * N + 4), &fp};
    gsl_multiroot_fdfsolver *s =
        gsl_multiroot_fdfsolver_alloc(gsl_multiroot_fdfsolver_hybridsj, (size_t)(2 * N + 4));
    assert_int_equal(gsl_multiroot_fdfsolver_set(s, &F, x), GSL_SUCCESS);
    int status = GSL_CONTINUE;
    for (int it = 0; it < 200 && status == GSL_CONTINUE; it++) {
      if (gsl_multiroot_fdfsolver_iterate(s) != GSL_SUCCESS) break;
      status = gsl_multiroot_test_residual(s->f, 1e-14);
    }
    assert_int_equal(status, GSL_SUCCESS);
    const gsl_vector *r = s->x;
    const double *B = r->data + N + 1, ubar = gsl_vector_get(r, (size_t)(2 * N + 1));
    const double vs = sqrt(g / k), c_ref = ubar * vs; /* c = ū: no mean Eulerian current */

    struct sph_stokes5 w;
    make_stokes(&w, cd->d, cd->H, cd->L, 0.0, 0.0);
    double err_eta = 0.0, err_u = 0.0;
    for (int m = 0; m <= N; m++) {
      const double X = m * M_PI / N, eta_ref = gsl_vector_get(r, (size_t)m) / k;
      const double xs = X / k; /* t = 0: x = X/k */
      err_eta = fmax(err_eta, fabs(at(&w, xs, 0.0, 0.0).eta - eta_ref) / cd->H);
      for (int j = 0; j <= 4; j++) {
        const double Y = k * eta_ref * j / 4.0;
        double U = -ubar, W = 0.0;
        for (int i = 1; i <= N; i++) {
          const double ch = cosh(i * fp.kd), bi = B[(i - 1) * (int)r->stride];
          U += i * bi * cosh(i * Y) / ch * cos(i * X);
          W += i * bi * sinh(i * Y) / ch * sin(i * X);
        }
        const struct sph_wave_point o = at(&w, xs, Y / k, 0.0);
        err_u = fmax(err_u, fmax(fabs(o.u - (c_ref + U * vs)), fabs(o.w - W * vs)) / c_ref);
      }
    }
    print_message(
        "%-6s H/L = %.3f kd = %.4f: Stokes5 vs Fourier (N = %d): eta %.2e H, u and w "
        "%.2e c, c %.2e c\n",
        cd->name, cd->H / cd->L, fp.kd, N, err_eta, err_u, fabs(w.c - c_ref) / c_ref);
    assert_true(err_eta <= tol_eta[n] && err_u <= tol_u[n] &&
                fabs(w.c - c_ref) <= tol_u[n] * c_ref);
    err_eta_ref[n] = err_eta;
    gsl_multiroot_fdfsolver_free(s);
    gsl_vector_free(x);
  }
  print_message("eta difference J IV.B / half height: %.1f (eps^5: 32)\n",
                err_eta_ref[0] / err_eta_ref[1]);
  assert_true(err_eta_ref[0] / err_eta_ref[1] >= pow(2.0, 4.5));
}

/* ---------------------------------------------------------------------------------------------
 * Stokes: errors
 * ------------------------------------------------------------------------------------------- */

static int try_stokes(double d, double H, double L, double T, double u_E, double g, double rho0,
                      char *msg, size_t len) {
  struct sph_stokes5_params p;
  sph_stokes5_params_init(&p);
  p.depth = d;
  p.height = H;
  p.length = L;
  p.period = T;
  p.current = u_E;
  p.g = g;
  p.rho0 = rho0;
  struct sph_stokes5 w;
  return sph_stokes5_init(&w, &p, msg, len);
}

#define EXPECT_STOKES(status, field, ...)                                 \
  do {                                                                    \
    char m_[512];                                                         \
    assert_int_equal(try_stokes(__VA_ARGS__, m_, sizeof m_), status);     \
    if (strncmp(m_, field ":", strlen(field ":")) != 0) {                 \
      print_error("message '%s' does not start with '%s:'\n", m_, field); \
      fail();                                                             \
    }                                                                     \
  } while (0)

static void test_stokes_errors(void **state) {
  (void)state;
  const double nan = NAN, inf = INFINITY;
  EXPECT_STOKES(SPH_WAVE_EINVAL, "depth", 0.0, 0.1, 2.5, 0.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "depth", nan, 0.1, 2.5, 0.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "depth", -0.5, 0.1, 2.5, 0.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "height", 0.5, -0.1, 2.5, 0.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "height", 0.5, inf, 2.5, 0.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "length", 0.5, 0.1, -2.5, 0.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "length", 0.5, 0.1, nan, 0.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "length", 0.5, 0.1, 0.0, 0.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "length", 0.5, 0.1, 2.5, 1.3, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "period", 0.5, 0.1, 0.0, -1.3, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "current", 0.5, 0.1, 2.5, 0.0, nan, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "g", 0.5, 0.1, 2.5, 0.0, 0.0, 0.0, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EINVAL, "rho0", 0.5, 0.1, 2.5, 0.0, 0.0, 9.81, -1.0);
  /* breaking: H/L = 0.16 > 0.142 tanh kd */
  EXPECT_STOKES(SPH_WAVE_EBREAK, "height", 0.5, 0.4, 2.5, 0.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_EBREAK, "height", 0.5, 0.45, 0.0, 2.0, 0.0, 9.81, 1000.0); /* H > .89 d */
  /* too long: L/d = 20, Ursell 0.05·400/... */
  EXPECT_STOKES(SPH_WAVE_ESHALLOW, "length", 0.5, 0.05, 10.0, 0.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_ENOWAVE, "period", 0.5, 0.05, 0.0, 10.0, 0.0, 9.81, 1000.0);
  EXPECT_STOKES(SPH_WAVE_ENOWAVE, "period", 0.5, 0.2, 0.0, 0.5, 0.0, 9.81, 1000.0);  /* steep */
  EXPECT_STOKES(SPH_WAVE_ENOWAVE, "period", 0.5, 0.1, 0.0, 1.3, -5.0, 9.81, 1000.0); /* blocked */
  EXPECT_STOKES(SPH_WAVE_ECURRENT, "current", 0.5, 0.1, 2.5, 0.0, -2.0, 9.81, 1000.0);
  /* a height that no valid length can carry: Ursell limit above the breaking limit */
  EXPECT_STOKES(SPH_WAVE_ESHALLOW, "height", 0.5, 0.44, 0.0, 2.0, 0.0, 9.81, 1000.0);
  assert_int_equal(sph_stokes5_init(NULL, NULL, NULL, 0), SPH_WAVE_EINVAL);

  struct sph_stokes5 w;
  make_stokes(&w, 0.5, 0.1, 2.5, 0.0, 0.0);
  struct sph_wave_point o;
  assert_int_equal(sph_stokes5_eval(&w, 0.0, 0.3, 0.0, &o), SPH_WAVE_SUCCESS);
  assert_int_equal(sph_stokes5_eval(&w, 0.0, 0.56, 0.0, &o), SPH_WAVE_EOUTSIDE); /* η = 0.5559 */
  assert_true(isfinite(o.u) && isfinite(o.p) && o.p < 0.0);
  assert_int_equal(sph_stokes5_eval(&w, 0.0, -0.01, 0.0, &o), SPH_WAVE_EOUTSIDE);
  assert_true(isfinite(o.u));
  assert_int_equal(sph_stokes5_eval(&w, 0.0, 50.0, 0.0, &o), SPH_WAVE_EOUTSIDE);
  assert_true(isnan(o.u) && isnan(o.w) && isnan(o.p) && isfinite(o.eta));
  assert_int_equal(sph_stokes5_eval(&w, NAN, 0.3, 0.0, &o), SPH_WAVE_EINVAL);
  assert_int_equal(sph_stokes5_eval(&w, 0.0, 0.3, INFINITY, &o), SPH_WAVE_EINVAL);
  assert_int_equal(sph_stokes5_eval(NULL, 0.0, 0.3, 0.0, &o), SPH_WAVE_EINVAL);
  for (int s = SPH_WAVE_SUCCESS; s <= SPH_WAVE_EOUTSIDE; s++) {
    assert_true(strncmp(sph_wave_status_name(s), "SPH_WAVE_", 9) == 0);
    assert_true(strlen(sph_wave_strerror(s)) > 5);
  }
  assert_string_equal(sph_wave_status_name(99), "SPH_WAVE_UNKNOWN");
}

/* ---------------------------------------------------------------------------------------------
 * Solitary wave J(42–47)
 * ------------------------------------------------------------------------------------------- */

static void make_solitary(struct sph_solitary *s, double D, double A, double theta, double x0) {
  struct sph_solitary_params p;
  sph_solitary_params_init(&p);
  p.depth = D;
  p.amplitude = A;
  p.angle = theta;
  p.x0 = x0;
  char msg[256];
  assert_int_equal(sph_solitary_init(s, &p, msg, sizeof msg), SPH_WAVE_SUCCESS);
}

static struct sph_wave_point sol_at(const struct sph_solitary *s, double x, double y, double z,
                                    double t) {
  struct sph_wave_point o;
  const int status = sph_solitary_eval(s, x, y, z, t, &o);
  assert_true(status == SPH_WAVE_SUCCESS || status == SPH_WAVE_EOUTSIDE);
  return o;
}

/* J(42–47) written out here with cosh (no overflow at these points), D = 0.6, A = D/2 (J §IV.C). */
static void test_solitary_closed_form(void **state) {
  (void)state;
  const double D = 0.6, A = 0.3, g = 9.81, rho = 1000.0;
  const double thetas[] = {0.0, 0.4363, -1.1};
  for (size_t a = 0; a < 3; a++) {
    const double th = thetas[a], x0 = -1.73;
    struct sph_solitary s;
    make_solitary(&s, D, A, th, x0);
    const double k = sqrt(3.0 * A / (4.0 * D * D * D)), c = sqrt(g * (A + D));
    assert_rel(s.k, k, 1e-15);
    assert_rel(s.c, c, 1e-15);
    struct sabre_rng rng;
    sabre_rng_seed(&rng, 2016 + a);
    for (int i = 0; i < 50; i++) {
      const double x = sabre_rng_uniform(&rng, -3, 3), y = sabre_rng_uniform(&rng, -2, 2);
      const double t = sabre_rng_uniform(&rng, 0, 2);
      const double xi = k * (x * cos(th) + y * sin(th) - c * t - x0);
      const double eta = A / (cosh(xi) * cosh(xi)), h = D + eta;
      const double z = sabre_rng_uniform(&rng, 0, 1) * h;
      const double eta_t = 2.0 * A * k * c * tanh(xi) / (cosh(xi) * cosh(xi));
      const struct sph_wave_point o = sol_at(&s, x, y, z, t);
      assert_rel(o.eta, h, 1e-14);
      assert_abs(o.eta_t, eta_t, 1e-14 * A * k * c);
      assert_abs(o.u, c * eta / h * cos(th), 1e-14 * c);
      assert_abs(o.v, c * eta / h * sin(th), 1e-14 * c);
      assert_abs(o.w, z / h * eta_t, 1e-14 * c);
      assert_abs(o.p, rho * g * (h - z), 1e-12 * rho * g * D);
    }
    /* crest: η = D + A where x cos θ + y sin θ = x0 + ct; p = 0 on the surface, ρ g h on the bed,
     * w = 0 on the bed and ∂η/∂t on the surface */
    const double t = 0.77, sx = (x0 + c * t) * cos(th), sy = (x0 + c * t) * sin(th);
    const struct sph_wave_point top = sol_at(&s, sx, sy, D + A, t);
    assert_rel(top.eta, D + A, 1e-15);
    assert_abs(top.p, 0.0, 1e-12 * rho * g * D);
    const struct sph_wave_point side = sol_at(&s, sx + 0.3, sy - 0.2, 0.0, t);
    assert_true(side.w == 0.0);
    assert_rel(side.p, rho * g * side.eta, 1e-15);
    const struct sph_wave_point surf = sol_at(&s, sx + 0.3, sy - 0.2, side.eta, t);
    assert_rel(surf.w, surf.eta_t, 1e-15);
  }
}

/* ∂η/∂t + ∂(h u)/∂x + ∂(h v)/∂y = 0 (finite differences, h u = c η cos θ exactly): mass in the
 * depth-integrated sense. */
static void test_solitary_mass(void **state) {
  (void)state;
  const double thetas[] = {0.0, 0.5236, 2.7};
  for (size_t a = 0; a < 3; a++) {
    struct sph_solitary s;
    make_solitary(&s, 0.6, 0.3, thetas[a], 0.41);
    const double hx = 1e-3 / s.k, ht = hx / s.c;
    double worst = 0.0;
    for (int i = 0; i < 40; i++) {
      const double x = -2.0 + 0.1 * i, y = 0.37 - 0.05 * i, t = 0.2;
      double f[3][4]; /* eta_t, d(hu)/dx, d(hv)/dy stencils */
      const int m4[4] = {-2, -1, 1, 2};
      for (int m = 0; m < 4; m++) {
        const struct sph_wave_point pt = sol_at(&s, x, y, 0.1, t + m4[m] * ht);
        const struct sph_wave_point px = sol_at(&s, x + m4[m] * hx, y, 0.1, t);
        const struct sph_wave_point py = sol_at(&s, x, y + m4[m] * hx, 0.1, t);
        f[0][m] = pt.eta;
        f[1][m] = px.eta * px.u;
        f[2][m] = py.eta * py.v;
      }
      double div = 0.0;
      for (int c = 0; c < 3; c++)
        div += (-f[c][3] + 8.0 * f[c][2] - 8.0 * f[c][1] + f[c][0]) / (12.0 * (c == 0 ? ht : hx));
      worst = fmax(worst, fabs(div) / (s.A * s.k * s.c));
    }
    print_message("solitary theta = %.4f: depth-integrated mass residual <= %.1e A k c\n",
                  thetas[a], worst);
    assert_true(worst < 1e-9);
  }
}

/* θ → −θ mirrors y; a rotation of θ by α with the point rotated by α gives the same wave with the
 * velocity rotated. */
static void test_solitary_symmetry(void **state) {
  (void)state;
  const double th = 0.61, al = 0.93;
  struct sph_solitary p, m, r;
  make_solitary(&p, 0.6, 0.21, th, -0.7);
  make_solitary(&m, 0.6, 0.21, -th, -0.7);
  make_solitary(&r, 0.6, 0.21, th + al, -0.7);
  for (int i = 0; i < 20; i++) {
    const double x = -1.0 + 0.17 * i, y = 0.8 - 0.11 * i, z = 0.3, t = 0.4;
    const struct sph_wave_point a = sol_at(&p, x, y, z, t), b = sol_at(&m, x, -y, z, t);
    assert_rel(b.eta, a.eta, 1e-15);
    assert_rel(b.u, a.u, 1e-14);
    assert_abs(b.v, -a.v, 1e-15);
    assert_rel(b.w, a.w, 1e-14);
    assert_rel(b.p, a.p, 1e-14);
    const double xr = x * cos(al) - y * sin(al), yr = x * sin(al) + y * cos(al);
    const struct sph_wave_point q = sol_at(&r, xr, yr, z, t);
    assert_rel(q.eta, a.eta, 1e-13);
    assert_abs(q.u, a.u * cos(al) - a.v * sin(al), 1e-13);
    assert_abs(q.v, a.u * sin(al) + a.v * cos(al), 1e-13);
    assert_abs(q.w, a.w, 1e-13);
  }
}

/* Far from the crest (|ξ| = 10⁴): η = D, no overflow (traps on). */
static void test_solitary_far_and_errors(void **state) {
  (void)state;
  struct sph_solitary s;
  make_solitary(&s, 0.6, 0.3, 0.0, 0.0);
  const struct sph_wave_point o = sol_at(&s, 1e4 / s.k, 0.0, 0.3, 0.0);
  assert_true(o.eta == 0.6 && o.u == 0.0 && o.w == 0.0);
  struct sph_wave_point q;
  assert_int_equal(sph_solitary_eval(&s, 0.0, 0.0, 0.95, 0.0, &q), SPH_WAVE_EOUTSIDE);
  assert_true(q.p < 0.0);
  assert_int_equal(sph_solitary_eval(&s, 0.0, 0.0, -0.1, 0.0, &q), SPH_WAVE_EOUTSIDE);
  assert_int_equal(sph_solitary_eval(&s, 0.0, NAN, 0.1, 0.0, &q), SPH_WAVE_EINVAL);
  assert_int_equal(sph_solitary_eval(NULL, 0.0, 0.0, 0.1, 0.0, &q), SPH_WAVE_EINVAL);

  struct {
    double D, A, th, x0, g, rho;
    int status;
    const char *field;
  } bad[] = {
      {0.0, 0.3, 0, 0, 9.81, 1000, SPH_WAVE_EINVAL, "depth"},
      {NAN, 0.3, 0, 0, 9.81, 1000, SPH_WAVE_EINVAL, "depth"},
      {0.6, -0.3, 0, 0, 9.81, 1000, SPH_WAVE_EINVAL, "amplitude"},
      {0.6, 0.3, NAN, 0, 9.81, 1000, SPH_WAVE_EINVAL, "angle"},
      {0.6, 0.3, 0, INFINITY, 9.81, 1000, SPH_WAVE_EINVAL, "x0"},
      {0.6, 0.3, 0, 0, -9.81, 1000, SPH_WAVE_EINVAL, "g"},
      {0.6, 0.3, 0, 0, 9.81, 0, SPH_WAVE_EINVAL, "rho0"},
      {0.6, 0.5, 0, 0, 9.81, 1000, SPH_WAVE_EBREAK, "amplitude"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    struct sph_solitary_params p;
    sph_solitary_params_init(&p);
    p.depth = bad[i].D;
    p.amplitude = bad[i].A;
    p.angle = bad[i].th;
    p.x0 = bad[i].x0;
    p.g = bad[i].g;
    p.rho0 = bad[i].rho;
    char msg[256];
    assert_int_equal(sph_solitary_init(&s, &p, msg, sizeof msg), bad[i].status);
    assert_true(strncmp(msg, bad[i].field, strlen(bad[i].field)) == 0 &&
                msg[strlen(bad[i].field)] == ':');
  }
  assert_int_equal(sph_solitary_init(NULL, NULL, NULL, 0), SPH_WAVE_EINVAL);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_stokes_laplace_bed),
      cmocka_unit_test(test_stokes_euler),
      cmocka_unit_test(test_stokes_free_surface_order),
      cmocka_unit_test(test_stokes_flux),
      cmocka_unit_test(test_stokes_current_height_depth),
      cmocka_unit_test(test_stokes_airy_limit),
      cmocka_unit_test(test_stokes_period),
      cmocka_unit_test(test_stokes_deep),
      cmocka_unit_test(test_stokes_fourier_reference),
      cmocka_unit_test(test_stokes_errors),
      cmocka_unit_test(test_solitary_closed_form),
      cmocka_unit_test(test_solitary_mass),
      cmocka_unit_test(test_solitary_symmetry),
      cmocka_unit_test(test_solitary_far_and_errors),
  };
  return cmocka_run_group_tests(tests, sabre_setup_gsl_traps, NULL);
}
