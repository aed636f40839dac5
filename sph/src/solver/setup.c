/*
 * Solver set-up: kernel and EOS, initial fluid state (uniform or hydrostatic pressure, masses
 * m_a = ρ_a Δr^d), vertex masses, force groups; and the solver's own per-particle arrays.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "operators/pair.h"
#include "sabre/common.h"
#include "sabre/sph_solver.h"

/* Hydrostatic pressure at depth d ≥ 0 below the level of p = 0, exact for the Tait EOS:
 * dp/dd = ρ(p) |g|  ⇒  p = b [(1 + (ξ−1) |g| d / c0²)^(ξ/(ξ−1)) − 1]  (ξ = 1: b (e^{|g|d/c0²} − 1)),
 * b = ρ0 c0²/ξ. */
static double hydrostatic_pressure(const struct rmn_eos *e, double g, double d) {
  const double c2 = e->c0 * e->c0;
  if (e->isothermal) return e->b * expm1(g * d / c2);
  return e->b * expm1(e->xi / (e->xi - 1.0) * log1p((e->xi - 1.0) * g * d / c2));
}

/*
 * Vertex masses: least squares (CGLS) for Σ_v m_v w_av = γ_a ρ_a − Σ_{b∈F} m_b w_ab over the fluid,
 * so that the summation density of the fluid at its initial positions equals its initial density
 * (the time-summation continuity then starts from a consistent state).
 */
static void vertex_masses(struct sph_solver *sv) {
  struct sph_system *s = &sv->sys;
  struct sph_parts *f = &s->part[SPH_KIND_FLUID], *v = &s->part[SPH_KIND_VERTEX];
  const struct sph_kernel *k = &sv->kernel;
  const struct sph_nlist *fv = &sv->nb.list[SPH_KIND_VERTEX], *ff = &sv->nb.list[SPH_KIND_FLUID];
  const struct sph_nlist *vf = &sv->nb.vf;
  const size_t nf = f->n, nv = v->n;
  for (size_t i = 0; i < nv; i++) v->mass[i] = 0.0;
  if (nv == 0 || nf == 0) return;
  double *r = cmn_calloc(nf, sizeof *r), *q = cmn_calloc(nf, sizeof *q);
  double *x = cmn_calloc(nv, sizeof *x), *sres = cmn_calloc(nv, sizeof *sres);
  double *p = cmn_calloc(nv, sizeof *p);
  for (size_t a = 0; a < nf; a++) {
    double sum = f->mass[a] * sph_kernel_w_inline(k, 0.0);
    for (size_t j = ff->offset[a]; j < ff->offset[a + 1]; j++) {
      struct sph_pair pr;
      if (sph_pair_eval(k, s, f, a, f, ff->index[j], &pr)) sum += f->mass[ff->index[j]] * pr.w;
    }
    r[a] = f->gamma[a] * f->rho[a] - sum;
  }
  /* s = Aᵀ r */
#define ATR(out, in)                                                    \
  for (size_t iv = 0; iv < nv; iv++) {                                  \
    double acc = 0.0;                                                   \
    for (size_t j = vf->offset[iv]; j < vf->offset[iv + 1]; j++) {      \
      struct sph_pair pr;                                               \
      if (sph_pair_eval(k, s, v, iv, f, vf->index[j], &pr))             \
        acc += pr.w * (in)[vf->index[j]];                               \
    }                                                                   \
    (out)[iv] = acc;                                                    \
  }
  ATR(sres, r);
  double gam = 0.0;
  for (size_t i = 0; i < nv; i++) {
    p[i] = sres[i];
    gam += sres[i] * sres[i];
  }
  const double gam0 = gam;
  for (int it = 0; it < 500 && gam > 1e-24 * gam0 && gam > 0.0; it++) {
    double qq = 0.0;
    for (size_t a = 0; a < nf; a++) {
      double acc = 0.0;
      for (size_t j = fv->offset[a]; j < fv->offset[a + 1]; j++) {
        struct sph_pair pr;
        if (sph_pair_eval(k, s, f, a, v, fv->index[j], &pr)) acc += pr.w * p[fv->index[j]];
      }
      q[a] = acc;
      qq += acc * acc;
    }
    if (!(qq > 0.0)) break;
    const double alpha = gam / qq;
    for (size_t i = 0; i < nv; i++) x[i] += alpha * p[i];
    for (size_t a = 0; a < nf; a++) r[a] -= alpha * q[a];
    ATR(sres, r);
    double gnew = 0.0;
    for (size_t i = 0; i < nv; i++) gnew += sres[i] * sres[i];
    const double beta = gnew / gam;
    for (size_t i = 0; i < nv; i++) p[i] = sres[i] + beta * p[i];
    gam = gnew;
  }
#undef ATR
  for (size_t i = 0; i < nv; i++) v->mass[i] = x[i];
  free(r);
  free(q);
  free(x);
  free(sres);
  free(p);
}

void sph_solver_init(struct sph_solver *sv, const struct sph_config *cfg, struct sph_system *s,
                     const int *seg_wall, const long *seg_edge) {
  memset(sv, 0, sizeof *sv);
  sv->cfg = *cfg;
  sv->sys = *s;
  int dim = s->dim;
  memset(s, 0, sizeof *s);
  sph_system_init(s, dim);
  struct sph_system *sys = &sv->sys;
  if (sph_kernel_init(&sv->kernel, sys->dim, sys->h) != 0)
    cmn_error("bad kernel: dimension %d, h = %g m", sys->dim, sys->h);
  if (rmn_eos_init(&sv->eos, cfg->rho0, cfg->c0, cfg->xi) != RMN_SUCCESS)
    cmn_error("bad EOS: rho0 = %g, c0 = %g, xi = %g", cfg->rho0, cfg->c0, cfg->xi);

  struct sph_parts *f = &sys->part[SPH_KIND_FLUID];
  const double gnorm = sqrt(cfg->gravity[0] * cfg->gravity[0] + cfg->gravity[1] * cfg->gravity[1] +
                            cfg->gravity[2] * cfg->gravity[2]);
  double up[3] = {0.0, 0.0, 0.0}; /* −g/|g| */
  if (gnorm > 0.0)
    for (int c = 0; c < 3; c++) up[c] = -cfg->gravity[c] / gnorm;
  double level = cfg->free_surface;
  if (isnan(level)) {
    level = -INFINITY;
    for (size_t a = 0; a < f->n; a++)
      level = fmax(level, up[0] * f->x[0][a] + up[1] * f->x[1][a] + up[2] * f->x[2][a]);
    level += 0.5 * sys->dr;
  }
  const double vol = pow(sys->dr, sys->dim);
  for (size_t a = 0; a < f->n; a++) {
    double p = 0.0;
    if (cfg->hydrostatic && gnorm > 0.0) {
      double depth = level - (up[0] * f->x[0][a] + up[1] * f->x[1][a] + up[2] * f->x[2][a]);
      p = hydrostatic_pressure(&sv->eos, gnorm, fmax(depth, 0.0));
    }
    f->rho[a] = rmn_eos_density(&sv->eos, p);
    f->mass[a] = f->rho[a] * vol;
    for (int c = 0; c < 3; c++) f->v[c][a] = c < sys->dim ? cfg->u0[c] : 0.0;
  }
  struct sph_parts *v = &sys->part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++) v->rho[i] = cfg->rho0;

  sph_nbrs_build(&sv->nb, sys, cfg->skin_over_h * sys->h);
  sph_nbrs_gamma(&sv->nb, sys, &sv->kernel);
  sph_solver_sync(sv);
  sph_solver_boundary_values(sv);
  vertex_masses(sv);
  sph_solver_boundary_values(sv);

  sv->evaluated_step = -1;
  sv->mass_ref = 0.0;
  for (size_t a = 0; a < f->n; a++) sv->mass_ref += f->mass[a];
  for (size_t i = 0; i < v->n; i++) sv->mass_ref += v->mass[i];

  /* Force groups: a segment belongs to the first group naming its wall (and element); a vertex
   * to the group of the first segment using it. */
  const struct sph_parts *sg = &sys->part[SPH_KIND_SEGMENT];
  sv->seg_group = cmn_malloc((sg->n + 1) * sizeof *sv->seg_group);
  sv->vert_group = cmn_malloc((v->n + 1) * sizeof *sv->vert_group);
  for (size_t i = 0; i < v->n; i++) sv->vert_group[i] = -1;
  for (size_t j = 0; j < sg->n; j++) {
    sv->seg_group[j] = -1;
    for (int g = 0; g < cfg->nforces && seg_wall && sv->seg_group[j] < 0; g++) {
      const struct sph_force_group *fg = &cfg->forces[g];
      if (fg->wall != seg_wall[j]) continue;
      int match = fg->nedges == 0;
      for (int e = 0; e < fg->nedges && !match; e++) match = seg_edge && fg->edges[e] == seg_edge[j];
      if (match) sv->seg_group[j] = g;
    }
    for (int k = 0; k < sys->dim; k++) {
      size_t iv = sg->vertex[k][j];
      if (sv->vert_group[iv] < 0) sv->vert_group[iv] = sv->seg_group[j];
    }
  }
}

void sph_solver_free(struct sph_solver *sv) {
  for (int k = 0; k < SPH_NKINDS; k++) {
    free(sv->p[k]);
    free(sv->mu[k]);
  }
  for (int c = 0; c < 3; c++) {
    free(sv->acc[c]);
    free(sv->x0[c]);
    free(sv->v0[c]);
    free(sv->wall_flux[c]);
  }
  free(sv->rho_n);
  free(sv->gamma_n);
  free(sv->diff);
  free(sv->seg_group);
  free(sv->vert_group);
  sph_nbrs_free(&sv->nb);
  sph_system_free(&sv->sys);
  memset(sv, 0, sizeof *sv);
}
