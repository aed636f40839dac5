/*
 * Scalar mode for fixed particles: boundary values (Robin/Neumann M 64–74 through sph_robin_*,
 * Dirichlet with a fitted normal derivative), the Laplacian M(18) through the solver's
 * sph_op_lap(), and velocity Verlet for u_tt = c² Lap u, M(75). Equations: docs/sph-scalar.md.
 */
#include <gsl/gsl_blas.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "operators/pair.h"
#include "sabre/common.h"
#include "sabre/sph_scalar.h"

void sph_scalar_bc_init(struct sph_scalar_bc *bc) {
  memset(bc, 0, sizeof *bc);
  bc->type = SPH_SCALAR_ROBIN;
  sph_robin_params_init(&bc->robin, 0.0);
  bc->value = 0.0;
  bc->order = 1;
}

double sph_scalar_auto_layer(const struct sph_system *s, const struct sph_nbrs *nb) {
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const struct sph_nlist *fs = &nb->list[SPH_KIND_SEGMENT];
  double dmin = INFINITY;
  for (size_t a = 0; a < fs->n; a++) {
    const double xa[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
    for (size_t q = fs->offset[a]; q < fs->offset[a + 1]; q++) {
      double v[3][3], foot[3];
      sph_segment_vertices(s, fs->index[q], xa, v);
      dmin = fmin(dmin, sph_element_distance(s->dim, (const double(*)[3])v, xa, foot));
    }
  }
  return isfinite(dmin) ? fmax(0.0, dmin / s->dr - 0.5) : 0.0;
}

void sph_scalar_init(struct sph_scalar *sc, struct sph_system *s, double c, double phi, int nbc,
                     const struct sph_scalar_bc *bc, const int *seg_bc) {
  memset(sc, 0, sizeof *sc);
  if (!(c > 0.0) || !isfinite(c)) cmn_error("wave speed c = %g must be positive", c);
  if (isnan(phi) || !isfinite(phi)) cmn_error("vertex layer phi = %g must be finite", phi);
  sc->sys = *s;
  const int dim = s->dim;
  memset(s, 0, sizeof *s);
  sph_system_init(s, dim);
  struct sph_system *sys = &sc->sys;
  if (sph_kernel_init(&sc->kernel, dim, sys->h) != 0)
    cmn_error("bad kernel: dimension %d, h = %g m", dim, sys->h);
  sc->c = c;
  const struct sph_parts *sg = &sys->part[SPH_KIND_SEGMENT];
  if (sg->n > 0 && (nbc < 1 || bc == NULL || seg_bc == NULL))
    cmn_error("%zu wall segments but no boundary groups", sg->n);

  /* Volumes: ρ = 1 everywhere, so that the store's masses are the volumes V = m/ρ. */
  struct sph_parts *f = &sys->part[SPH_KIND_FLUID], *v = &sys->part[SPH_KIND_VERTEX];
  const double vol = pow(sys->dr, dim);
  for (size_t a = 0; a < f->n; a++) {
    f->rho[a] = 1.0;
    f->mass[a] = vol;
  }
  for (size_t i = 0; i < v->n; i++) {
    v->rho[i] = 1.0;
    v->mass[i] = 0.0;
  }
  for (size_t j = 0; j < sg->n; j++) {
    sys->part[SPH_KIND_SEGMENT].rho[j] = 1.0;
    for (int d = 0; d < dim; d++) v->mass[sg->vertex[d][j]] += sg->measure[j] / dim;
  }

  /* The particles do not move: lists (radius 2h) and wall integrals once. */
  sph_nbrs_build(&sc->nb, sys, 0.0);
  sph_nbrs_gamma(&sc->nb, sys, &sc->kernel);
  if (sc->nb.escaped >= 0) {
    const long a = sc->nb.escaped;
    cmn_error(
        "fluid particle %ld at (%g, %g, %g) lies behind a wall (%zu of %zu fluid particles "
        "do, the one with the lowest index is named)",
        a, f->x[0][a], f->x[1][a], f->x[2][a], sc->nb.nescaped, f->n);
  }
  if (phi < 0.0) phi = sph_scalar_auto_layer(sys, &sc->nb);
  sc->phi = phi;
  for (size_t i = 0; i < v->n; i++) v->mass[i] *= phi * sys->dr; /* V_v = φ A_v Δr */

  sc->nbc = nbc;
  sc->bc = cmn_malloc(((size_t)nbc + 1) * sizeof *sc->bc);
  for (int g = 0; g < nbc; g++) {
    sc->bc[g] = bc[g];
    if (sc->bc[g].robin.length == 0.0) sc->bc[g].robin.length = sph_kernel_support(&sc->kernel);
    if (sc->bc[g].type == SPH_SCALAR_DIRICHLET &&
        (sc->bc[g].order < 1 || sc->bc[g].order > SPH_ROBIN_M_MAX))
      cmn_error("boundary group %d: Dirichlet order %d outside 1..%d", g, sc->bc[g].order,
                SPH_ROBIN_M_MAX);
  }
  sc->seg_bc = cmn_malloc((sg->n + 1) * sizeof *sc->seg_bc);
  sc->vert_bc = cmn_malloc((v->n + 1) * sizeof *sc->vert_bc);
  for (size_t i = 0; i < v->n; i++) sc->vert_bc[i] = -1;
  for (size_t j = 0; j < sg->n; j++) {
    if (seg_bc[j] < 0 || seg_bc[j] >= nbc)
      cmn_error("segment %zu: boundary group %d outside 0..%d", j, seg_bc[j], nbc - 1);
    sc->seg_bc[j] = seg_bc[j];
    for (int d = 0; d < dim; d++) {
      size_t iv = sg->vertex[d][j];
      if (sc->vert_bc[iv] < 0) sc->vert_bc[iv] = seg_bc[j];
    }
  }
  for (size_t i = 0; i < v->n; i++)
    if (sc->vert_bc[i] < 0) cmn_error("vertex %zu belongs to no segment", i);

  for (int k = 0; k < SPH_NKINDS; k++) {
    const size_t n = sys->part[k].n + 1;
    sc->u[k] = cmn_calloc(n, sizeof(double));
    sc->one[k] = cmn_malloc(n * sizeof(double));
    for (size_t i = 0; i < n; i++) sc->one[k][i] = 1.0;
    if (k != SPH_KIND_FLUID) sc->dudn[k] = cmn_calloc(n, sizeof(double));
  }
  sc->ut = cmn_calloc(f->n + 1, sizeof(double));
  sc->lap = cmn_calloc(f->n + 1, sizeof(double));
  const struct sph_nlist *fs = &sc->nb.list[SPH_KIND_SEGMENT];
  sc->flux_cap = (fs->n ? fs->offset[fs->n] : 0) + 1;
  sc->flux = cmn_calloc(sc->flux_cap, sizeof(double));
}

void sph_scalar_free(struct sph_scalar *sc) {
  for (int k = 0; k < SPH_NKINDS; k++) {
    free(sc->u[k]);
    free(sc->one[k]);
    free(sc->dudn[k]);
  }
  free(sc->ut);
  free(sc->lap);
  free(sc->flux);
  free(sc->bc);
  free(sc->seg_bc);
  free(sc->vert_bc);
  sph_nbrs_free(&sc->nb);
  sph_system_free(&sc->sys);
  memset(sc, 0, sizeof *sc);
}

/*
 * Dirichlet: ∂u/∂n at a vertex of value g from the weighted least squares
 *   min Σ_a V_a w_va (u_a − g − Σ_{j=1..m} c_j x_a^j)²,  x_a = r_av·n_v,
 * in scaled distance ξ = x/L (columns ξ^j are O(1)); ∂u/∂n = c_1 = β_1/L. Same solve as
 * sph_robin_finish (normal equations, GSL one-sided Jacobi SVD, no allocation).
 */
struct dirichlet_fit {
  int m;
  double a[SPH_ROBIN_M_MAX * SPH_ROBIN_M_MAX], b[SPH_ROBIN_M_MAX];
  double v[SPH_ROBIN_M_MAX * SPH_ROBIN_M_MAX], s[SPH_ROBIN_M_MAX], work[SPH_ROBIN_M_MAX],
      beta[SPH_ROBIN_M_MAX];
  double distinct[SPH_ROBIN_M_MAX];
  int n_distinct;
};

static void dirichlet_add(struct dirichlet_fit *d, double xi, double y, double weight,
                          double dist_tol) {
  if (!(weight > 0.0)) return;
  const int m = d->m;
  double row[SPH_ROBIN_M_MAX];
  double pw = 1.0;
  for (int j = 0; j < m; j++) {
    pw *= xi;
    row[j] = pw;
  }
  for (int j = 0; j < m; j++)
    for (int k = 0; k < m; k++) d->a[j * m + k] += weight * row[j] * row[k];
  for (int j = 0; j < m; j++) d->b[j] += weight * row[j] * y;
  /* ξ = 0 adds nothing to the fit: it is not a distinct distance. */
  if (d->n_distinct < m && fabs(xi) > dist_tol) {
    int is_new = 1;
    for (int k = 0; k < d->n_distinct; k++)
      if (fabs(xi - d->distinct[k]) <= dist_tol) is_new = 0;
    if (is_new) d->distinct[d->n_distinct++] = xi;
  }
}

static int dirichlet_solve(struct dirichlet_fit *d, double rcond_min, double *beta1) {
  const size_t m = (size_t)d->m;
  if (d->n_distinct < d->m) return SPH_ROBIN_ETOOFEW;
  gsl_matrix_view a = gsl_matrix_view_array(d->a, m, m);
  gsl_matrix_view v = gsl_matrix_view_array(d->v, m, m);
  gsl_vector_view s = gsl_vector_view_array(d->s, m);
  gsl_vector_view work = gsl_vector_view_array(d->work, m);
  gsl_vector_view b = gsl_vector_view_array(d->b, m);
  gsl_vector_view beta = gsl_vector_view_array(d->beta, m);
  if (gsl_linalg_SV_decomp_jacobi(&a.matrix, &v.matrix, &s.vector) != GSL_SUCCESS)
    return SPH_ROBIN_ESINGULAR;
  double smax = 0.0, smin = INFINITY;
  for (size_t j = 0; j < m; j++) {
    smax = fmax(smax, d->s[j]);
    smin = fmin(smin, d->s[j]);
  }
  if (!(smax > 0.0) || !(smin >= rcond_min * smax) || !(smin > 0.0)) return SPH_ROBIN_ESINGULAR;
  gsl_blas_dgemv(CblasTrans, 1.0, &a.matrix, &b.vector, 0.0, &work.vector);
  for (size_t j = 0; j < m; j++) d->work[j] /= d->s[j];
  gsl_blas_dgemv(CblasNoTrans, 1.0, &v.matrix, &work.vector, 0.0, &beta.vector);
  if (!isfinite(d->beta[0])) return SPH_ROBIN_ESINGULAR;
  *beta1 = d->beta[0];
  return SPH_ROBIN_SUCCESS;
}

/* Value and normal derivative at vertex iv from the fluid values u_F. */
static int vertex_value(struct sph_scalar *sc, size_t iv, double *u_v, double *dudn_v) {
  const struct sph_system *s = &sc->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID], *v = &s->part[SPH_KIND_VERTEX];
  const struct sph_nlist *vf = &sc->nb.vf;
  const struct sph_scalar_bc *bc = &sc->bc[sc->vert_bc[iv]];
  const double *uf = sc->u[SPH_KIND_FLUID];
  const double n_v[3] = {v->normal[0][iv], v->normal[1][iv], v->normal[2][iv]};
  if (bc->type == SPH_SCALAR_ROBIN) {
    const struct sph_robin_params *p = &bc->robin;
    sph_robin_begin(&sc->ws, p, s->dim, n_v);
    for (size_t q = vf->offset[iv]; q < vf->offset[iv + 1]; q++) {
      size_t b = vf->index[q];
      struct sph_pair pr;
      if (!sph_pair_eval(&sc->kernel, s, v, iv, f, b, &pr)) continue;
      const double r_av[3] = {-pr.r[0], -pr.r[1], -pr.r[2]}; /* pr.r = r_v − r_b */
      sph_robin_add(&sc->ws, r_av, uf[b], f->mass[b] / f->rho[b] * pr.w, 1.0);
    }
    int status = sph_robin_finish(&sc->ws, u_v);
    *dudn_v = (p->mu3 - p->mu1 * *u_v) / p->mu2; /* M(65) */
    return status;
  }
  struct dirichlet_fit d;
  memset(&d, 0, sizeof d);
  d.m = bc->order;
  const double inv_len = 1.0 / bc->robin.length;
  for (size_t q = vf->offset[iv]; q < vf->offset[iv + 1]; q++) {
    size_t b = vf->index[q];
    struct sph_pair pr;
    if (!sph_pair_eval(&sc->kernel, s, v, iv, f, b, &pr)) continue;
    const double x = -(pr.r[0] * n_v[0] + pr.r[1] * n_v[1] + pr.r[2] * n_v[2]);
    dirichlet_add(&d, x * inv_len, uf[b] - bc->value, f->mass[b] / f->rho[b] * pr.w,
                  bc->robin.dist_tol);
  }
  *u_v = bc->value;
  double beta1 = NAN;
  int status = dirichlet_solve(&d, bc->robin.rcond_min, &beta1);
  *dudn_v = beta1 * inv_len;
  return status;
}

int sph_scalar_boundary_values(struct sph_scalar *sc, long *bad_vertex) {
  struct sph_system *s = &sc->sys;
  const struct sph_parts *v = &s->part[SPH_KIND_VERTEX], *sg = &s->part[SPH_KIND_SEGMENT];
  if (bad_vertex) *bad_vertex = -1;
  for (size_t iv = 0; iv < v->n; iv++) {
    int status = vertex_value(sc, iv, &sc->u[SPH_KIND_VERTEX][iv], &sc->dudn[SPH_KIND_VERTEX][iv]);
    if (status != SPH_ROBIN_SUCCESS) {
      if (bad_vertex) *bad_vertex = (long)iv;
      return status;
    }
  }
  const int dim = s->dim;
  for (size_t j = 0; j < sg->n; j++) {
    double us = 0.0, dn = 0.0;
    for (int k = 0; k < dim; k++) {
      us += sc->u[SPH_KIND_VERTEX][sg->vertex[k][j]];
      dn += sc->dudn[SPH_KIND_VERTEX][sg->vertex[k][j]];
    }
    us /= dim;
    dn /= dim;
    const struct sph_scalar_bc *bc = &sc->bc[sc->seg_bc[j]];
    if (bc->type == SPH_SCALAR_ROBIN) dn = (bc->robin.mu3 - bc->robin.mu1 * us) / bc->robin.mu2;
    sc->u[SPH_KIND_SEGMENT][j] = us;
    sc->dudn[SPH_KIND_SEGMENT][j] = dn;
  }
  /* Wall term of M(18) with f = 1: −2/γ_a Σ_s ∂u/∂n|_s |∇γ_as|; sph_op_lap() takes the flux
   * β_s ∂u/∂n|_s + β_a ∂u/∂n|_a of J(8), which is 2 ∂u/∂n|_s for β = 1. */
  const struct sph_nlist *fs = &sc->nb.list[SPH_KIND_SEGMENT];
  const size_t npairs = fs->n ? fs->offset[fs->n] : 0;
  if (npairs >= sc->flux_cap) {
    sc->flux_cap = npairs + 1;
    sc->flux = cmn_realloc(sc->flux, sc->flux_cap * sizeof(double));
  }
  for (size_t a = 0; a < fs->n; a++)
    for (size_t q = fs->offset[a]; q < fs->offset[a + 1]; q++)
      sc->flux[q] = 2.0 * sc->dudn[SPH_KIND_SEGMENT][fs->index[q]];
  return SPH_ROBIN_SUCCESS;
}

int sph_scalar_laplacian(struct sph_scalar *sc, long *bad_vertex) {
  int status = sph_scalar_boundary_values(sc, bad_vertex);
  if (status != SPH_ROBIN_SUCCESS) return status;
  const struct sph_op op = {&sc->sys, &sc->kernel, &sc->nb, 0};
  const double *beta[SPH_NKINDS], *A[SPH_NKINDS][3];
  for (int k = 0; k < SPH_NKINDS; k++) {
    beta[k] = sc->one[k];
    A[k][0] = sc->u[k];
    A[k][1] = A[k][2] = NULL;
  }
  const double *flux[3] = {sc->flux, NULL, NULL};
  const size_t n = sc->sys.part[SPH_KIND_FLUID].n;
#ifdef _OPENMP
#pragma omp parallel for schedule(static)
#endif
  for (size_t a = 0; a < n; a++) {
    double out[3];
    sph_op_lap(&op, (const double *const *)beta, (const double *const(*)[3])A,
               (const double *const *)flux, a, out);
    sc->lap[a] = out[0];
  }
  return SPH_ROBIN_SUCCESS;
}

static void vertex_message(const struct sph_scalar *sc, long iv, int status, char *msg,
                           size_t msglen) {
  const struct sph_parts *v = &sc->sys.part[SPH_KIND_VERTEX];
  snprintf(msg, msglen,
           "step %ld, t = %.9g s: vertex %ld at (%g, %g, %g), boundary group %d: %s (%s)",
           sc->step + 1, sc->time, iv, v->x[0][iv], v->x[1][iv], v->x[2][iv], sc->vert_bc[iv],
           sph_robin_strerror(status), sph_robin_status_name(status));
}

int sph_scalar_step(struct sph_scalar *sc, double dt, char *msg, size_t msglen) {
  const struct sph_parts *f = &sc->sys.part[SPH_KIND_FLUID];
  const size_t n = f->n;
  double *u = sc->u[SPH_KIND_FLUID], *ut = sc->ut;
  const double half = 0.5 * dt * sc->c * sc->c;
  /* Kick, drift (u^{n+1} = u^n + Δt u_t^n + Δt²/2 c² Lap u^n), new Laplacian, kick. */
  for (size_t a = 0; a < n; a++) {
    ut[a] += half * sc->lap[a];
    u[a] += dt * ut[a];
  }
  long bad;
  int status = sph_scalar_laplacian(sc, &bad);
  if (status != SPH_ROBIN_SUCCESS) {
    vertex_message(sc, bad, status, msg, msglen);
    return -1;
  }
  for (size_t a = 0; a < n; a++) {
    ut[a] += half * sc->lap[a];
    if (!isfinite(u[a]) || !isfinite(ut[a])) {
      snprintf(msg, msglen,
               "step %ld, t = %.9g s: u = %g, u_t = %g at fluid particle %zu (%g, %g, %g): "
               "unstable (time step above the limit?)",
               sc->step + 1, sc->time + dt, u[a], ut[a], a, f->x[0][a], f->x[1][a], f->x[2][a]);
      return -1;
    }
  }
  sc->time += dt;
  sc->step++;
  return 0;
}

double sph_scalar_spectral_radius(struct sph_scalar *sc, int iters) {
  const size_t n = sc->sys.part[SPH_KIND_FLUID].n;
  if (n == 0 || iters < 1) return 0.0;
  double *u = sc->u[SPH_KIND_FLUID];
  double *save = cmn_malloc(n * sizeof *save), *lap0 = cmn_malloc(n * sizeof *lap0);
  memcpy(save, u, n * sizeof *save);
  /* Affine part (μ3 ≠ 0, Dirichlet g ≠ 0): Lap of u = 0, subtracted from every product. */
  double radius = NAN;
  memset(u, 0, n * sizeof *u);
  if (sph_scalar_laplacian(sc, NULL) != SPH_ROBIN_SUCCESS) goto done;
  memcpy(lap0, sc->lap, n * sizeof *lap0);
  /* Sawtooth start: rich in the highest lattice frequencies, which carry the largest |λ|. */
  for (size_t a = 0; a < n; a++) u[a] = (a % 2 ? 1.0 : -1.0) * (1.0 + 0.1 * (double)(a % 7));
  radius = 0.0;
  for (int it = 0; it < iters; it++) {
    double nx = 0.0, ny = 0.0;
    for (size_t a = 0; a < n; a++) nx += u[a] * u[a];
    if (sph_scalar_laplacian(sc, NULL) != SPH_ROBIN_SUCCESS) {
      radius = NAN;
      goto done;
    }
    for (size_t a = 0; a < n; a++) {
      const double y = sc->lap[a] - lap0[a];
      ny += y * y;
    }
    if (!(ny > 0.0)) break;
    radius = sqrt(ny / nx);
    const double scale = 1.0 / sqrt(ny);
    for (size_t a = 0; a < n; a++) u[a] = (sc->lap[a] - lap0[a]) * scale;
  }
done:
  memcpy(u, save, n * sizeof *save);
  sph_scalar_laplacian(sc, NULL);
  free(save);
  free(lap0);
  return radius;
}

double sph_scalar_dt_limit(const struct sph_scalar *sc, double radius) {
  return 2.0 / (sc->c * sqrt(radius));
}
