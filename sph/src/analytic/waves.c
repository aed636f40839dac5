/*
 * Wave generators (sabre/sph_waves.h): Stokes fifth order after Fenton (1985), and the solitary
 * wave of J(42–47). Formulas, validity and verification: docs/sph-waves.md.
 *
 * Fenton's coefficients are rational functions of S = sech 2kd, some divided by sinh kd. They are
 * evaluated here through q = e^{−2kd} (S = 2q/(1 + q²), 1 − S = (1 − q)²/(1 + q²), tanh kd =
 * (1 − q)/(1 + q)) with 1 − q = −expm1(−2kd): no cancellation in 1 − S in shallow water, no
 * overflow of sinh kd or cosh jkz in deep water. For the latter, A_ij cosh(jkz) is written as
 * Â_ij · ½(e^{jk(z−d)} + e^{−jk(z+d)}) with Â_ij = A_ij e^{jkd}: every A_ij with harmonic j carries
 * a factor S^m / sinh^s kd with 2m + s ≥ j, so Â_ij is finite at any kd.
 */
#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include "sabre/sph_waves.h"

const char *sph_wave_strerror(int status) {
  switch (status) {
#define SPH_WAVE_X_TEXT(name, value, text) \
  case name:                               \
    return text;
    SPH_WAVE_STATUS_LIST(SPH_WAVE_X_TEXT)
#undef SPH_WAVE_X_TEXT
    default:
      return "unknown status";
  }
}

const char *sph_wave_status_name(int status) {
  switch (status) {
#define SPH_WAVE_X_NAME(name, value, text) \
  case name:                               \
    return #name;
    SPH_WAVE_STATUS_LIST(SPH_WAVE_X_NAME)
#undef SPH_WAVE_X_NAME
    default:
      return "SPH_WAVE_UNKNOWN";
  }
}

/* Write the message (if wanted) and return the status. */
static int fail(int status, char *msg, size_t msglen, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int fail(int status, char *msg, size_t msglen, const char *fmt, ...) {
  if (msg != NULL && msglen > 0) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, msglen, fmt, ap);
    va_end(ap);
  }
  return status;
}

/* SPH_WAVE_SUCCESS if x is finite and > 0, else a message naming the field. */
static int check_positive(const char *name, const char *unit, double x, char *msg, size_t len) {
  if (isfinite(x) && x > 0.0) return SPH_WAVE_SUCCESS;
  return fail(SPH_WAVE_EINVAL, msg, len, "%s: expected a positive finite number [%s], got %g", name,
              unit, x);
}

/* ---------------------------------------------------------------------------------------------
 * Stokes fifth order
 * ------------------------------------------------------------------------------------------- */

void sph_stokes5_params_init(struct sph_stokes5_params *p) {
  if (p == NULL) return;
  p->depth = p->height = p->length = p->period = 0.0;
  p->current = 0.0;
  p->g = 9.81;
  p->rho0 = 1000.0;
  p->ursell_max = SPH_WAVE_URSELL_MAX;
}

/* Fenton's coefficients at kd (Fenton 1985, Table 1, with the corrections of Fenton 1990), into
 * w->A_hat, B.., C.., D.., E.. . Only w->kd is read. */
static void stokes5_coefficients(struct sph_stokes5 *w) {
  const double kd = w->kd;
  const double q = exp(-2.0 * kd), om = -expm1(-2.0 * kd); /* e^{−2kd}, 1 − e^{−2kd} */
  const double S = 2.0 * q / (1.0 + q * q);
  const double oms = om * om / (1.0 + q * q); /* 1 − S */
  const double th = om / (1.0 + q), cth = (1.0 + q) / om;
  const double r = 2.0 / om;             /* e^{kd}/sinh kd */
  const double sh = 2.0 / (1.0 + q * q); /* S e^{2kd} */
  const double S2 = S * S, S3 = S2 * S, S4 = S3 * S, S5 = S4 * S, S6 = S5 * S, S7 = S6 * S,
               S8 = S7 * S;
  const double o2 = oms * oms, o3 = o2 * oms, o4 = o3 * oms, o5 = o4 * oms, o6 = o5 * oms;
  const double f32 = 3.0 + 2.0 * S, f4 = 4.0 + S;

  double(*A)[6] = w->A_hat;
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < 6; j++) A[i][j] = 0.0;
  /* Â_ij = A_ij e^{jkd}; the comment gives A_ij. */
  A[1][1] = r; /* 1/sinh kd */
  /* 3S²/(2(1−S)²) */
  A[2][2] = 3.0 * sh * sh * q / (2.0 * o2);
  /* (−4 − 20S + 10S² − 13S³)/(8 sinh kd (1−S)³) */
  A[3][1] = r * (-4.0 - 20.0 * S + 10.0 * S2 - 13.0 * S3) / (8.0 * o3);
  /* (−2S² + 11S³)/(8 sinh kd (1−S)³) */
  A[3][3] = r * sh * sh * q * (-2.0 + 11.0 * S) / (8.0 * o3);
  /* (12S − 14S² − 264S³ − 45S⁴ − 13S⁵)/(24(1−S)⁵) */
  A[4][2] = sh * (12.0 - 14.0 * S - 264.0 * S2 - 45.0 * S3 - 13.0 * S4) / (24.0 * o5);
  /* (10S³ − 174S⁴ + 291S⁵ + 278S⁶)/(48(3+2S)(1−S)⁵) */
  A[4][4] = sh * sh * sh * q * (10.0 - 174.0 * S + 291.0 * S2 + 278.0 * S3) / (48.0 * f32 * o5);
  /* (−1184 + 32S + 13232S² + 21712S³ + 20940S⁴ + 12554S⁵ − 500S⁶ − 3341S⁷ − 670S⁸)
   * /(64 sinh kd (3+2S)(4+S)(1−S)⁶) */
  A[5][1] = r *
            (-1184.0 + 32.0 * S + 13232.0 * S2 + 21712.0 * S3 + 20940.0 * S4 + 12554.0 * S5 -
             500.0 * S6 - 3341.0 * S7 - 670.0 * S8) /
            (64.0 * f32 * f4 * o6);
  /* (4S + 105S² + 198S³ − 1376S⁴ − 1302S⁵ − 117S⁶ + 58S⁷)/(32 sinh kd (3+2S)(1−S)⁶) */
  A[5][3] = r * sh *
            (4.0 + 105.0 * S + 198.0 * S2 - 1376.0 * S3 - 1302.0 * S4 - 117.0 * S5 + 58.0 * S6) /
            (32.0 * f32 * o6);
  /* (−6S³ + 272S⁴ − 1552S⁵ + 852S⁶ + 2029S⁷ + 430S⁸)/(64 sinh kd (3+2S)(4+S)(1−S)⁶) */
  A[5][5] = r * sh * sh * sh * q *
            (-6.0 + 272.0 * S - 1552.0 * S2 + 852.0 * S3 + 2029.0 * S4 + 430.0 * S5) /
            (64.0 * f32 * f4 * o6);

  w->B22 = cth * (1.0 + 2.0 * S) / (2.0 * oms);
  w->B31 = -3.0 * (1.0 + 3.0 * S + 3.0 * S2 + 2.0 * S3) / (8.0 * o3);
  w->B42 =
      cth * (6.0 - 26.0 * S - 182.0 * S2 - 204.0 * S3 - 25.0 * S4 + 26.0 * S5) / (6.0 * f32 * o4);
  w->B44 =
      cth * (24.0 + 92.0 * S + 122.0 * S2 + 66.0 * S3 + 67.0 * S4 + 34.0 * S5) / (24.0 * f32 * o4);
  w->B53 = 9.0 *
           (132.0 + 17.0 * S - 2216.0 * S2 - 5897.0 * S3 - 6292.0 * S4 - 2687.0 * S5 + 194.0 * S6 +
            467.0 * S7 + 82.0 * S8) /
           (128.0 * f32 * f4 * o6);
  w->B55 = 5.0 *
           (300.0 + 1579.0 * S + 3176.0 * S2 + 2949.0 * S3 + 1188.0 * S4 + 675.0 * S5 +
            1326.0 * S6 + 827.0 * S7 + 130.0 * S8) /
           (384.0 * f32 * f4 * o6);

  w->C0 = sqrt(th);
  w->C2 = w->C0 * (2.0 + 7.0 * S2) / (4.0 * o2);
  w->C4 = w->C0 * (4.0 + 32.0 * S - 116.0 * S2 - 400.0 * S3 - 71.0 * S4 + 146.0 * S5) / (32.0 * o5);
  w->D2 = -0.5 * sqrt(cth);
  w->D4 = sqrt(cth) * (2.0 + 4.0 * S + S2 + 2.0 * S3) / (8.0 * o3);
  w->E2 = th * (2.0 + 2.0 * S + 5.0 * S2) / (4.0 * o2);
  w->E4 = th * (8.0 + 12.0 * S - 152.0 * S2 - 308.0 * S3 - 42.0 * S4 + 77.0 * S5) / (32.0 * o5);
}

/* ū √(k/g) = C0 + ε² C2 + ε⁴ C4 at wave number k (coefficients at kd into *w). */
static double stokes5_ubar(struct sph_stokes5 *w, double k) {
  w->k = k;
  w->kd = k * w->d;
  w->eps = 0.5 * k * w->H;
  stokes5_coefficients(w);
  const double e2 = w->eps * w->eps;
  return sqrt(w->g / k) * (w->C0 + e2 * (w->C2 + e2 * w->C4));
}

/* Everything that follows from k once the coefficients are known. */
static void stokes5_finish(struct sph_stokes5 *w) {
  const double k = w->k, e = w->eps, e2 = e * e, g = w->g;
  w->L = 2.0 * M_PI / k;
  w->ubar = sqrt(g / k) * (w->C0 + e2 * (w->C2 + e2 * w->C4));
  w->c = w->u_E + w->ubar;
  w->omega = k * w->c;
  w->T = w->L / w->c;
  w->R = (g / k) * (0.5 * w->C0 * w->C0 + w->kd + e2 * (w->E2 + e2 * w->E4));
  w->q = sqrt(g / (k * k * k)) *
         (w->C0 * w->kd + e2 * (w->C2 * w->kd + w->D2) + e2 * e2 * (w->C4 * w->kd + w->D4));
  w->u_mass = w->c - w->q / w->d;
  w->ursell = w->H * w->L * w->L / (w->d * w->d * w->d);
  const double e3 = e2 * e, e4 = e2 * e2, e5 = e4 * e;
  const double(*A)[6] = (const double(*)[6])w->A_hat;
  w->b[0] = w->a[0] = 0.0;
  w->b[1] = e + e3 * w->B31 - e5 * (w->B53 + w->B55);
  w->b[2] = e2 * w->B22 + e4 * w->B42;
  w->b[3] = -e3 * w->B31 + e5 * w->B53;
  w->b[4] = e4 * w->B44;
  w->b[5] = e5 * w->B55;
  w->a[1] = e * A[1][1] + e3 * A[3][1] + e5 * A[5][1];
  w->a[2] = e2 * A[2][2] + e4 * A[4][2];
  w->a[3] = e3 * A[3][3] + e5 * A[5][3];
  w->a[4] = e4 * A[4][4];
  w->a[5] = e5 * A[5][5];
}

/* Breaking: H/L > SPH_WAVE_BREAKING tanh kd. */
static int breaks(double H, double k, double d) {
  return H * k / (2.0 * M_PI) > SPH_WAVE_BREAKING * tanh(k * d);
}

/* ω(k) − ω_T for the period solve; the struct carries d, H, u_E, g. */
struct period_fn {
  struct sph_stokes5 *w;
  double omega_T;
};
static double period_residual(double k, void *vp) {
  struct period_fn *f = vp;
  return k * (f->w->u_E + stokes5_ubar(f->w, k)) - f->omega_T;
}

/* Breaking limit in k: H k − 2π·0.142 tanh kd, increasing through zero once when H < 0.892 d. */
static double breaking_residual(double k, void *vp) {
  const struct sph_stokes5 *w = vp;
  return w->H * k - 2.0 * M_PI * SPH_WAVE_BREAKING * tanh(k * w->d);
}

/* Root of f in [lo, hi] (f(lo) < 0 < f(hi) or the reverse) by Brent to |Δk| ≤ 4 ε k. */
static int brent(gsl_root_fsolver *s, gsl_function *f, double lo, double hi, double *root) {
  if (gsl_root_fsolver_set(s, f, lo, hi) != GSL_SUCCESS) return SPH_WAVE_ENOCONV;
  for (int iter = 0; iter < 200; iter++) {
    if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) return SPH_WAVE_ENOCONV;
    const double a = gsl_root_fsolver_x_lower(s), b = gsl_root_fsolver_x_upper(s);
    if (gsl_root_test_interval(a, b, 0.0, 4.0 * DBL_EPSILON) == GSL_SUCCESS) {
      *root = gsl_root_fsolver_root(s);
      return SPH_WAVE_SUCCESS;
    }
  }
  return SPH_WAVE_ENOCONV;
}

/*
 * Wave number of the period T: the valid k lie in [k_a, k_b], k_a from the Ursell limit and k_b
 * from breaking. ω(k) is scanned on a geometric grid there for the first sign change of ω − ω_T,
 * then refined by Brent (several roots are possible only with an opposing current: the smallest
 * k, the longest wave, is the one that joins the wave without current).
 */
#define PERIOD_SCAN 256
static int stokes5_solve_period(struct sph_stokes5 *w, double T, double ursell_max, char *msg,
                                size_t len) {
  const double d = w->d, H = w->H;
  if (H >= 2.0 * M_PI * SPH_WAVE_BREAKING * d)
    return fail(SPH_WAVE_EBREAK, msg, len,
                "height: H/d = %.4g: every steady wave of this height breaks (H/L > %.3g tanh kd "
                "for all L requires H/d < %.4g)",
                H / d, SPH_WAVE_BREAKING, 2.0 * M_PI * SPH_WAVE_BREAKING);
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (s == NULL) return fail(SPH_WAVE_ENOMEM, msg, len, "period: memory allocation failed");
  int status;
  double k_b;
  {
    gsl_function f = {breaking_residual, w};
    const double hi = 4.0 * M_PI * SPH_WAVE_BREAKING / H; /* residual > 0 there */
    const double lo = 1e-6 / d;                           /* residual ≈ (H − 0.892 d) k < 0 */
    status = brent(s, &f, lo, hi, &k_b);
  }
  const double k_a = 2.0 * M_PI * sqrt(H / (ursell_max * d * d * d));
  if (status != SPH_WAVE_SUCCESS) {
    gsl_root_fsolver_free(s);
    return fail(status, msg, len, "period: the breaking limit in k did not converge");
  }
  if (!(k_a < k_b)) {
    gsl_root_fsolver_free(s);
    return fail(SPH_WAVE_ESHALLOW, msg, len,
                "height: H/d = %.4g: every wave of this height short enough for the series (Ursell "
                "number H L^2/d^3 <= %g) is steeper than the breaking limit",
                H / d, ursell_max);
  }
  struct period_fn pf = {w, 2.0 * M_PI / T};
  gsl_function f = {period_residual, &pf};
  double k_prev = k_a, f_prev = period_residual(k_a, &pf), f_first = f_prev, k_root = NAN;
  status = SPH_WAVE_ENOWAVE;
  for (int i = 1; i <= PERIOD_SCAN; i++) {
    const double k = i == PERIOD_SCAN ? k_b : k_a * pow(k_b / k_a, (double)i / PERIOD_SCAN);
    const double fk = period_residual(k, &pf);
    if (f_prev == 0.0 || fk == 0.0) { /* an exact hit */
      k_root = f_prev == 0.0 ? k_prev : k;
      status = SPH_WAVE_SUCCESS;
      break;
    }
    if ((f_prev < 0.0) != (fk < 0.0)) {
      status = brent(s, &f, k_prev, k, &k_root);
      break;
    }
    k_prev = k;
    f_prev = fk;
  }
  gsl_root_fsolver_free(s);
  if (status == SPH_WAVE_ENOCONV)
    return fail(status, msg, len, "period: the dispersion relation did not converge");
  /* No sign change: ω − ω_T kept the sign of f_first over the whole range. */
  if (status != SPH_WAVE_SUCCESS && f_first > 0.0)
    return fail(SPH_WAVE_ENOWAVE, msg, len,
                "period: T = %g s gives a wave too long for the depth (Ursell number H L^2/d^3 > "
                "%g, beyond the fifth-order series; the longest accepted period is %.6g s)",
                T, ursell_max, 2.0 * M_PI / (f_first + pf.omega_T));
  if (status != SPH_WAVE_SUCCESS && w->u_E >= 0.0) /* then ω(k_b) > 0 */
    return fail(SPH_WAVE_ENOWAVE, msg, len,
                "period: T = %g s gives a wave steeper than the breaking limit H/L = %.3g tanh kd "
                "(the shortest accepted period for this height is %.6g s)",
                T, SPH_WAVE_BREAKING, 2.0 * M_PI / (f_prev + pf.omega_T));
  if (status != SPH_WAVE_SUCCESS)
    return fail(SPH_WAVE_ENOWAVE, msg, len,
                "period: no wave of period T = %g s within the validity range: the opposing "
                "current (%g m/s) blocks it or it would break",
                T, w->u_E);
  w->k = k_root;
  return SPH_WAVE_SUCCESS;
}

int sph_stokes5_init(struct sph_stokes5 *w, const struct sph_stokes5_params *p, char *msg,
                     size_t msglen) {
  if (msg != NULL && msglen > 0) msg[0] = '\0';
  if (w == NULL || p == NULL) return fail(SPH_WAVE_EINVAL, msg, msglen, "NULL argument");
  int status;
  if ((status = check_positive("depth", "m", p->depth, msg, msglen)) ||
      (status = check_positive("height", "m", p->height, msg, msglen)) ||
      (status = check_positive("g", "m/s^2", p->g, msg, msglen)) ||
      (status = check_positive("rho0", "kg/m^3", p->rho0, msg, msglen)) ||
      (status = check_positive("ursell_max", "-", p->ursell_max, msg, msglen)))
    return status;
  if (!isfinite(p->current))
    return fail(SPH_WAVE_EINVAL, msg, msglen, "current: expected a finite number [m/s], got %g",
                p->current);
  const int has_L = p->length != 0.0, has_T = p->period != 0.0;
  if (has_L == has_T)
    return fail(SPH_WAVE_EINVAL, msg, msglen,
                has_L ? "length: give a wave length or a period, not both"
                      : "length: give a wave length or a period");
  if (has_L && (status = check_positive("length", "m", p->length, msg, msglen))) return status;
  if (has_T && (status = check_positive("period", "s", p->period, msg, msglen))) return status;

  w->d = p->depth;
  w->H = p->height;
  w->u_E = p->current;
  w->g = p->g;
  w->rho0 = p->rho0;
  if (has_T && (status = stokes5_solve_period(w, p->period, p->ursell_max, msg, msglen)))
    return status;
  const double k = has_L ? 2.0 * M_PI / p->length : w->k;
  const char *which = has_L ? "length" : "period";
  if (breaks(w->H, k, w->d))
    return fail(SPH_WAVE_EBREAK, msg, msglen,
                "height: H/L = %.4g exceeds the breaking limit %.3g tanh kd = %.4g (kd = %.4g): no "
                "steady wave of this height and length exists, and the series fails before it",
                w->H * k / (2.0 * M_PI), SPH_WAVE_BREAKING, SPH_WAVE_BREAKING * tanh(k * w->d),
                k * w->d);
  const double L = 2.0 * M_PI / k, ursell = w->H * L * L / (w->d * w->d * w->d);
  if (ursell > p->ursell_max)
    return fail(SPH_WAVE_ESHALLOW, msg, msglen,
                "%s: the wave is too long for the depth: Ursell number H L^2/d^3 = %.4g > %g (L/d "
                "= %.4g): outside the range of the fifth-order Stokes series",
                which, ursell, p->ursell_max, L / w->d);
  stokes5_ubar(w, k);
  stokes5_finish(w);
  if (!(w->c > 0.0))
    return fail(SPH_WAVE_ECURRENT, msg, msglen,
                "current: u_E = %g m/s against a wave of speed %g m/s relative to it: the phase "
                "speed c = %g m/s is not positive (the wave must travel towards +x)",
                w->u_E, w->ubar, w->c);
  return SPH_WAVE_SUCCESS;
}

int sph_stokes5_eval(const struct sph_stokes5 *w, double x, double z, double t,
                     struct sph_wave_point *out) {
  if (w == NULL || out == NULL || !isfinite(x) || !isfinite(z) || !isfinite(t))
    return SPH_WAVE_EINVAL;
  const double k = w->k, d = w->d;
  /* Phase θ = k(x − ct) reduced to [−π, π] before the harmonics. */
  double s = (x - w->c * t) / w->L;
  s -= nearbyint(s);
  const double th = 2.0 * M_PI * s, c1 = cos(th), s1 = sin(th);
  double cj[6], sj[6];
  cj[0] = 1.0;
  sj[0] = 0.0;
  for (int j = 1; j <= 5; j++) {
    cj[j] = cj[j - 1] * c1 - sj[j - 1] * s1;
    sj[j] = sj[j - 1] * c1 + cj[j - 1] * s1;
  }
  double keta = 0.0, eta_x = 0.0; /* k(η − d): added to d last, for precision in deep water */
  for (int j = 1; j <= 5; j++) {
    keta += w->b[j] * cj[j];
    eta_x -= j * w->b[j] * sj[j];
  }
  out->eta = d + keta / k;
  out->eta_x = eta_x;
  out->eta_y = 0.0;
  out->eta_t = -w->c * eta_x;
  out->v = 0.0;
  const int inside = z >= 0.0 && z <= out->eta;
  if (z > d + w->L || z < -w->L) {
    out->u = out->w = out->p = NAN;
    return SPH_WAVE_EOUTSIDE;
  }
  /* cosh(jkz) e^{−jkd} = ½(E^j + F^j), sinh(jkz) e^{−jkd} = ½(E^j − F^j). */
  const double E = exp(k * (z - d)), F = exp(-k * (z + d));
  double Ej = 1.0, Fj = 1.0, us = 0.0, ws = 0.0;
  for (int j = 1; j <= 5; j++) {
    Ej *= E;
    Fj *= F;
    us += j * w->a[j] * 0.5 * (Ej + Fj) * cj[j];
    ws += j * w->a[j] * 0.5 * (Ej - Fj) * sj[j];
  }
  const double V = w->C0 * sqrt(w->g / k);
  const double up = V * us, wp = V * ws; /* u − u_E, w */
  out->u = w->u_E + up;
  out->w = wp;
  const double ur = up - w->ubar; /* u − c */
  out->p = w->rho0 * (w->R - w->g * z - 0.5 * (ur * ur + wp * wp));
  return inside ? SPH_WAVE_SUCCESS : SPH_WAVE_EOUTSIDE;
}

/* ---------------------------------------------------------------------------------------------
 * Solitary wave, J(42–47)
 * ------------------------------------------------------------------------------------------- */

void sph_solitary_params_init(struct sph_solitary_params *p) {
  if (p == NULL) return;
  p->depth = p->amplitude = 0.0;
  p->angle = p->x0 = 0.0;
  p->g = 9.81;
  p->rho0 = 1000.0;
}

int sph_solitary_init(struct sph_solitary *s, const struct sph_solitary_params *p, char *msg,
                      size_t msglen) {
  if (msg != NULL && msglen > 0) msg[0] = '\0';
  if (s == NULL || p == NULL) return fail(SPH_WAVE_EINVAL, msg, msglen, "NULL argument");
  int status;
  if ((status = check_positive("depth", "m", p->depth, msg, msglen)) ||
      (status = check_positive("amplitude", "m", p->amplitude, msg, msglen)) ||
      (status = check_positive("g", "m/s^2", p->g, msg, msglen)) ||
      (status = check_positive("rho0", "kg/m^3", p->rho0, msg, msglen)))
    return status;
  if (!isfinite(p->angle))
    return fail(SPH_WAVE_EINVAL, msg, msglen, "angle: expected a finite number, got %g", p->angle);
  if (!isfinite(p->x0))
    return fail(SPH_WAVE_EINVAL, msg, msglen, "x0: expected a finite number [m], got %g", p->x0);
  if (p->amplitude > SPH_WAVE_SOLITARY_MAX * p->depth)
    return fail(SPH_WAVE_EBREAK, msg, msglen,
                "amplitude: A/D = %.4g exceeds %.2g, the highest solitary wave",
                p->amplitude / p->depth, SPH_WAVE_SOLITARY_MAX);
  s->D = p->depth;
  s->A = p->amplitude;
  s->g = p->g;
  s->rho0 = p->rho0;
  s->theta = p->angle;
  s->cos_theta = cos(p->angle);
  s->sin_theta = sin(p->angle);
  s->x0 = p->x0;
  s->k = sqrt(3.0 * s->A / (4.0 * s->D * s->D * s->D));
  s->c = sqrt(s->g * (s->A + s->D));
  return SPH_WAVE_SUCCESS;
}

int sph_solitary_eval(const struct sph_solitary *s, double x, double y, double z, double t,
                      struct sph_wave_point *out) {
  if (s == NULL || out == NULL || !isfinite(x) || !isfinite(y) || !isfinite(z) || !isfinite(t))
    return SPH_WAVE_EINVAL;
  const double xi = s->k * (x * s->cos_theta + y * s->sin_theta - s->c * t - s->x0);
  /* sech ξ = 2e^{−|ξ|}/(1 + e^{−2|ξ|}): no overflow of cosh far from the crest. */
  const double e = exp(-fabs(xi)), sech = 2.0 * e / (1.0 + e * e), th = tanh(xi);
  const double eta = s->A * sech * sech;      /* J(42), above the still level */
  const double deta = -2.0 * s->k * eta * th; /* ∂η/∂ξ' with ξ' = x cos θ + y sin θ */
  const double h = s->D + eta;                /* J(43) */
  const double eta_t = -s->c * deta;
  const double un = s->c * eta / h; /* J(45–46) along the direction of travel */
  out->eta = h;
  out->eta_x = deta * s->cos_theta;
  out->eta_y = deta * s->sin_theta;
  out->eta_t = eta_t;
  out->u = un * s->cos_theta;
  out->v = un * s->sin_theta;
  out->w = z / h * eta_t;            /* J(47) */
  out->p = s->rho0 * s->g * (h - z); /* J(44) with the gauge sign */
  return z >= 0.0 && z <= h ? SPH_WAVE_SUCCESS : SPH_WAVE_EOUTSIDE;
}
