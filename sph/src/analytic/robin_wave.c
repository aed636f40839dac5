/*
 * Analytical solution M(78–79) of the Robin wave problem M(75–77), M §6.2. Derivation of the
 * root bracketing, the orthogonality, ‖φ_i‖², the projection α_i and the tail correction:
 * docs/sph-robin.md §3.
 */
#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdlib.h>

#include "sabre/sph_analytic.h"

/* κ − 2 arctan(1/κ) − jπ: zero exactly at the roots of M(79) with κ ∈ [jπ, (j + 1)π]. */
static double root_fn(double kappa, void *param) {
  const double j = *(const double *)param;
  return kappa - 2.0 * atan2(1.0, kappa) - j * M_PI;
}

static int find_root(gsl_root_fsolver *s, size_t i, double *kappa) {
  double j = (double)(i - 1);
  gsl_function f = {root_fn, &j};
  const double lo = j * M_PI, hi = (j + 1.0) * M_PI;
  if (gsl_root_fsolver_set(s, &f, lo, hi) != GSL_SUCCESS) return SPH_ROBIN_ENOCONV;
  for (int iter = 0; iter < 200; iter++) {
    if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) return SPH_ROBIN_ENOCONV;
    const double a = gsl_root_fsolver_x_lower(s), b = gsl_root_fsolver_x_upper(s);
    if (gsl_root_test_interval(a, b, 0.0, 4.0 * DBL_EPSILON) == GSL_SUCCESS ||
        root_fn(gsl_root_fsolver_root(s), &j) == 0.0) {
      *kappa = gsl_root_fsolver_root(s);
      return SPH_ROBIN_SUCCESS;
    }
  }
  return SPH_ROBIN_ENOCONV;
}

int sph_robin_wave_root(size_t i, double *kappa) {
  if (kappa == NULL || i == 0) return SPH_ROBIN_EINVAL;
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (s == NULL) return SPH_ROBIN_ENOMEM;
  const int status = find_root(s, i, kappa);
  gsl_root_fsolver_free(s);
  return status;
}

int sph_robin_wave_init(struct sph_robin_wave *w, size_t n_terms) {
  if (w == NULL) return SPH_ROBIN_EINVAL;
  w->n_terms = 0;
  w->kappa = w->alpha = NULL;
  w->tail = 1;
  if (n_terms == 0) return SPH_ROBIN_EINVAL;
  double *kappa = malloc(n_terms * sizeof *kappa);
  double *alpha = malloc(n_terms * sizeof *alpha);
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (kappa == NULL || alpha == NULL || s == NULL) {
    free(kappa);
    free(alpha);
    if (s != NULL) gsl_root_fsolver_free(s);
    return SPH_ROBIN_ENOMEM;
  }
  const double k = 2.0 * M_PI; /* u_t(x, 0) = sin(kx) */
  for (size_t i = 1; i <= n_terms; i++) {
    const int status = find_root(s, i, &kappa[i - 1]);
    if (status != SPH_ROBIN_SUCCESS) {
      free(kappa);
      free(alpha);
      gsl_root_fsolver_free(s);
      return status;
    }
    /* (κ² − k²) <sin kx, φ_i> = k (φ_i(1) − φ_i(0)) = k κ_i ((−1)^(i−1) − 1) and
     * ‖φ_i‖² = (κ_i² + 3)/2, so α_i κ_i = <sin kx, φ_i>/‖φ_i‖² (docs/sph-robin.md §3.3). */
    const double kap = kappa[i - 1];
    alpha[i - 1] = i % 2 == 1 ? 0.0 : -4.0 * k / ((kap * kap - k * k) * (kap * kap + 3.0));
  }
  gsl_root_fsolver_free(s);
  w->n_terms = n_terms;
  w->kappa = kappa;
  w->alpha = alpha;
  return SPH_ROBIN_SUCCESS;
}

void sph_robin_wave_free(struct sph_robin_wave *w) {
  if (w == NULL) return;
  free(w->kappa);
  free(w->alpha);
  w->kappa = w->alpha = NULL;
  w->n_terms = 0;
}

/* y reduced to [−1, 1] modulo 2. */
static double reduce2(double y) { return y - 2.0 * nearbyint(0.5 * y); }

void sph_robin_wave_eval(const struct sph_robin_wave *w, double x, double t, double *u, double *u_t,
                         double *u_x) {
  const double k = 2.0 * M_PI;
  double su = 0.0, sut = 0.0, sux = 0.0;
  for (size_t i = 2; i <= w->n_terms; i += 2) { /* α_i = 0 for odd i */
    const double kap = w->kappa[i - 1], a = w->alpha[i - 1];
    const double skx = sin(kap * x), ckx = cos(kap * x);
    const double skt = sin(kap * t), ckt = cos(kap * t);
    const double phi = skx + kap * ckx;
    const double dphi = kap * ckx - kap * kap * skx;
    su += a * skt * phi;
    double tut = a * kap * ckt * phi, tux = a * skt * dphi;
    if (w->tail) {
      /* Leading asymptotic term of mode i (n = i − 1 odd, κ_i = nπ + O(1/n)): subtracted here,
       * its sum over all odd n added below in closed form. */
      const double np = (double)(i - 1) * M_PI, c = 4.0 * k / (np * np);
      tut += c * cos(np * x) * cos(np * t);
      tux -= c * sin(np * x) * sin(np * t);
    }
    sut += tut;
    sux += tux;
  }
  if (w->tail) {
    /* Σ_{n odd} cos(nπy)/n² = (π²/8)(1 − 2|y|) for |y| ≤ 1, 2-periodic. */
    const double yp = fabs(reduce2(x + t)), ym = fabs(reduce2(x - t));
    sut += -0.25 * k * ((1.0 - 2.0 * yp) + (1.0 - 2.0 * ym));
    sux += 0.5 * k * (yp - ym);
  }
  if (u != NULL) *u = su;
  if (u_t != NULL) *u_t = sut;
  if (u_x != NULL) *u_x = sux;
}
