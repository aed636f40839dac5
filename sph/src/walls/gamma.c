/*
 * γ_a and ∇γ_a over a set of wall elements, J(2)–J(4), with the solid-angle limit for points on
 * the walls, and the dynamic form M(4). The per-dimension element integrals are in gamma1d.c,
 * gamma2d.c and gamma3d.c; derivations in docs/sph-gamma.md.
 */
#include <math.h>

#include "kernel.h"
#include "sabre/sph_walls.h"
#include "walls/gamma_impl.h"

typedef void (*element_fn)(const struct sph_kernel *, const double *,
                           const struct sph_wall_element *, const double *, double *, double *);
typedef int (*incident_fn)(const struct sph_kernel *, const double *,
                           const struct sph_wall_element *, double, double *);
typedef int (*check_fn)(const struct sph_wall_element *);

static const element_fn element_fns[4] = {NULL, sph_gamma1d_element, sph_gamma2d_element,
                                          sph_gamma3d_element};
static const incident_fn incident_fns[4] = {NULL, sph_gamma1d_incident, sph_gamma2d_incident,
                                            sph_gamma3d_incident};
static const check_fn check_fns[4] = {NULL, sph_gamma1d_check, sph_gamma2d_check,
                                      sph_gamma3d_check};

void sph_gamma_element(const struct sph_kernel *k, const double *a,
                       const struct sph_wall_element *e, double *gamma_term,
                       double grad_gamma_as[3]) {
  element_fns[k->dim](k, a, e, NULL, gamma_term, grad_gamma_as);
}

/* Move a (on the walls) onto the nearest element vertex, or else the nearest triangle edge, within
 * SPH_GAMMA_SNAP_TOL·h; as = a if there is none. */
static void snap(const struct sph_kernel *k, const double *a, size_t n,
                 const struct sph_wall_element *e, double as[3]) {
  const int dim = k->dim, nv = dim;
  const double tol = SPH_GAMMA_SNAP_TOL * k->h;
  double best = tol * tol;
  int found = 0;
  for (size_t s = 0; s < n; s++)
    for (int j = 0; j < nv; j++) {
      double d2 = 0.0;
      for (int i = 0; i < dim; i++) d2 += (a[i] - e[s].x[j][i]) * (a[i] - e[s].x[j][i]);
      if (d2 <= best) {
        best = d2;
        found = 1;
        for (int i = 0; i < dim; i++) as[i] = e[s].x[j][i];
      }
    }
  if (found || dim < 3) return;
  for (size_t s = 0; s < n; s++)
    for (int j = 0; j < 3; j++) {
      const double *x0 = e[s].x[j], *x1 = e[s].x[(j + 1) % 3];
      double u[3], r[3], uu = 0.0, ru = 0.0;
      for (int i = 0; i < 3; i++) {
        u[i] = x1[i] - x0[i];
        r[i] = a[i] - x0[i];
        uu += u[i] * u[i];
        ru += r[i] * u[i];
      }
      const double t = ru / uu;
      if (t <= 0.0 || t >= 1.0) continue;
      double d2 = 0.0, p[3];
      for (int i = 0; i < 3; i++) {
        p[i] = x0[i] + t * u[i];
        d2 += (a[i] - p[i]) * (a[i] - p[i]);
      }
      if (d2 <= best) {
        best = d2;
        for (int i = 0; i < 3; i++) as[i] = p[i];
      }
    }
}

static int fail(double *gamma, double grad_gamma[3]) {
  if (gamma != NULL) *gamma = NAN;
  if (grad_gamma != NULL) grad_gamma[0] = grad_gamma[1] = grad_gamma[2] = NAN;
  return -1;
}

int sph_gamma_eval(const struct sph_kernel *k, const double *a, size_t n,
                   const struct sph_wall_element *e, double *gamma, double grad_gamma[3]) {
  if (k == NULL || a == NULL || gamma == NULL || grad_gamma == NULL || (n > 0 && e == NULL) ||
      k->dim < 1 || k->dim > 3 || !isfinite(k->h) || k->h <= 0.0)
    return fail(gamma, grad_gamma);
  const int dim = k->dim;
  for (int i = 0; i < dim; i++)
    if (!isfinite(a[i])) return fail(gamma, grad_gamma);

  /* Pass 1: validate, and find whether a lies on the walls, near an element vertex or edge. */
  const double tol_plane = SPH_GAMMA_PLANE_TOL * k->h, tol_snap = SPH_GAMMA_SNAP_TOL * k->h;
  int on_wall = 0;
  for (size_t s = 0; s < n; s++) {
    if (check_fns[dim](&e[s]) != 0) return fail(gamma, grad_gamma);
    on_wall |= incident_fns[dim](k, a, &e[s], tol_snap, NULL);
  }
  double as[3] = {a[0], dim > 1 ? a[1] : 0.0, dim > 2 ? a[2] : 0.0};
  double m[3] = {0.0, 0.0, 0.0};
  const double *dir = NULL;
  if (on_wall) {
    /* A point on the walls near a vertex or edge is moved onto it, so that every element sharing
     * that vertex or edge classifies it alike (docs/sph-gamma.md §6); then the pseudo-normal m of
     * the elements containing it is the common direction of approach from the fluid. */
    snap(k, a, n, e, as);
    int touched = 0;
    for (size_t s = 0; s < n; s++) touched += incident_fns[dim](k, as, &e[s], tol_plane, m);
    if (touched > 0) {
      const double mn = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
      if (!(mn > 1e-8)) return fail(gamma, grad_gamma);
      for (int i = 0; i < 3; i++) m[i] /= mn;
      /* m must not be tangent to any touched element (e.g. on a zero-thickness plate). */
      for (size_t s = 0; s < n; s++) {
        double tmp[3] = {0.0, 0.0, 0.0};
        if (incident_fns[dim](k, as, &e[s], tol_plane, tmp)) {
          const double tn = sqrt(tmp[0] * tmp[0] + tmp[1] * tmp[1] + tmp[2] * tmp[2]);
          if (!(fabs(m[0] * tmp[0] + m[1] * tmp[1] + m[2] * tmp[2]) > 1e-8 * tn))
            return fail(gamma, grad_gamma);
        }
      }
      dir = m;
    }
  }

  /* Pass 2: G1 and J(4). */
  double sum_term = 0.0, g[3] = {0.0, 0.0, 0.0};
  for (size_t s = 0; s < n; s++) {
    double term, gs[3];
    element_fns[dim](k, as, &e[s], dir, &term, gs);
    sum_term += term;
    for (int i = 0; i < 3; i++) g[i] += gs[i];
  }
  *gamma = 1.0 - sum_term;
  for (int i = 0; i < 3; i++) grad_gamma[i] = g[i];
  return 0;
}

double sph_gamma_dynamic_step(double gamma_old, const double *v_old, const double *grad_old,
                              const double *v_new, const double *grad_new, int dim, double dt) {
  double rate_old = 0.0, rate_new = 0.0;
  for (int i = 0; i < dim; i++) {
    rate_old += v_old[i] * grad_old[i];
    rate_new += v_new[i] * grad_new[i];
  }
  return gamma_old + 0.5 * dt * (rate_old + rate_new);
}
