/*
 * Mass through the open boundaries (sabre/sph_open.h, docs/sph-solver.md §10): the vertex masses
 * of J(14–15) through the predictor–corrector, and the i/o terms of the time-summation continuity
 * J(11–13). The mass fluxes ṁ_v themselves are computed with the boundary values (open.c).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "kernel.h"
#include "open_internal.h"
#include "sabre/common.h"
#include "sabre/sph_open.h"
#include "sabre/sph_solver.h"
#include "sabre/sph_walls.h"

void sph_open_mass_begin(struct sph_open *op, const struct sph_solver *sv) {
  if (!op) return;
  const struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++) op->mass0[i] = v->mass[i];
}

/* The lowest mass open vertex i may reach by an outflow from m0, its mass at the start of the
 * step: its wall mass less what it may owe (outflow_deficit particle masses), or m0 when below
 * that already (a floor never raises a mass). */
static double mass_floor(const struct sph_open *op, const struct sph_solver *sv, size_t i,
                         double m0) {
  const double owe =
      sv->cfg.open.group[op->vert_group[i]].outflow_deficit * sv->cfg.rho0 * op->cell_volume;
  return fmin(sv->sys.part[SPH_KIND_VERTEX].wall_mass[i] - owe, m0);
}

void sph_open_mass_set(struct sph_open *op, struct sph_solver *sv, double fac) {
  if (!op) return;
  struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++) {
    if (op->vert_group[i] < 0) continue;
    const double m = fac != 0.0 ? op->mass0[i] + fac * op->mdot[i] : op->mass0[i];
    v->mass[i] = op->mdot[i] < 0.0 ? fmax(m, mass_floor(op, sv, i, op->mass0[i])) : m;
  }
}

void sph_open_mass_end(struct sph_open *op, struct sph_solver *sv, double dt) {
  if (!op) return;
  sph_open_mass_set(op, sv, dt);
  /* what the floor held back, by the group of the vertex (0 bitwise when nothing was) */
  double held[SPH_MAX_OPEN_GROUPS] = {0.0};
  const struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++)
    if (op->vert_group[i] >= 0 && op->mdot[i] < 0.0)
      held[op->vert_group[i]] += v->mass[i] - (op->mass0[i] + dt * op->mdot[i]);
  for (int g = 0; g < op->ngroups; g++) {
    op->mass_step[g] = dt * op->stats[g].mass_flux + held[g];
    sph_open_kahan_add(&op->mass_entered[g], &op->mass_comp[0][g], op->mass_step[g]);
    sph_open_kahan_add(&op->mass_withheld[g], &op->mass_comp[2][g], held[g]);
  }
}

double sph_open_continuity_terms(const struct sph_open *op, const struct sph_solver *sv, size_t a,
                                 const double xa0[3], double rho_a0, double fac) {
  if (!op || sv->open_off || op->no_io_terms) return 0.0;
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT], *v = &s->part[SPH_KIND_VERTEX];
  const struct sph_kernel *k = &sv->kernel;
  const double support = sph_kernel_support(k);
  double seg_sum = 0.0, vert_sum = 0.0;
  /* ρ_a^n/2 Σ_s [∇γ_as(r_as^n + δr_s) + ∇γ_as(r_as^n)]·δr_s, δr_s = fac u_s (fixed boundary).
   * Only the elements within the support of either position count (∇γ_as is zero beyond it), so
   * that the sum does not depend on how far the list reaches (lists kept over several steps). */
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
    double foot[3];
    if (sph_element_distance(s->dim, (const double(*)[3])e.x, xa0, foot) >= support &&
        sph_element_distance(s->dim, (const double(*)[3])e.x, xa1, foot) >= support)
      continue;
    double t0, t1, g0[3], g1[3];
    sph_gamma_element(k, xa0, &e, &t0, g0);
    sph_gamma_element(k, xa1, &e, &t1, g1);
    for (int c = 0; c < 3; c++) seg_sum += (g0[c] + g1[c]) * dr[c];
  }
  /* Σ_v m_v^n [w(r_av^n) − w(r_av^n + δr_v)] over the open vertices, δr_v = fac u_v, and over
   * the wall vertices with the part of the open boundary's displacement along the wall (the
   * virtual motion slides the wall's vertex layer along itself with the open boundary, so that
   * the end of that layer at the open boundary moves with it; docs/sph-solver.md §10): the
   * displacement of the open vertex nearest to a, among those within the support (r < 2h: the
   * choice must not depend on how far the list reaches; ties go to the lowest index, the rows
   * being sorted). */
  const struct sph_nlist *lv = &sv->nb.list[SPH_KIND_VERTEX];
  double u_open[3] = {0.0, 0.0, 0.0}, best = INFINITY;
  for (size_t q = lv->offset[a]; q < lv->offset[a + 1]; q++) {
    const size_t i = lv->index[q];
    if (op->vert_group[i] < 0) continue;
    const double xv[3] = {v->x[0][i], v->x[1][i], v->x[2][i]};
    double d[3];
    sph_domain_delta(&s->domain, xv, xa0, d);
    const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (d2 < best && d2 < support * support) {
      best = d2;
      for (int c = 0; c < 3; c++) u_open[c] = v->v[c][i];
    }
  }
  if (best == INFINITY) return 0.5 * rho_a0 * seg_sum; /* no open vertex near a */
  for (size_t q = lv->offset[a]; q < lv->offset[a + 1]; q++) {
    const size_t i = lv->index[q];
    double u[3];
    if (op->vert_group[i] >= 0) {
      for (int c = 0; c < 3; c++) u[c] = v->v[c][i];
    } else {
      const double nv[3] = {v->normal[0][i], v->normal[1][i], v->normal[2][i]};
      const double nn = nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2];
      const double un =
          nn > 0.0 ? (u_open[0] * nv[0] + u_open[1] * nv[1] + u_open[2] * nv[2]) / nn : 0.0;
      for (int c = 0; c < 3; c++) u[c] = u_open[c] - un * nv[c];
    }
    if (u[0] == 0.0 && u[1] == 0.0 && u[2] == 0.0) continue;
    const double xv[3] = {v->x[0][i], v->x[1][i], v->x[2][i]};
    double d[3];
    sph_domain_delta(&s->domain, xv, xa0, d); /* r_av^n = r_a^n − r_v */
    const double r0 = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int c = 0; c < 3; c++) d[c] += fac * u[c];
    const double r1 = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (r0 >= support && r1 >= support) continue;
    vert_sum += op->mass0[i] * (sph_kernel_w_inline(k, r0) - sph_kernel_w_inline(k, r1));
  }
  return 0.5 * rho_a0 * seg_sum + vert_sum;
}

/* The weights of sph_open_share: share[d] for the segment's vertex d. */
static void share_weights(const struct sph_system *s, size_t j, const double x[3],
                          double share[3]) {
  const struct sph_parts *v = &s->part[SPH_KIND_VERTEX], *sg = &s->part[SPH_KIND_SEGMENT];
  const int dim = s->dim;
  double ex[3][3], foot[3], w[3] = {1.0, 0.0, 0.0};
  sph_segment_vertices(s, j, x, ex);
  sph_element_distance(dim, (const double(*)[3])ex, x, foot);
  if (dim == 2) {
    double t = 0.0, l2 = 0.0;
    for (int c = 0; c < 2; c++) {
      t += (foot[c] - ex[0][c]) * (ex[1][c] - ex[0][c]);
      l2 += (ex[1][c] - ex[0][c]) * (ex[1][c] - ex[0][c]);
    }
    t = fmin(fmax(t / l2, 0.0), 1.0);
    w[0] = 1.0 - t;
    w[1] = t;
  } else if (dim == 3) { /* barycentric: areas of the sub-triangles opposite each vertex */
    double total = 0.0;
    for (int d = 0; d < 3; d++) {
      const double *b = ex[(d + 1) % 3], *c2 = ex[(d + 2) % 3];
      double u[3], z[3];
      for (int c = 0; c < 3; c++) {
        u[c] = b[c] - foot[c];
        z[c] = c2[c] - foot[c];
      }
      const double cr[3] = {u[1] * z[2] - u[2] * z[1], u[2] * z[0] - u[0] * z[2],
                            u[0] * z[1] - u[1] * z[0]};
      w[d] = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
      total += w[d];
    }
    for (int d = 0; d < 3; d++) w[d] = total > 0.0 ? w[d] / total : 1.0 / 3.0;
  }
  /* corners take nothing: their weight goes to the others in proportion (all when every vertex
   * is a corner, or when the others have no weight) */
  double free_w = 0.0;
  int nfree = 0;
  for (int d = 0; d < dim; d++)
    if (!(v->flags[sg->vertex[d][j]] & SPH_FLAG_CORNER)) free_w += w[d], nfree++;
  share[0] = share[1] = share[2] = 0.0;
  for (int d = 0; d < dim; d++) {
    const size_t iv = sg->vertex[d][j];
    const int corner = (v->flags[iv] & SPH_FLAG_CORNER) != 0;
    if (nfree == 0)
      share[d] = w[d];
    else if (free_w > 0.0)
      share[d] = corner ? 0.0 : w[d] / free_w;
    else
      share[d] = corner ? 0.0 : 1.0 / nfree;
  }
}

void sph_open_share(const struct sph_system *s, size_t j, const double x[3], double q,
                    double *acc) {
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT];
  double share[3];
  share_weights(s, j, x, share);
  for (int d = 0; d < s->dim; d++) acc[sg->vertex[d][j]] += q * share[d];
}

long sph_open_exit_segment(const struct sph_open *op, const struct sph_solver *sv, size_t a) {
  if (!op || sv->open_off || !sv->nb.behind[a]) return -1;
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const struct sph_nlist *ls = &sv->nb.list[SPH_KIND_SEGMENT];
  const double xa[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
  /* behind[a] was decided by the elements within the support: the nearest is one of them, in
   * every list that covers the support, and ties go to the lowest index (sorted rows). */
  double dmin = INFINITY;
  long jmin = -1;
  for (size_t q = ls->offset[a]; q < ls->offset[a + 1]; q++) {
    const size_t j = ls->index[q];
    double ex[3][3], foot[3];
    sph_segment_vertices(s, j, xa, ex);
    const double d = sph_element_distance(s->dim, (const double(*)[3])ex, xa, foot);
    if (d < dmin) dmin = d, jmin = (long)j;
  }
  return jmin >= 0 && op->seg_group[jmin] >= 0 ? jmin : -1; /* behind a wall: not an exit */
}

/* Does open vertex iv take a share of its segments' fluxes: not a corner, and wet (at or below
 * the free surface, open.c)? */
static int takes_flux(const struct sph_open *op, const struct sph_parts *v, size_t iv) {
  return !(v->flags[iv] & SPH_FLAG_CORNER) &&
         op->pts[op->vert_group[iv]].wet[op->vert_point[iv]] > 0.0;
}

double sph_open_share_flux(const struct sph_system *s, const struct sph_open *op, size_t j,
                           double q, double *acc) {
  const struct sph_parts *v = &s->part[SPH_KIND_VERTEX], *sg = &s->part[SPH_KIND_SEGMENT];
  /* a d-th to each vertex that is not a corner; a dry vertex's share (a segment straddling the
   * free surface) to its wet vertices that are not corners */
  int nfree = 0, nwet = 0;
  for (int d = 0; d < s->dim; d++) {
    const size_t iv = sg->vertex[d][j];
    nfree += !(v->flags[iv] & SPH_FLAG_CORNER);
    nwet += takes_flux(op, v, iv);
  }
  if (nwet == 0) return 0.0;
  const double share = nwet == nfree ? q / s->dim : q * nfree / (s->dim * nwet);
  for (int d = 0; d < s->dim; d++)
    if (takes_flux(op, v, sg->vertex[d][j])) acc[sg->vertex[d][j]] += share;
  return nwet * share;
}

size_t sph_open_delete_particles(struct sph_open *op, struct sph_solver *sv) {
  if (!op) return 0;
  struct sph_system *s = &sv->sys;
  struct sph_parts *f = &s->part[SPH_KIND_FLUID], *v = &s->part[SPH_KIND_VERTEX];
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT];
  uint8_t *remove = NULL;
  size_t count = 0;
  for (size_t a = 0; a < f->n; a++) {
    const long jmin = sph_open_exit_segment(op, sv, a);
    if (jmin < 0) continue; /* in the fluid, or behind a wall: check_state's failure */
    if (!remove) remove = cmn_calloc(f->n + 1, 1);
    remove[a] = 1;
    const double xa[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
    const int g = op->seg_group[jmin];
    double w[3]; /* the particle's weights on the segment's vertices (sph_open_share's rule) */
    share_weights(s, (size_t)jmin, xa, w);
    for (int d = 0; d < s->dim; d++) {
      const size_t iv = sg->vertex[d][jmin];
      if (w[d] == 0.0) continue;
      const double q = w[d] * f->mass[a];
      if (op->mdot[iv] < 0.0) { /* outflow: back towards the wall mass, the rest leaves */
        const double dm = w[d] * (v->wall_mass[iv] - v->mass[iv]);
        v->mass[iv] += dm;
        sph_open_kahan_add(&op->mass_released[g], &op->mass_comp[1][g], q - dm);
      } else {
        v->mass[iv] += q; /* J(14) */
      }
    }
    op->deleted[g]++;
    count++;
  }
  if (!count) return 0;
  size_t k = 0;
  for (size_t a = 0; a < f->n; a++)
    if (!remove[a]) sv->nb.behind[k++] = sv->nb.behind[a];
  sph_parts_remove(f, remove);
  free(remove);
  return count;
}

size_t sph_open_create_particles(struct sph_open *op, struct sph_solver *sv) {
  if (!op) return 0;
  struct sph_system *s = &sv->sys;
  struct sph_parts *v = &s->part[SPH_KIND_VERTEX];
  /* the centre of the cell, Δr thick, in front of the layer the wall mass stands for: with the
   * difference form the lattice's wall gap λΔr (numerics.vertex_layer), one spacing before the
   * first row; with M(37) and its inflow layer the fitted φΔr, where that layer's centre is at one
   * particle mass (docs/sph-solver.md §10) */
  const double lambda = sv->cfg.open_gradient_difference ? sv->cfg.vertex_layer : sv->vertex_phi;
  const double offset = (lambda + 0.5) * s->dr;
  size_t count = 0;
  for (size_t i = 0; i < v->n; i++) {
    const int g = op->vert_group[i];
    if (g < 0 || (v->flags[i] & SPH_FLAG_CORNER)) continue;
    /* a volume Δr^d of the fluid that entered, at the density the boundary problem gave it (ρ0
     * for a vertex never solved, which has no flux either) */
    const double m = (v->rho[i] > 0.0 ? v->rho[i] : sv->cfg.rho0) * op->cell_volume;
    if (!(v->mass[i] - v->wall_mass[i] >= m)) continue;
    const double *n = op->pts[g].normal[op->vert_point[i]];
    const size_t a = sph_system_append(s, SPH_KIND_FLUID, 1);
    struct sph_parts *f = &s->part[SPH_KIND_FLUID];
    for (int c = 0; c < 3; c++) {
      f->x[c][a] = v->x[c][i] + offset * n[c];
      f->v[c][a] = v->v[c][i];
    }
    f->mass[a] = m;
    f->rho[a] = v->rho[i];
    f->p[a] = v->p[i];
    f->gamma[a] = 1.0; /* the closed form at its position replaces it at the next evaluation */
    v->mass[i] -= m;
    op->created[g]++;
    count++;
  }
  return count;
}

void sph_open_layer(struct sph_open *op, const struct sph_solver *sv) {
  if (!op) return;
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *v = &s->part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++) {
    op->layer_vol[i] = 0.0;
    const int g = op->vert_group[i];
    if (g < 0 || (v->flags[i] & SPH_FLAG_CORNER) || !(v->rho[i] > 0.0)) continue;
    const double dm = v->mass[i] - v->wall_mass[i];
    if (!(dm > 0.0)) continue;
    const double *n = op->pts[g].normal[op->vert_point[i]];
    double un = 0.0;
    for (int c = 0; c < 3; c++) un += v->v[c][i] * n[c];
    if (!(un > 0.0)) continue; /* an outflow (or a dry vertex, at rest): the mass stays at r_v */
    /* the layer of fluid δm stands for: δm/(ρ_v Δr^{d−1}) thick, in front of the wall layer */
    const double frac = dm / (v->rho[i] * op->cell_volume);
    const double off = (sv->vertex_phi + 0.5 * frac) * s->dr;
    op->layer_vol[i] = dm / v->rho[i];
    for (int c = 0; c < 3; c++) op->layer_x[c][i] = v->x[c][i] + off * n[c];
  }
}
