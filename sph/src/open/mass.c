/*
 * Mass through the open boundaries (sabre/sph_open.h, docs/sph-solver.md §10): the vertex masses
 * of J(14–15) through the predictor–corrector, and the i/o terms of the time-summation continuity
 * J(11–13). The mass fluxes ṁ_v themselves are computed with the boundary values (open.c).
 */
#include <math.h>
#include <string.h>

#include "kernel.h"
#include "sabre/common.h"
#include "sabre/sph_open.h"
#include "sabre/sph_solver.h"
#include "sabre/sph_walls.h"

void sph_open_mass_begin(struct sph_open *op, const struct sph_solver *sv) {
  if (!op) return;
  const struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++) op->mass0[i] = v->mass[i];
}

void sph_open_mass_set(struct sph_open *op, struct sph_solver *sv, double fac) {
  if (!op) return;
  struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++)
    if (op->vert_group[i] >= 0)
      v->mass[i] = fac != 0.0 ? op->mass0[i] + fac * op->mdot[i] : op->mass0[i];
}

void sph_open_mass_end(struct sph_open *op, struct sph_solver *sv, double dt) {
  if (!op) return;
  sph_open_mass_set(op, sv, dt);
  for (int g = 0; g < op->ngroups; g++) op->mass_step[g] = dt * op->stats[g].mass_flux;
}

double sph_open_continuity_terms(const struct sph_open *op, const struct sph_solver *sv, size_t a,
                                 const double xa0[3], double rho_a0, double fac) {
  if (!op || sv->open_off || op->no_io_terms) return 0.0;
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT], *v = &s->part[SPH_KIND_VERTEX];
  const struct sph_kernel *k = &sv->kernel;
  const double support = sph_kernel_support(k);
  double seg_sum = 0.0, vert_sum = 0.0;
  /* ρ_a^n/2 Σ_s [∇γ_as(r_as^n + δr_s) + ∇γ_as(r_as^n)]·δr_s, δr_s = fac u_s (fixed boundary) */
  const struct sph_nlist *ls = &sv->nb.list[SPH_KIND_SEGMENT];
  for (size_t q = ls->offset[a]; q < ls->offset[a + 1]; q++) {
    const size_t j = ls->index[q];
    if (op->seg_group[j] < 0) continue;
    const double dr[3] = {fac * sg->v[0][j], fac * sg->v[1][j], fac * sg->v[2][j]};
    if (dr[0] == 0.0 && dr[1] == 0.0 && dr[2] == 0.0) continue;
    struct sph_wall_element e;
    sph_segment_vertices(s, j, xa0, e.x);
    for (int c = 0; c < 3; c++) e.normal[c] = sg->normal[c][j];
    const double xa1[3] = {xa0[0] + dr[0], xa0[1] + dr[1], xa0[2] + dr[2]};
    double t0, t1, g0[3], g1[3];
    sph_gamma_element(k, xa0, &e, &t0, g0);
    sph_gamma_element(k, xa1, &e, &t1, g1);
    for (int c = 0; c < 3; c++) seg_sum += (g0[c] + g1[c]) * dr[c];
  }
  /* Σ_v m_v^n [w(r_av^n) − w(r_av^n + δr_v)], δr_v = fac u_v */
  const struct sph_nlist *lv = &sv->nb.list[SPH_KIND_VERTEX];
  for (size_t q = lv->offset[a]; q < lv->offset[a + 1]; q++) {
    const size_t i = lv->index[q];
    if (op->vert_group[i] < 0) continue;
    const double xv[3] = {v->x[0][i], v->x[1][i], v->x[2][i]};
    double d[3];
    sph_domain_delta(&s->domain, xv, xa0, d); /* r_av^n = r_a^n − r_v */
    const double r0 = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int c = 0; c < 3; c++) d[c] += fac * v->v[c][i];
    const double r1 = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (r0 >= support && r1 >= support) continue;
    vert_sum += op->mass0[i] * (sph_kernel_w_inline(k, r0) - sph_kernel_w_inline(k, r1));
  }
  return 0.5 * rho_a0 * seg_sum + vert_sum;
}
