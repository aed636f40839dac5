/*
 * Open-boundary values (sabre/sph_open.h, docs/sph-solver.md §10): per group, the interior state
 * of each point (segment centroid or open vertex) by Shepard interpolation J(33–35), the imposed
 * value there, and one rmn_boundary_solve_batch call (J §III, docs/theory.md §1.1); the results
 * replace the wall values of the group's segments and vertices in the store.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "open_internal.h"
#include "operators/pair.h"
#include "sabre/common.h"
#include "sabre/sph_open.h"
#include "sabre/sph_solver.h"

static double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static int fail_create(int *failed, char *msg, size_t msglen, struct sph_open *op, const char *fmt,
                       ...) __attribute__((format(printf, 5, 6)));
static int fail_create(int *failed, char *msg, size_t msglen, struct sph_open *op, const char *fmt,
                       ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, msglen, fmt, ap);
  va_end(ap);
  *failed = 1;
  sph_open_free(op);
  return 0;
}

/* Shepard sums of one point: Σ V_b w, Σ V_b w p̃_b (p_b with the hydrostatic correction),
 * Σ V_b w p_b, Σ V_b w max(p̃_b, 0) and Σ V_b w v_b. */
struct shepard {
  double alpha, p, p_raw, p_pos, u[3];
  double ztop; /* the highest of the fluid particles summed, along −g [m] */
};

/* Does group g select segment j? */
static int selects(const struct sph_open_group *g, const struct sph_parts *sg, size_t j,
                   const int *seg_wall, const long *seg_edge) {
  if (!seg_wall) return 0;
  const double n[3] = {sg->normal[0][j], sg->normal[1][j], sg->normal[2][j]};
  return sph_open_group_selects(g, seg_wall[j], seg_edge ? seg_edge[j] : 0, n, sg->flags[j]);
}

struct sph_open *sph_open_create(const struct sph_solver *sv, const int *seg_wall,
                                 const long *seg_edge, int *failed, char *msg, size_t msglen) {
  const struct sph_open_config *oc = &sv->cfg.open;
  *failed = 0;
  if (msglen > 0) msg[0] = '\0';
  if (oc->ngroups == 0) return NULL;
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT], *v = &s->part[SPH_KIND_VERTEX];
  const int dim = s->dim, ng = oc->ngroups;
  struct sph_open *op = cmn_calloc(1, sizeof *op);
  op->ngroups = ng;
  op->src = cmn_calloc((size_t)ng, sizeof *op->src);
  op->pts = cmn_calloc((size_t)ng, sizeof *op->pts);
  op->stats = cmn_calloc((size_t)ng, sizeof *op->stats);
  op->seg_group = cmn_malloc((sg->n + 1) * sizeof *op->seg_group);
  op->seg_point = cmn_malloc((sg->n + 1) * sizeof *op->seg_point);
  op->vert_group = cmn_malloc((v->n + 1) * sizeof *op->vert_group);
  op->vert_point = cmn_malloc((v->n + 1) * sizeof *op->vert_point);
  /* Segments: the group that selects them (exactly one for an open segment). */
  for (size_t j = 0; j < sg->n; j++) {
    op->seg_group[j] = -1;
    op->seg_point[j] = -1;
    for (int g = 0; g < ng && op->seg_group[j] < 0; g++)
      if (selects(&oc->group[g], sg, j, seg_wall, seg_edge)) op->seg_group[j] = g;
    if (op->seg_group[j] >= 0 && !(sg->flags[j] & SPH_FLAG_OPEN)) {
      fail_create(failed, msg, msglen, op,
                  "open boundary '%s': segment %zu (element %ld of geometry.walls[%d]) is a wall, "
                  "not open",
                  oc->group[op->seg_group[j]].name, j, seg_edge ? seg_edge[j] : 0L,
                  seg_wall ? seg_wall[j] : -1);
      return NULL;
    }
    if (op->seg_group[j] < 0 && (sg->flags[j] & SPH_FLAG_OPEN)) {
      fail_create(failed, msg, msglen, op,
                  "open segment %zu at (%g, %g, %g) (element %ld of geometry.walls[%d]) belongs "
                  "to no open_boundaries group",
                  j, sg->x[0][j], sg->x[1][j], sg->x[2][j], seg_edge ? seg_edge[j] : 0L,
                  seg_wall ? seg_wall[j] : -1);
      return NULL;
    }
  }
  /* Vertices: the group of their first open segment (corners shared with walls included). */
  for (size_t i = 0; i < v->n; i++) op->vert_group[i] = -1, op->vert_point[i] = -1;
  for (size_t j = 0; j < sg->n; j++)
    for (int k = 0; k < dim && op->seg_group[j] >= 0; k++) {
      const size_t iv = sg->vertex[k][j];
      if (op->vert_group[iv] < 0) op->vert_group[iv] = op->seg_group[j];
    }
  for (int g = 0; g < ng; g++) {
    struct sph_open_points *pt = &op->pts[g];
    for (size_t j = 0; j < sg->n; j++) pt->nseg += op->seg_group[j] == g;
    for (size_t i = 0; i < v->n; i++) pt->nvert += op->vert_group[i] == g;
    if (pt->nseg == 0) {
      fail_create(failed, msg, msglen, op, "open boundary '%s' selects no segment",
                  oc->group[g].name);
      return NULL;
    }
    const size_t n = pt->npoints = pt->nseg + pt->nvert;
    pt->index = cmn_malloc(n * sizeof *pt->index);
    pt->normal = cmn_calloc(n, sizeof *pt->normal);
    pt->measure = cmn_calloc(n, sizeof *pt->measure);
    pt->element = cmn_malloc(n * sizeof *pt->element);
    pt->zrange = cmn_calloc(n, sizeof *pt->zrange);
    pt->alpha = cmn_calloc(n, sizeof *pt->alpha);
    pt->wet = cmn_calloc(n, sizeof *pt->wet);
    pt->p_int = cmn_calloc(n, sizeof *pt->p_int);
    pt->u_int = cmn_calloc(n, sizeof *pt->u_int);
    pt->value = cmn_calloc(n, sizeof *pt->value);
    pt->in = cmn_calloc(n, sizeof *pt->in);
    pt->out = cmn_calloc(n, sizeof *pt->out);
    pt->slot = cmn_malloc(n * sizeof *pt->slot);
    size_t k = 0;
    for (size_t j = 0; j < sg->n; j++) {
      if (op->seg_group[j] != g) continue;
      op->seg_point[j] = (long)k;
      pt->index[k] = j;
      for (int c = 0; c < 3; c++) pt->normal[k][c] = sg->normal[c][j];
      pt->measure[k] = sg->measure[j];
      pt->element[k] = seg_edge ? seg_edge[j] : 0;
      k++;
    }
    for (size_t i = 0; i < v->n; i++) {
      if (op->vert_group[i] != g) continue;
      op->vert_point[i] = (long)k;
      pt->index[k] = i;
      pt->element[k] = -1;
      k++;
    }
    /* A vertex's normal: the measure-weighted mean of its open segments' normals in this group
     * (at a corner the wall's normal does not enter: the vertex is a point of the open boundary).
     */
    for (size_t j = 0; j < sg->n; j++) {
      if (op->seg_group[j] != g) continue;
      for (int d = 0; d < dim; d++) {
        const size_t iv = sg->vertex[d][j];
        if (op->vert_group[iv] != g) continue;
        for (int c = 0; c < 3; c++)
          pt->normal[op->vert_point[iv]][c] += sg->measure[j] * sg->normal[c][j];
      }
    }
    for (size_t q = pt->nseg; q < n; q++) {
      const double len = sqrt(dot3(pt->normal[q], pt->normal[q]));
      if (!(len > 0.0)) {
        fail_create(failed, msg, msglen, op,
                    "open boundary '%s': vertex %zu: its open segments' normals cancel",
                    oc->group[g].name, pt->index[q]);
        return NULL;
      }
      for (int c = 0; c < 3; c++) pt->normal[q][c] /= len;
    }
    char err[1536];
    if (sph_open_source_init(&op->src[g], &oc->group[g], dim, sv->cfg.gravity, &sv->eos, err,
                             sizeof err) != 0) {
      fail_create(failed, msg, msglen, op, "%s", err);
      return NULL;
    }
    rmn_params_default(&op->params[g]);
    op->params[g].shock = (enum rmn_shock_model)oc->group[g].shock;
    /* vertical extents for the wet rule (open.c: wet_fraction) */
    const double *up = op->src[g].up;
    for (size_t q = 0; q < n; q++) {
      const size_t i = pt->index[q];
      double lo = INFINITY, hi = -INFINITY;
      for (int d = 0; d < (q < pt->nseg ? dim : 1); d++) {
        const size_t iv = q < pt->nseg ? sg->vertex[d][i] : i;
        const double z = dot3((const double[3]){v->x[0][iv], v->x[1][iv], v->x[2][iv]}, up);
        lo = fmin(lo, z);
        hi = fmax(hi, z);
      }
      pt->zrange[q][0] = lo;
      pt->zrange[q][1] = hi;
    }
  }
  size_t nvert_open = 0;
  for (size_t i = 0; i < v->n; i++) nvert_open += op->vert_group[i] >= 0;
  op->wall_v = cmn_calloc(nvert_open + 1, sizeof *op->wall_v);
  op->mdot = cmn_calloc(v->n + 1, sizeof *op->mdot);
  op->mass0 = cmn_calloc(v->n + 1, sizeof *op->mass0);
  for (size_t i = 0; i < v->n; i++) op->mass0[i] = v->mass[i];
  op->layer_vol = cmn_calloc(v->n + 1, sizeof *op->layer_vol); /* sph_open_layer() */
  for (int c = 0; c < 3; c++) op->layer_x[c] = cmn_calloc(v->n + 1, sizeof *op->layer_x[c]);
  op->cell_volume = pow(sv->sys.dr, dim);
  for (size_t i = 0, q = 0; i < v->n; i++)
    if (op->vert_group[i] >= 0) {
      for (int c = 0; c < 3; c++) op->wall_v[q][c] = v->v[c][i];
      q++;
    }
  size_t ntot = 0;
  for (int g = 0; g < ng; g++) ntot += op->pts[g].npoints;
  op->work = cmn_calloc((ntot + 1) * sizeof(struct shepard) / sizeof(double), sizeof(double));
  op->ws = rmn_workspace_alloc();
  if (!op->ws) cmn_error("riemann workspace: out of memory");
  for (int g = 0; g < ng; g++) op->stats[g].level = NAN;
  return op;
}

void sph_open_free(struct sph_open *op) {
  if (!op) return;
  for (int g = 0; g < op->ngroups; g++) {
    sph_open_source_free(&op->src[g]);
    struct sph_open_points *pt = &op->pts[g];
    free(pt->index);
    free(pt->normal);
    free(pt->measure);
    free(pt->element);
    free(pt->alpha);
    free(pt->p_int);
    free(pt->u_int);
    free(pt->wet);
    free(pt->zrange);
    free(pt->value);
    free(pt->in);
    free(pt->out);
    free(pt->slot);
  }
  free(op->src);
  free(op->pts);
  free(op->stats);
  free(op->seg_group);
  free(op->seg_point);
  free(op->vert_group);
  free(op->vert_point);
  free(op->wall_v);
  free(op->mdot);
  free(op->mass0);
  free(op->layer_vol);
  for (int c = 0; c < 3; c++) free(op->layer_x[c]);
  free(op->work);
  rmn_workspace_free(op->ws);
  free(op);
}

void sph_open_restore_walls(struct sph_open *op, struct sph_solver *sv) {
  if (!op) return;
  struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  for (size_t i = 0, q = 0; i < v->n; i++)
    if (op->vert_group[i] >= 0) {
      for (int c = 0; c < 3; c++) v->v[c][i] = op->wall_v[q][c];
      q++;
    }
}

static void shepard_add(struct shepard *sh, const struct sph_parts *f, size_t b,
                        const struct sph_pair *pr, int hydro, const double *gravity,
                        const double *up, const double *n) {
  const double vw = f->mass[b] / f->rho[b] * pr->w;
  const double z = dot3((const double[3]){f->x[0][b], f->x[1][b], f->x[2][b]}, up);
  if (z > sh->ztop) sh->ztop = z;
  double pb = f->p[b];
  if (hydro != SPH_VHYDRO_NONE) {
    double r[3] = {pr->r[0], pr->r[1], pr->r[2]}; /* r_point − r_b */
    if (hydro == SPH_VHYDRO_TANGENTIAL) {
      const double rn = dot3(r, n);
      for (int c = 0; c < 3; c++) r[c] -= rn * n[c];
    }
    pb += f->rho[b] * dot3(gravity, r);
  }
  sh->alpha += vw;
  sh->p += vw * pb;
  sh->p_raw += vw * f->p[b];
  sh->p_pos += vw * fmax(pb, 0.0);
  for (int c = 0; c < 3; c++) sh->u[c] += vw * f->v[c][b];
}

static const char *imposed_text(const struct sph_open_group *g, const struct sph_open_value *val,
                                char *buf, size_t len) {
  if (g->imposed == RMN_IMPOSE_PRESSURE)
    snprintf(buf, len, "imposed pressure %.9g Pa (tangential velocity (%.6g, %.6g, %.6g) m/s)",
             val->p, val->u[0], val->u[1], val->u[2]);
  else
    snprintf(buf, len, "imposed normal velocity %.9g m/s (velocity (%.6g, %.6g, %.6g) m/s)",
             val->un, val->u[0], val->u[1], val->u[2]);
  return buf;
}

/* The level of an absorbing hydrostatic outlet (docs/sph-solver.md §10): the shallow-water
 * Riemann invariants u ± 2√(g d) along the outward normal, the outgoing one u_out + 2√(g d_int)
 * from the fluid (its measured level and the mean Shepard outflow velocity of the group's
 * segments), the incoming one that of the steady state at the group's depth D and outward
 * current U, U − 2√(g D); their boundary state has √(g d_b) = (u_out − U + 2√(g d_int) +
 * 2√(g D))/4. Without a measured level or velocity (no fluid near the outlet) the level is D's. */
static double absorbing_level(const struct sph_open_group *grp, double gnorm, double level,
                              double u_out) {
  const double d_int = level - grp->bed;
  if (!(d_int > 0.0) || !isfinite(u_out) || !(gnorm > 0.0)) return grp->bed + grp->depth;
  const double c =
      0.25 * (u_out - grp->current + 2.0 * sqrt(gnorm * d_int) + 2.0 * sqrt(gnorm * grp->depth));
  return grp->bed + (c > 0.0 ? c * c / gnorm : 0.0);
}

/* The wet fraction of an open point whose Shepard sum has fluid (docs/sph-solver.md §10): with
 * gravity, the local free surface is Δr/2 above the highest fluid particle of the sum (as the
 * initial free surface and the measured depth); a vertex is wet at or below it, a segment by the
 * part of its vertical extent below it (its vertices' heights along −g). Without gravity every
 * such point is wet. */
static double wet_fraction(const struct sph_system *s, int is_seg, const double zrange[2],
                           double ztop, const double *up) {
  if (up[0] == 0.0 && up[1] == 0.0 && up[2] == 0.0) return 1.0;
  const double level = ztop + 0.5 * s->dr;
  const double lo = zrange[0], hi = zrange[1];
  if (!is_seg) return lo <= level;
  if (hi - lo <= 1e-9 * s->dr) return level >= lo;
  return fmin(fmax((level - lo) / (hi - lo), 0.0), 1.0);
}

void sph_open_boundary_values(struct sph_open *op, struct sph_solver *sv, double t) {
  if (!op) return;
  struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT], *v = &s->part[SPH_KIND_VERTEX];
  const struct sph_kernel *kernel = &sv->kernel;
  const struct sph_nlist *fs = &sv->nb.list[SPH_KIND_SEGMENT], *vf = &sv->nb.vf;
  const int dim = s->dim, hydro = sv->cfg.vertex_hydro, ng = op->ngroups;
  const double *gravity = sv->cfg.gravity, nu = sv->cfg.nu;
  op->fail = 0;
  op->fail_msg[0] = '\0';
  memset(op->mdot, 0, v->n * sizeof *op->mdot);

  /* Measured free-surface levels (hydrostatic, depth: measured): the top fluid particle of the
   * group's Shepard sums below, plus Δr/2 (as the initial free surface). */
  double level[SPH_MAX_OPEN_GROUPS];
  for (int g = 0; g < ng; g++) level[g] = -INFINITY;
  const double *up = op->src[0].up;
  const int free_surface = up[0] != 0.0 || up[1] != 0.0 || up[2] != 0.0;

  /* Shepard sums, J(33–35): segments from the fluid → segment lists (which hold every fluid
   * particle within 2h of a centroid: the distance to the element is at most the distance to its
   * centroid), in fluid order; vertices from the vertex → fluid lists. */
  size_t ntot = 0;
  for (int g = 0; g < ng; g++) ntot += op->pts[g].npoints;
  struct shepard *sh = (struct shepard *)op->work;
  memset(sh, 0, ntot * sizeof *sh);
  for (size_t k = 0; k < ntot; k++) sh[k].ztop = -INFINITY;
  size_t base[SPH_MAX_OPEN_GROUPS + 1];
  base[0] = 0;
  for (int g = 0; g < ng; g++) base[g + 1] = base[g] + op->pts[g].npoints;
  for (size_t a = 0; a < f->n; a++)
    for (size_t q = fs->offset[a]; q < fs->offset[a + 1]; q++) {
      const size_t j = fs->index[q];
      const int g = op->seg_group[j];
      if (g < 0) continue;
      struct sph_pair pr;
      if (!sph_pair_eval(kernel, s, sg, j, f, a, &pr)) continue;
      const size_t k = (size_t)op->seg_point[j];
      shepard_add(&sh[base[g] + k], f, a, &pr, hydro, gravity, up, op->pts[g].normal[k]);
      if (sh[base[g] + k].ztop > level[g]) level[g] = sh[base[g] + k].ztop;
    }
  for (int g = 0; g < ng; g++) {
    const struct sph_open_points *pt = &op->pts[g];
    for (size_t k = pt->nseg; k < pt->npoints; k++) {
      const size_t iv = pt->index[k];
      for (size_t q = vf->offset[iv]; q < vf->offset[iv + 1]; q++) {
        struct sph_pair pr;
        const size_t b = vf->index[q];
        if (sph_pair_eval(kernel, s, v, iv, f, b, &pr))
          shepard_add(&sh[base[g] + k], f, b, &pr, hydro, gravity, up, pt->normal[k]);
      }
    }
  }

  for (int g = 0; g < ng; g++) {
    const struct sph_open_group *grp = &sv->cfg.open.group[g];
    const int measured = grp->depth_measured || grp->absorbing;
    level[g] = measured && isfinite(level[g]) ? level[g] + 0.5 * s->dr : NAN;
    if (grp->absorbing) {
      /* the mean Shepard outflow velocity over the group's segments that see fluid */
      const struct sph_open_points *pt = &op->pts[g];
      double su = 0.0, sm = 0.0;
      for (size_t k = 0; k < pt->nseg; k++) {
        const struct shepard *h = &sh[base[g] + k];
        if (!(h->alpha > 0.0)) continue;
        su -= pt->measure[k] * dot3(h->u, pt->normal[k]) / h->alpha;
        sm += pt->measure[k];
      }
      level[g] = absorbing_level(grp, op->src[g].g, level[g], sm > 0.0 ? su / sm : NAN);
    }
    op->stats[g].level = level[g];
  }

  /* wet fractions of every group first: a segment's flux goes to its wet vertices, which may
   * belong to another group */
  for (int g = 0; g < ng; g++) {
    struct sph_open_points *pt = &op->pts[g];
    for (size_t k = 0; k < pt->npoints; k++) {
      const struct shepard *h = &sh[base[g] + k];
      pt->wet[k] = h->alpha > 0.0 ? wet_fraction(s, k < pt->nseg, pt->zrange[k], h->ztop, up) : 0.0;
    }
  }

  for (int g = 0; g < ng; g++) {
    const struct sph_open_group *grp = &sv->cfg.open.group[g];
    struct sph_open_points *pt = &op->pts[g];
    size_t nwet = 0;
    for (size_t k = 0; k < pt->npoints; k++) {
      const struct sph_parts *pk = k < pt->nseg ? sg : v;
      const size_t i = pt->index[k];
      const double x[3] = {pk->x[0][i], pk->x[1][i], pk->x[2][i]};
      sph_open_source_eval(&op->src[g], t, x, pt->normal[k], level[g], &pt->value[k]);
      const struct shepard *h = &sh[base[g] + k];
      pt->alpha[k] = h->alpha;
      pt->slot[k] = (size_t)-1;
      if (!(pt->wet[k] > 0.0)) {
        pt->p_int[k] = NAN;
        for (int c = 0; c < 3; c++) pt->u_int[k][c] = NAN;
        continue;
      }
      /* with gravity (a free surface carries no tension) each particle's share is clipped at 0,
       * as in the reference implementation; without, the floor of the wall vertices: no suction
       * from the hydrostatic extrapolation (docs/sph-solver.md §4, §10) */
      pt->p_int[k] = free_surface ? h->p_pos / h->alpha
                                  : fmax(h->p / h->alpha, fmin(h->p_raw / h->alpha, 0.0));
      for (int c = 0; c < 3; c++) pt->u_int[k][c] = h->u[c] / h->alpha;
      struct rmn_boundary_input *in = &pt->in[nwet];
      for (int c = 0; c < 3; c++) {
        in->normal[c] = pt->normal[k][c];
        in->u[c] = pt->u_int[k][c];
      }
      in->rho = rmn_eos_density(&sv->eos, pt->p_int[k]);
      in->imposed = (enum rmn_imposed)grp->imposed;
      in->value = grp->imposed == RMN_IMPOSE_PRESSURE ? pt->value[k].p : pt->value[k].un;
      /* the inflow's tangential velocity in the solver's own frame of this normal */
      struct rmn_frame frame;
      double loc[3] = {0.0, 0.0, 0.0};
      if (rmn_frame_from_normal(dim, in->normal, &frame) == RMN_SUCCESS)
        rmn_frame_to_local(&frame, pt->value[k].u, loc);
      in->ut[0] = loc[1];
      in->ut[1] = loc[2];
      pt->slot[k] = nwet++;
    }
    pt->nwet = nwet;
    size_t first = 0;
    const int st = rmn_boundary_solve_batch(&sv->eos, &op->params[g], op->ws, dim, nwet, pt->in,
                                            pt->out, &first);
    if (st != RMN_SUCCESS && op->fail == 0) {
      size_t k = 0;
      while (k < pt->npoints && pt->slot[k] != first) k++;
      const int is_seg = k < pt->nseg;
      const struct sph_parts *pk = is_seg ? sg : v;
      const size_t i = pt->index[k];
      const struct rmn_boundary_input *in = &pt->in[first];
      char where[256], imp[256];
      if (is_seg)
        snprintf(where, sizeof where,
                 "segment id %lld (index %zu, element %ld of "
                 "geometry.walls[%d])",
                 (long long)pk->id[i], i, pt->element[k], grp->wall);
      else
        snprintf(where, sizeof where, "vertex id %lld (index %zu)", (long long)pk->id[i], i);
      snprintf(op->fail_msg, sizeof op->fail_msg,
               "open boundary '%s': %s at (%.9g, %.9g, %.9g), normal (%.6g, %.6g, %.6g), "
               "t = %.9g s: boundary Riemann problem failed: %s (%s); interior state rho = %.9g "
               "kg/m^3, p = %.9g Pa, u = (%.6g, %.6g, %.6g) m/s, u_n = %.6g m/s (Shepard sum "
               "%.3g); %s",
               grp->name, where, pk->x[0][i], pk->x[1][i], pk->x[2][i], in->normal[0],
               in->normal[1], in->normal[2], t, rmn_status_name(st), rmn_strerror(st), in->rho,
               pt->p_int[k], in->u[0], in->u[1], in->u[2], dot3(in->u, in->normal), pt->alpha[k],
               imposed_text(grp, &pt->value[k], imp, sizeof imp));
      op->fail = st;
    }
    /* Results into the store; dry or failed points keep their wall values. */
    struct sph_open_stats *stt = &op->stats[g];
    double m = 0.0, s_imp = 0.0, s_p = 0.0, s_un = 0.0, s_pi = 0.0, s_ui = 0.0, flux = 0.0;
    double mflux = 0.0;
    stt->nwave[0] = stt->nwave[1] = stt->nwave[2] = 0;
    stt->ndry = 0;
    for (size_t k = 0; k < pt->npoints; k++) {
      const int is_seg = k < pt->nseg;
      struct sph_parts *pk = is_seg ? sg : v;
      const size_t i = pt->index[k];
      pk->flags[i] &= (uint8_t)~SPH_FLAG_WET;
      if (pt->slot[k] == (size_t)-1) {
        stt->ndry += is_seg;
        continue;
      }
      const struct rmn_boundary_result *r = &pt->out[pt->slot[k]];
      if (r->status != RMN_SUCCESS) continue;
      pk->flags[i] |= SPH_FLAG_WET;
      pk->rho[i] = r->rho;
      pk->p[i] = r->p;

      for (int c = 0; c < 3; c++) pk->v[c][i] = c < dim ? r->u[c] : 0.0;
      sv->mu[is_seg ? SPH_KIND_SEGMENT : SPH_KIND_VERTEX][i] = nu * r->rho;
      if (!is_seg) continue;
      const double w = pt->measure[k] * pt->wet[k];
      stt->nwave[r->wave]++;
      m += w;
      s_imp += w * (grp->imposed == RMN_IMPOSE_PRESSURE ? pt->value[k].p : pt->value[k].un);
      s_p += w * r->p;
      s_un += w * r->un;
      s_pi += w * pt->p_int[k];
      s_ui += w * dot3(pt->u_int[k], pt->normal[k]);
      /* J(15): the mass flux ρ_s |s| (u_s − v_s)·n_s of the segment's wet part (fixed boundary:
       * v_s = 0), a d-th to each of its vertices that is not a corner, a dry vertex's share to
       * the wet ones (docs/sph-solver.md §10) */
      const double q = r->rho * w * r->un;
      const double qv = sph_open_share_flux(s, op, i, q, op->mdot);
      mflux += qv;
      flux += qv / r->rho;
    }
    stt->time = t;
    stt->imposed = m > 0.0 ? s_imp / m : NAN;
    stt->p = m > 0.0 ? s_p / m : NAN;
    stt->un = m > 0.0 ? s_un / m : NAN;
    stt->p_int = m > 0.0 ? s_pi / m : NAN;
    stt->un_int = m > 0.0 ? s_ui / m : NAN;
    stt->volume_flux = flux;
    stt->mass_flux = mflux;
  }
}

const char *const *sph_open_csv_columns(void) {
  static const char *const names[SPH_OPEN_CSV_COLUMNS] = {
      "time",        "imposed",   "p",       "un",           "p_interior",    "un_interior",
      "volume_flux", "mass_flux", "level",   "contact",      "expansion",     "shock",
      "dry",         "created",   "deleted", "mass_entered", "mass_released", "mass_withheld"};
  return names;
}

void sph_open_csv_row(const struct sph_open *op, int g, double time,
                      double row[SPH_OPEN_CSV_COLUMNS]) {
  const struct sph_open_stats *s = &op->stats[g];
  const double r[SPH_OPEN_CSV_COLUMNS] = {time,
                                          s->imposed,
                                          s->p,
                                          s->un,
                                          s->p_int,
                                          s->un_int,
                                          s->volume_flux,
                                          s->mass_flux,
                                          s->level,
                                          (double)s->nwave[RMN_WAVE_CONTACT],
                                          (double)s->nwave[RMN_WAVE_EXPANSION],
                                          (double)s->nwave[RMN_WAVE_SHOCK],
                                          (double)s->ndry,
                                          (double)op->created[g],
                                          (double)op->deleted[g],
                                          op->mass_entered[g],
                                          op->mass_released[g],
                                          op->mass_withheld[g]};
  memcpy(row, r, sizeof r);
}
