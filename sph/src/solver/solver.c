/*
 * The weakly-compressible USAW solver (docs/sph-solver.md): set-up, Tait EOS (riemann/), vertex
 * and segment values M(16–17), momentum M(14) with Grad^{γ,k} M(37) and Lap^γ J(8) with the wall
 * shear stress M(19–20), the volume-diffusion rate of M(84) (Ferrari M(49–50), η M(48), gravity
 * correction M(81), or the Brezzi-type term of J §II.C), the time-step limits, and the
 * predictor–corrector with the time-summation continuity M(13), J(10), M(84).
 */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "operators/pair.h"
#include "operators/pressure.h"
#include "sabre/common.h"
#include "sabre/sph_robin.h"
#include "sabre/sph_solver.h"
#include "solver/solver_internal.h"

static double *grow(double *p, size_t cap) { return cmn_realloc(p, (cap ? cap : 1) * sizeof *p); }

/* Grow the per-particle arrays to the store's and the lists' sizes. */
static void grow_arrays(struct sph_solver *sv) {
  for (int k = 0; k < SPH_NKINDS; k++) {
    size_t n = sv->sys.part[k].n;
    if (n <= sv->cap[k] && sv->mu[k]) continue;
    size_t cap = n + n / 4 + 8;
    sv->mu[k] = grow(sv->mu[k], cap);
    if (k == SPH_KIND_FLUID) {
      for (int c = 0; c < 3; c++) {
        sv->acc[c] = grow(sv->acc[c], cap);
        sv->x0[c] = grow(sv->x0[c], cap);
        sv->x_list[c] = grow(sv->x_list[c], cap);
        sv->v0[c] = grow(sv->v0[c], cap);
        sv->grad_gamma_n[c] = grow(sv->grad_gamma_n[c], cap);
      }
      sv->rho_n = grow(sv->rho_n, cap);
      sv->sum_w[0] = grow(sv->sum_w[0], cap);
      sv->sum_w[1] = grow(sv->sum_w[1], cap);
      sv->sum_wf[0] = grow(sv->sum_wf[0], cap);
      sv->sum_wf[1] = grow(sv->sum_wf[1], cap);
      sv->gamma_n = grow(sv->gamma_n, cap);
      sv->diff = grow(sv->diff, cap);
      sv->csound = grow(sv->csound, cap);
      sv->vol = grow(sv->vol, cap);
      sv->inv_rho2 = grow(sv->inv_rho2, cap);
      sv->impedance = grow(sv->impedance, cap);
    }
    sv->cap[k] = cap;
  }
}

void sph_solver_sync(struct sph_solver *sv) {
  grow_arrays(sv);
  sv->evaluated_step = -1;
  sv->gamma_current = 0;
  sv->lists_valid = 0;
  sv->sum_w_valid = 0;
}

static double skin(const struct sph_solver *sv) { return sv->cfg.skin_over_h * sv->sys.h; }

/* Accumulate the wall time since t0 in phase ph; returns the current time. */
static double timed(struct sph_solver *sv, enum sph_phase ph, double t0) {
  const double t1 = cmn_wall_time();
  sv->timing[ph] += t1 - t0;
  return t1;
}

/* Largest squared displacement of a fluid particle since the last build of the lists, at its
 * current position and, with with_x0, at its position x0 of the start of the step (the
 * time-summation continuity needs the pairs of both). Along periodic directions the minimum image
 * is taken: a particle wrapped by a period has not moved, and its rows stay right. */
static double moved2(const struct sph_solver *sv, int with_x0) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const struct sph_domain *dom = &sv->sys.domain;
  double period[3], half[3];
  for (int c = 0; c < 3; c++) {
    const int per = c < dom->dim && dom->periodic[c];
    period[c] = per ? dom->hi[c] - dom->lo[c] : 0.0;
    half[c] = per ? 0.5 * period[c] : INFINITY;
  }
  double m = 0.0;
  for (int set = 0; set <= with_x0; set++) {
    const double *const *x = set ? (const double *const *)sv->x0 : (const double *const *)f->x;
    for (size_t a = 0; a < f->n; a++) {
      double d2 = 0.0;
      for (int c = 0; c < 3; c++) {
        double d = x[c][a] - sv->x_list[c][a];
        d = d - period[c] * (d > half[c]) + period[c] * (d < -half[c]);
        d2 += d * d;
      }
      m = fmax(m, d2);
    }
  }
  return m;
}

/* Whether the lists must be rebuilt before evaluating at the current positions: always with
 * numerics.list_rebuild = every_step (the caller builds once per step), else when they are stale
 * or some particle has moved more than skin/2 since their build (then a pair now within 2h, or
 * within 2h at x0, was within 2h + skin at the build: the lists still hold it). */
static int lists_stale(const struct sph_solver *sv, int with_x0) {
  if (!sv->lists_valid || sv->cfg.list_rebuild == SPH_LISTS_EVERY_STEP) return 1;
  const double half = 0.5 * skin(sv);
  return moved2(sv, with_x0) > half * half;
}

/* The build positions and the count, after a build of the lists at the current positions. */
static void lists_built(struct sph_solver *sv) {
  grow_arrays(sv);
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  for (int c = 0; c < 3; c++) memcpy(sv->x_list[c], f->x[c], f->n * sizeof(double));
  sv->lists_valid = 1;
  sv->list_builds++;
}

/* Lists, γ and ∇γ_as at the current positions (the start of a step). */
static void neighbours(struct sph_solver *sv) {
  /* With the dynamic γ, γ is state: keep it through the lists' closed-form evaluation. */
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const int keep = sv->cfg.gamma_dynamic && sv->cap[SPH_KIND_FLUID] >= f->n && sv->gamma_n;
  if (keep) memcpy(sv->gamma_n, f->gamma, f->n * sizeof(double));
  double t0 = cmn_wall_time();
  if (!lists_stale(sv, 0)) {
    if (!sv->gamma_current) {
      sph_nbrs_gamma(&sv->nb, &sv->sys, &sv->kernel);
      timed(sv, SPH_PHASE_WALLS, t0);
    }
  } else if (sv->gamma_current) {
    sph_nbrs_rebuild_reuse(&sv->nb, &sv->sys, &sv->kernel, skin(sv));
    timed(sv, SPH_PHASE_LISTS, t0);
    lists_built(sv);
  } else {
    sph_nbrs_build(&sv->nb, &sv->sys, skin(sv));
    t0 = timed(sv, SPH_PHASE_LISTS, t0);
    lists_built(sv);
    sph_nbrs_gamma(&sv->nb, &sv->sys, &sv->kernel);
    timed(sv, SPH_PHASE_WALLS, t0);
  }
  sv->gamma_current = 1;
  grow_arrays(sv);
  if (keep) memcpy(f->gamma, sv->gamma_n, f->n * sizeof(double));
}

/* In the predictor and the corrector, before γ is refreshed: with list_rebuild = when_needed,
 * rebuild the lists at these positions if a particle (here or at x0) has moved more than skin/2
 * since their build. */
static void lists_check(struct sph_solver *sv) {
  if (sv->cfg.list_rebuild == SPH_LISTS_EVERY_STEP || !lists_stale(sv, 1)) return;
  const double t0 = cmn_wall_time();
  sph_nbrs_build(&sv->nb, &sv->sys, skin(sv));
  timed(sv, SPH_PHASE_LISTS, t0);
  lists_built(sv);
}

/* Dynamic γ, M(4), by the trapezoidal rule from the start of the step: the particles moved by
 * dt (v_old + v_new)/2, and ∇γ is the closed form at both ends. */
static void gamma_dynamic(struct sph_solver *sv, const double *const v_new[3], double dt) {
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const int dim = sv->sys.dim;
  for (size_t a = 0; a < f->n; a++) {
    const double v_old[3] = {sv->v0[0][a], sv->v0[1][a], sv->v0[2][a]};
    const double vn[3] = {v_new[0][a], v_new[1][a], v_new[2][a]};
    const double g_old[3] = {sv->grad_gamma_n[0][a], sv->grad_gamma_n[1][a],
                             sv->grad_gamma_n[2][a]};
    const double g_new[3] = {f->grad_gamma[0][a], f->grad_gamma[1][a], f->grad_gamma[2][a]};
    f->gamma[a] = sph_gamma_dynamic_step(sv->gamma_n[a], v_old, g_old, vn, g_new, dim, dt);
  }
}

static void refresh_gamma(struct sph_solver *sv) {
  const double t0 = cmn_wall_time();
  sph_nbrs_gamma(&sv->nb, &sv->sys, &sv->kernel);
  timed(sv, SPH_PHASE_WALLS, t0);
}

static double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* ------------------------------------------------------------------------------------------- */

/* The wall group of each vertex for the vertex values: the first group of cfg.vertex_groups that
 * names the wall (and element) of the vertex's first segment, else the default (−1). */
void sph_solver_vertex_groups(struct sph_solver *sv, const int *seg_wall, const long *seg_edge) {
  const struct sph_config *cfg = &sv->cfg;
  const struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX], *sg = &sv->sys.part[SPH_KIND_SEGMENT];
  if (v->n + 1 > sv->cap_vert_bc) {
    sv->vert_bc = cmn_realloc(sv->vert_bc, (v->n + 1) * sizeof *sv->vert_bc);
    sv->cap_vert_bc = v->n + 1;
  }
  for (size_t i = 0; i < v->n; i++) sv->vert_bc[i] = -2; /* not yet seen */
  for (size_t j = 0; j < sg->n; j++) {
    int group = -1;
    for (int g = 0; g < cfg->nvertex_groups && seg_wall && group < 0; g++) {
      const struct sph_vertex_bc *b = &cfg->vertex_groups[g];
      if (b->wall != seg_wall[j]) continue;
      int match = b->nedges == 0;
      for (int e = 0; e < b->nedges && !match; e++) match = seg_edge && b->edges[e] == seg_edge[j];
      if (match) group = g;
    }
    for (int k = 0; k < sv->sys.dim; k++) {
      size_t iv = sg->vertex[k][j];
      if (sv->vert_bc[iv] == -2) sv->vert_bc[iv] = group;
    }
  }
  for (size_t i = 0; i < v->n; i++)
    if (sv->vert_bc[i] == -2) sv->vert_bc[i] = -1;
}

static const struct sph_vertex_bc *vertex_bc(const struct sph_solver *sv, size_t iv) {
  const int g = sv->vert_bc && iv < sv->cap_vert_bc ? sv->vert_bc[iv] : -1;
  return g >= 0 ? &sv->cfg.vertex_groups[g] : &sv->cfg.vertex_bc;
}

/*
 * Order-m least-squares vertex pressure, M(64–74), with the constraint M(83) (tangential) or M(82),
 * over the vertex's fluid neighbours; μ3 gains μ2 ρ_v g·n_v with gravity_flux (∂p/∂n = ρ g·n), ρ_v
 * the Shepard mean density of the neighbours. With too_few = lower, an undetermined order-m fit is
 * redone at the order the distinct distances allow. Returns an SPH_ROBIN_* status; *m_used the
 * order of the last fit, *n_distinct the distinct distances found.
 */
static int robin_pressure(const struct sph_solver *sv, const struct sph_vertex_bc *bc, size_t iv,
                          double rho_v, double *pv, int *m_used, int *n_distinct) {
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID], *v = &s->part[SPH_KIND_VERTEX];
  const struct sph_nlist *nl = &sv->nb.vf;
  const double nv[3] = {v->normal[0][iv], v->normal[1][iv], v->normal[2][iv]};
  struct sph_robin_params prm;
  sph_robin_params_init(&prm, 2.0 * s->h);
  prm.m = bc->order;
  prm.mu1 = bc->mu[0];
  prm.mu2 = bc->mu[1];
  prm.mu3 = bc->mu[2];
  if (bc->gravity_flux) prm.mu3 += bc->mu[1] * rho_v * dot3(sv->cfg.gravity, nv);
  prm.hydro = bc->tangential;
  for (int c = 0; c < 3; c++) prm.gravity[c] = sv->cfg.gravity[c];
  struct sph_robin_ws ws; /* on this thread's stack: no allocation per step */
  int status;
  for (;;) {
    sph_robin_begin(&ws, &prm, s->dim, nv);
    for (size_t q = nl->offset[iv]; q < nl->offset[iv + 1]; q++) {
      size_t b = nl->index[q];
      struct sph_pair pr;
      if (!sph_pair_eval(&sv->kernel, s, v, iv, f, b, &pr)) continue;
      const double r_av[3] = {-pr.r[0], -pr.r[1], -pr.r[2]};
      sph_robin_add(&ws, r_av, f->p[b], f->mass[b] / f->rho[b] * pr.w, f->rho[b]);
    }
    status = sph_robin_finish(&ws, pv);
    if (status == SPH_ROBIN_ETOOFEW && bc->too_few == SPH_VTOOFEW_LOWER && ws.n_distinct >= 1 &&
        ws.n_distinct < prm.m) {
      prm.m = ws.n_distinct;
      continue;
    }
    break;
  }
  *m_used = prm.m;
  *n_distinct = ws.n_distinct;
  return status;
}

static int lone_particle(const struct sph_solver *sv, size_t a);

static void boundary_values_impl(struct sph_solver *sv) {
  struct sph_system *s = &sv->sys;
  struct sph_parts *f = &s->part[SPH_KIND_FLUID], *v = &s->part[SPH_KIND_VERTEX];
  struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT];
  const struct rmn_eos *eos = &sv->eos;
  const double nu = sv->cfg.nu, *g = sv->cfg.gravity;
  for (size_t a = 0; a < f->n; a++) {
    double p = rmn_eos_pressure(eos, f->rho[a]);
    if (p < 0.0 && sv->cfg.lone_ambient && lone_particle(sv, a)) p = 0.0; /* a droplet */
    s->part[SPH_KIND_FLUID].p[a] = p;
    sv->mu[SPH_KIND_FLUID][a] = nu * f->rho[a];
    if (sv->cfg.wall_impedance) sv->impedance[a] = f->rho[a] * rmn_eos_sound_speed(eos, f->rho[a]);
  }
  /* Shepard M(16–17) with the hydrostatic correction p_b + ρ_b g·(r_v − r_b) (full) or its part
   * tangential to the wall, M(83). */
  const struct sph_nlist *nl = &sv->nb.vf;
  const int hydro = sv->cfg.vertex_hydro;
  long fail = -1; /* the lowest failing vertex index: deterministic whatever the threads */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 64)
#endif
  for (size_t iv = 0; iv < v->n; iv++) {
    double alpha = 0.0, sum = 0.0, sum_raw = 0.0, sum_rho = 0.0;
    const double nv[3] = {v->normal[0][iv], v->normal[1][iv], v->normal[2][iv]};
    for (size_t q = nl->offset[iv]; q < nl->offset[iv + 1]; q++) {
      size_t b = nl->index[q];
      struct sph_pair pr;
      if (!sph_pair_eval(&sv->kernel, s, v, iv, f, b, &pr)) continue;
      double vw = f->mass[b] / f->rho[b] * pr.w;
      double pb = s->part[SPH_KIND_FLUID].p[b];
      if (hydro != SPH_VHYDRO_NONE) {
        double r[3] = {pr.r[0], pr.r[1], pr.r[2]}; /* r_v − r_b */
        if (hydro == SPH_VHYDRO_TANGENTIAL) {
          double rn = dot3(r, nv);
          for (int c = 0; c < 3; c++) r[c] -= rn * nv[c];
        }
        pb += f->rho[b] * dot3(g, r);
      }
      alpha += vw;
      sum_rho += vw * f->rho[b];
      sum += vw * pb;
      sum_raw += vw * s->part[SPH_KIND_FLUID].p[b];
    }
    double pv = alpha > 0.0 ? sum / alpha : 0.0;
    const struct sph_vertex_bc *bc = vertex_bc(sv, iv);
    if (bc->method == SPH_VVALUES_ROBIN && alpha > 0.0) {
      /* (No fluid within 2h: no fluid particle sees this vertex either; it keeps p_v = 0.) */
      int m_used, n_distinct;
      const int st = robin_pressure(sv, bc, iv, sum_rho / alpha, &pv, &m_used, &n_distinct);
      if (st != SPH_ROBIN_SUCCESS) {
#ifdef _OPENMP
#pragma omp critical(sph_vertex_fail)
#endif
        if (fail < 0 || (long)iv < fail) {
          fail = (long)iv;
          sv->vertex_fail_status = st;
          snprintf(sv->vertex_fail_msg, sizeof sv->vertex_fail_msg,
                   "vertex id %lld (index %zu) at (%.9g, %.9g, %.9g), normal (%.6g, %.6g, %.6g): "
                   "order-%d pressure fit M(74) failed: %s (%s; %d distinct fluid distances "
                   "along the normal for order %d)",
                   (long long)v->id[iv], iv, v->x[0][iv], v->x[1][iv], v->x[2][iv], nv[0], nv[1],
                   nv[2], m_used, sph_robin_status_name(st), sph_robin_strerror(st), n_distinct,
                   bc->order);
        }
        pv = sum_raw / alpha; /* keep the state finite; the step stops on vertex_fail */
      }
    }
    /* Above the free surface the hydrostatic extrapolation gives a negative pressure that the
     * fluid does not have (air): it would suck the fluid up the walls. The correction may not take
     * the value below min(plain Shepard value, 0). */
    if (alpha > 0.0) pv = fmax(pv, fmin(sum_raw / alpha, 0.0));
    double pmin = rmn_eos_min_pressure(eos);
    if (!(pv > 0.999 * pmin)) pv = 0.999 * pmin; /* keep ρ(p) defined */
    s->part[SPH_KIND_VERTEX].p[iv] = pv;
    v->rho[iv] = rmn_eos_density(eos, pv);
    sv->mu[SPH_KIND_VERTEX][iv] = nu * v->rho[iv];
  }
  sv->vertex_fail = fail;
  const int dim = s->dim;
  for (size_t j = 0; j < sg->n; j++) {
    double rho = 0.0, p = 0.0, vel[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < dim; k++) {
      size_t iv = sg->vertex[k][j];
      rho += v->rho[iv];
      p += s->part[SPH_KIND_VERTEX].p[iv];
      for (int c = 0; c < 3; c++) vel[c] += v->v[c][iv];
    }
    sg->rho[j] = rho / dim;
    s->part[SPH_KIND_SEGMENT].p[j] = p / dim;
    sv->mu[SPH_KIND_SEGMENT][j] = nu * sg->rho[j];
    for (int c = 0; c < 3; c++) sg->v[c][j] = vel[c] / dim;
  }
}

/* ------------------------------------------------------------------------------------------- */

/* One fluid pair's term of the volume-diffusion rate D_a = d(γ_a ρ_a)/dt of M(84) (Ferrari/η) or
 * of the Brezzi-type term (before its factor Λ), pr the pair's geometry (r_ab ≠ 0); cab_r_eta:
 * c_ab r_ab of diffusion_speed eta, 2 c0 Δr/η, and slope0 = ρ0/c0² (the same for every pair). */
static double diffusion_pair(const struct sph_solver *sv, size_t a, size_t b,
                             const struct sph_pair *pr, double cab_r_eta, double slope0) {
  const struct sph_config *cfg = &sv->cfg;
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const double gcorr = cfg->gravity_correction ? 1.0 : 0.0;
  const double rho_ref = cfg->rho0, rho_a = f->rho[a];
  const double g_r = gcorr * dot3(cfg->gravity, pr->r); /* g·r_ab */
  if (cfg->diffusion == SPH_DIFFUSION_FERRARI) {
    /* ϱ_ab = ρ_a − ρ_b − ρ0/c0² g·r_ab, M(81) (with g = −g e_z: the paper's form). */
    double slope = slope0; /* dρ/dp of M(81), ρ0/c0² */
    if (cfg->gravity_correction == 2) {
      const double rho_m = 0.5 * (rho_a + f->rho[b]), c_m = rmn_eos_sound_speed(&sv->eos, rho_m);
      slope = rho_m / (c_m * c_m);
    }
    const double varrho = rho_a - f->rho[b] - slope * g_r;
    /* m_b c_ab (r_ab/r_ab)·∇w_ab ϱ_ab/ρ_b = m_b c_ab r_ab · w'(r)/r · ϱ_ab/ρ_b */
    double cab_r; /* c_ab r_ab */
    if (cfg->diffusion_speed == SPH_DSPEED_MAX) {
      const double ca = sv->csound[a], cb = sv->csound[b];
      cab_r = (ca > cb ? ca : cb) * pr->dist; /* M(50) */
    } else {
      cab_r = cab_r_eta; /* r_ab c_ab = 2K, K = c0 Δr/η, M(52), M(48) */
    }
    return sv->vol[b] * cab_r * pr->dwdr_over_r * varrho;
  }
  /* Λ Δt Lap(p) with the hydrostatic part removed: Σ V_b 2 (p_ab − ρ0 g·r_ab) w'/r. */
  const double pab = f->p[a] - f->p[b] - rho_ref * g_r;
  return sv->vol[b] * 2.0 * pab * pr->dwdr_over_r;
}

/* The fluid pairs of a in one pass (their geometry evaluated once): the pressure gradient's sum
 * g, the viscous Laplacian's sum l (if viscous) and the diffusion rate (if any), in the list's
 * order and with the arithmetic of sph_op_grad_pressure and sph_op_lap, which then go on over the
 * vertices and segments (operators/pressure.h). */
static double fluid_pairs(const struct sph_solver *sv, size_t a, double fc, int viscous,
                          double g[3], double l[3]) {
  const struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const struct sph_nlist *nl = &sv->nb.list[SPH_KIND_FLUID];
  const double k = sv->cfg.grad_k, rho_a = f->rho[a], pa = f->p[a];
  const int k1 = k == 1.0;
  const double qa = (pa - fc) / rho_a; /* the pairs' p_a part for k = 1 */
  const double *mu = sv->mu[SPH_KIND_FLUID], mu_a = mu[a];
  const int diffusion = sv->cfg.diffusion != SPH_DIFFUSION_NONE;
  const double cab_r_eta = 2.0 * (sv->cfg.c0 * s->dr / sv->cfg.eta);
  const double slope0 = sv->cfg.rho0 / (sv->cfg.c0 * sv->cfg.c0);
  double dsum = 0.0;
  for (int c = 0; c < 3; c++) g[c] = l[c] = 0.0;
  for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
    const size_t b = nl->index[q];
    struct sph_pair pr;
    if (!sph_pair_eval(&sv->kernel, s, f, a, f, b, &pr)) continue;
    double t;
    if (k1) { /* k = 1 without a division: vb × sum = m_b (ρ_a (f_b − fc)/ρ_b² + (f_a − fc)/ρ_a) */
      t = sph_pair_pressure_k1(f->mass[b], rho_a, sv->inv_rho2[b], f->p[b] - fc, qa) *
          pr.dwdr_over_r;
    } else {
      const double ratio = sph_rho_ratio_k(rho_a, f->rho[b], k);
      double sum = ratio * f->p[b] + pa / ratio;
      if (fc != 0.0) sum -= fc * (ratio + 1.0 / ratio);
      t = sv->vol[b] * sum * pr.dwdr_over_r;
    }
    for (int c = 0; c < 3; c++) g[c] += t * pr.r[c];
    if (pr.dist == 0.0) continue;
    if (viscous) {
      const double bsum = mu_a + mu[b];
      const double bbar = bsum > 0.0 ? 2.0 * mu_a * mu[b] / bsum : 0.0; /* J(9) */
      const double tl = sv->vol[b] * 2.0 * bbar * pr.dwdr_over_r;
      for (int c = 0; c < 3; c++) l[c] += tl * (f->v[c][a] - f->v[c][b]);
    }
    if (diffusion) dsum += diffusion_pair(sv, a, b, &pr, cab_r_eta, slope0);
  }
  /* The Brezzi-type term takes its time scale Δt in continuity(). */
  if (sv->cfg.diffusion == SPH_DIFFUSION_BREZZI) dsum *= sv->cfg.brezzi_lambda;
  return dsum;
}

static void forces_impl(struct sph_solver *sv) {
  struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const int viscous = sv->cfg.nu > 0.0;
  /* the wall shear stress per F–S pair, M(19–20), computed in the viscous term */
  const struct sph_wall_shear shear = {sv->mu[SPH_KIND_FLUID], sv->mu[SPH_KIND_SEGMENT],
                                       0.5 * s->dr};
  const struct sph_op op = {s, &sv->kernel, &sv->nb, sv->cfg.no_pull_normal};
  const double *pk[SPH_NKINDS] = {s->part[0].p, s->part[1].p, s->part[2].p};
  const double *muk[SPH_NKINDS] = {sv->mu[0], sv->mu[1], sv->mu[2]};
  const double *vel[SPH_NKINDS][3];
  for (int k = 0; k < SPH_NKINDS; k++)
    for (int c = 0; c < 3; c++) vel[k][c] = s->part[k].v[c];
  /* the inflow vertices' entered mass as a layer in front of them, with M(37) (§10) */
  const int use_layer = sv->open && !sv->open_off && !sv->cfg.open_gradient_difference;
  if (use_layer) sph_open_layer(sv->open, sv);
    /* the sound speeds of the diffusion's pairs and the volumes m/ρ, once per particle (the
     * volume is the quotient the pair loop formed per pair: the same bits) */
#ifdef _OPENMP
#pragma omp parallel for schedule(static)
#endif
  for (size_t a = 0; a < f->n; a++) {
    sv->csound[a] = rmn_eos_sound_speed(&sv->eos, f->rho[a]);
    sv->vol[a] = f->mass[a] / f->rho[a];
    sv->inv_rho2[a] = sph_inv_rho2(f->rho[a]);
  }
  const struct sph_vertex_layer layer = {
      use_layer ? sv->open->layer_vol : NULL,
      use_layer ? (const double *const *)sv->open->layer_x : NULL};
  const struct sph_wall_impedance imp = {
      sv->impedance,
      sv->cfg.wall_impedance == SPH_IMPEDANCE_CONTACT ? sv->cfg.wall_impedance_reach * s->dr : 0.0};
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 64)
#endif
  for (size_t a = 0; a < f->n; a++) {
    if (sph_open_exit_segment(sv->open, sv, a) >= 0) { /* leaving: gravity only (§10) */
      for (int c = 0; c < 3; c++) sv->acc[c][a] = sv->cfg.gravity[c];
      sv->diff[a] = 0.0;
      continue;
    }
    double gp[3], lap[3] = {0.0, 0.0, 0.0}, gf[3], lf[3];
    const int diffo = sv->cfg.open_gradient_difference;
    const double fc = diffo ? sph_op_open_share(&op, a) * pk[SPH_KIND_FLUID][a] : 0.0;
    sv->diff[a] = fluid_pairs(sv, a, fc, viscous, gf, lf);
    /* no wall pulls an approaching particle; with numerics.wall_impedance, harder push on it */
    sph_op_grad_pressure_walls(&op, sv->cfg.grad_k, pk, a, sv->cfg.wall_impedance ? &imp : NULL,
                               diffo, use_layer ? &layer : NULL, gf, gp);
    if (viscous) sph_op_lap_walls(&op, muk, (const double *const(*)[3])vel, &shear, a, lf, lap);
    const double inv_rho = 1.0 / f->rho[a];
    for (int c = 0; c < 3; c++) sv->acc[c][a] = (lap[c] - gp[c]) * inv_rho + sv->cfg.gravity[c];
  }
}

/* ------------------------------------------------------------------------------------------- */

double sph_solver_timestep(const struct sph_solver *sv) {
  const struct sph_config *cfg = &sv->cfg;
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const double h = sv->sys.h;
  double smax = 0.0, vmax = 0.0, amax = 0.0, gmax = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    double v2 = 0.0, a2 = 0.0, vg = 0.0;
    for (int c = 0; c < 3; c++) {
      v2 += f->v[c][a] * f->v[c][a];
      a2 += sv->acc[c][a] * sv->acc[c][a];
      vg += f->v[c][a] * f->grad_gamma[c][a];
    }
    double speed = sqrt(v2);
    double sig = rmn_eos_sound_speed(&sv->eos, f->rho[a]) + speed;
    smax = fmax(smax, sig);
    vmax = fmax(vmax, speed);
    amax = fmax(amax, sqrt(a2));
    gmax = fmax(gmax, fabs(vg));
  }
  double dt = cfg->dt_max;
  if (smax > 0.0) dt = fmin(dt, cfg->cfl * h / smax);
  if (cfg->nu > 0.0) dt = fmin(dt, cfg->viscous_factor * h * h / cfg->nu);
  if (amax > 0.0) dt = fmin(dt, cfg->force_factor * sqrt(h / amax));
  if (gmax > 0.0) dt = fmin(dt, cfg->gamma_factor / gmax);
  /* Neighbour skin: |v| dt + 2|a| dt² ≤ skin/2 (the corrector displacement, with margin). */
  const double half = 0.5 * cfg->skin_over_h * h, a2 = 2.0 * amax;
  double dt_skin = a2 > 0.0 ? (-vmax + sqrt(vmax * vmax + 4.0 * a2 * half)) / (2.0 * a2)
                            : (vmax > 0.0 ? half / vmax : INFINITY);
  return fmin(dt, dt_skin);
}

/* ------------------------------------------------------------------------------------------- */

/* start + Σ_b m_b w_ab of fluid particle a over its neighbours of one kind (fluid or vertex), at
 * the positions x of the fluid (x0 or the store's) and the vertices' own; pairs beyond the support
 * add +0. The sum over P = F ∪ V is kernel_sum(VERTEX, kernel_sum(FLUID, 0)): the vertex part
 * goes on from the fluid part, so a fluid part kept from earlier gives the same bits. */
static double kernel_sum(const struct sph_solver *sv, size_t a, const double *const x[3], int kind,
                         double start) {
  const struct sph_system *s = &sv->sys;
  const struct sph_kernel *k = &sv->kernel;
  const double support = sph_kernel_support(k), support2 = support * support;
  const double xa[3] = {x[0][a], x[1][a], x[2][a]};
  double sum = start;
  const struct sph_parts *pb = &s->part[kind];
  const struct sph_nlist *nl = &sv->nb.list[kind];
  const double *const *xk = kind == SPH_KIND_FLUID ? x : (const double *const *)pb->x;
  for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
    const size_t b = nl->index[q];
    const double xb[3] = {xk[0][b], xk[1][b], xk[2][b]};
    double d[3];
    sph_domain_delta(&s->domain, xb, xa, d);
    const double r2 = dot3(d, d);
    if (r2 >= support2) continue; /* the square root only within the support */
    sum += pb->mass[b] * sph_kernel_w_inline(k, sqrt(r2));
  }
  return sum;
}

/* The fluid fraction of fluid particle a's kernel, φ_a = Σ_b m_b w_ab / (ρ0 γ_a) over the fluid
 * particles b, a's own m_a w(0) included (the lists leave a out): about 1 inside the fluid, 0.69 in
 * the top row under a flat free surface, m_a w(0)/ρ0 for a particle alone (0.14 in 2D with the
 * Wendland kernel at h = 2Δr; numerics.lone_particle). */
static double fluid_fraction(const struct sph_solver *sv, size_t a) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const double self = f->mass[a] * sph_kernel_w_inline(&sv->kernel, 0.0);
  const double sum = kernel_sum(sv, a, (const double *const *)f->x, SPH_KIND_FLUID, self);
  return sum / (sv->cfg.rho0 * f->gamma[a]);
}

/* 1 for a droplet: fluid particle a's kernel holds less fluid than numerics.lone_fraction. */
static int lone_particle(const struct sph_solver *sv, size_t a) {
  return fluid_fraction(sv, a) < sv->cfg.lone_fraction;
}

double sph_solver_kernel_sum(const struct sph_solver *sv, size_t a) {
  const double *const *x = (const double *const *)sv->sys.part[SPH_KIND_FLUID].x;
  return kernel_sum(sv, a, x, SPH_KIND_VERTEX, kernel_sum(sv, a, x, SPH_KIND_FLUID, 0.0));
}

/* γ_a ρ_a = γ^n ρ^n + Σ_{b∈P} m_b w_ab − Σ_{b∈P} m_b w_ab^n + fac · D, J(10), M(84): positions now
 * vs x0. The sums at x0 (sv->sum_w[0]) are formed in the predictor and kept for the corrector;
 * without open boundaries (constant masses) they are the previous corrector's sums at the same
 * positions (sv->sum_w[1], swapped in at the end of the step), so that a step forms one sum per
 * stage. With open boundaries the vertex masses change between steps and only the fluid part is
 * carried over (sv->sum_wf), the vertex part formed again on top of it. The continuity of the
 * corrector keeps its sums in sum_w[1] and sum_wf[1]; it returns 1 if some particle was leaving
 * (its sums not formed: nothing can be carried over). */
static int continuity_impl(struct sph_solver *sv, double fac, int corrector) {
  struct sph_system *s = &sv->sys;
  struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  const double scale = fac * (sv->cfg.diffusion == SPH_DIFFUSION_BREZZI ? sv->dt : 1.0);
  const int fluid0 = sv->sum_w_valid, need0 = !corrector && !(fluid0 && sv->open == NULL);
  double *sum0 = sv->sum_w[0], *sum1 = sv->sum_w[1], *sumf0 = sv->sum_wf[0], *sumf1 = sv->sum_wf[1];
  const double *const *xnow = (const double *const *)f->x;
  const double *const *xold = (const double *const *)sv->x0;
  int leaving = 0;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 64) reduction(| : leaving)
#endif
  for (size_t a = 0; a < f->n; a++) {
    if (need0) {
      const double sf = fluid0 ? sumf0[a] : kernel_sum(sv, a, xold, SPH_KIND_FLUID, 0.0);
      sum0[a] = kernel_sum(sv, a, xold, SPH_KIND_VERTEX, sf);
    }
    if (sph_open_exit_segment(sv->open, sv, a) >= 0) { /* leaving: density kept (§10) */
      f->rho[a] = sv->rho_n[a];
      if (corrector) sum1[a] = sumf1[a] = 0.0;
      leaving = 1;
      continue;
    }
    const double nowf = kernel_sum(sv, a, xnow, SPH_KIND_FLUID, 0.0);
    const double now = kernel_sum(sv, a, xnow, SPH_KIND_VERTEX, nowf);
    if (corrector) {
      sum1[a] = now;
      sumf1[a] = nowf;
    }
    const double xa0[3] = {sv->x0[0][a], sv->x0[1][a], sv->x0[2][a]};
    double dsum = now - sum0[a];
    /* Open boundaries: the i/o terms of J(11) (docs/sph-solver.md §10), 0 without open groups. */
    dsum += sph_open_continuity_terms(sv->open, sv, a, xa0, sv->rho_n[a], fac);
    f->rho[a] = (sv->gamma_n[a] * sv->rho_n[a] + dsum + scale * sv->diff[a]) / f->gamma[a];
  }
  return leaving;
}

static void wrap(struct sph_solver *sv) {
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const struct sph_domain *d = &sv->sys.domain;
  for (int c = 0; c < d->dim; c++) {
    if (!d->periodic[c]) continue;
    const double lo = d->lo[c], len = d->hi[c] - d->lo[c];
    for (size_t a = 0; a < f->n; a++) {
      double x = f->x[c][a];
      if (x < lo)
        x += len;
      else if (x >= lo + len)
        x -= len;
      f->x[c][a] = x;
    }
  }
}

static int check_state(struct sph_solver *sv, char *msg, size_t msglen) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const double lo = sv->cfg.density_band[0], hi = sv->cfg.density_band[1];
  const double rho_ref = sv->cfg.rho0;
  long step = sv->step + 1;
  /* The lowest failing index is named, and how many fail: a whole lattice row failing at once
   * (a 1D flow) is otherwise easily read as a defect at the particle named, which is merely the
   * first of its row in index order. Every particle behind a wall counts (nb.behind). */
  size_t nbad = 0, first = 0;
  const char *first_what = NULL;
  for (size_t a = 0; a < f->n; a++) {
    int bad = !isfinite(f->rho[a]);
    for (int c = 0; c < 3; c++) bad |= !isfinite(f->x[c][a]) || !isfinite(f->v[c][a]);
    const char *what = bad ? "a non-finite value" : NULL;
    double r = f->rho[a] / rho_ref;
    if (!what && !(r >= lo && r <= hi) &&
        !(r > 0.0 && r < lo && sv->cfg.lone_ambient && lone_particle(sv, a)))
      what = "a density outside numerics.density_band";
    if (!what && sv->nb.behind[a]) what = "left the fluid domain through a wall";
    if (what && nbad++ == 0) {
      first = a;
      first_what = what;
    }
  }
  if (nbad == 0) return 0;
  const size_t a = first;
  snprintf(msg, msglen,
           "step %ld, t = %.9g s: fluid particle id %lld (index %zu) at (%.9g, %.9g, %.9g): "
           "%s (rho/rho0 = %.9g, v = (%.6g, %.6g, %.6g)); %zu of %zu fluid particles fail these "
           "checks, the one with the lowest index is named",
           step, sv->time, (long long)f->id[a], a, f->x[0][a], f->x[1][a], f->x[2][a], first_what,
           f->rho[a] / rho_ref, f->v[0][a], f->v[1][a], f->v[2][a], nbad, f->n);
  return -1;
}

/* The timed phases (sv->timing). */
void sph_solver_boundary_values(struct sph_solver *sv) {
  const double t0 = cmn_wall_time();
  sph_open_restore_walls(sv->open, sv); /* open vertices: their wall velocity for the wall pass */
  boundary_values_impl(sv);
  /* Open boundaries: the Riemann solve of J §III replaces the wall values of open segments and
   * vertices (sabre/sph_open.h); not during the repacking, which needs walls at uniform pressure.
   */
  if (!sv->open_off) sph_open_boundary_values(sv->open, sv, sv->stage_time);
  timed(sv, SPH_PHASE_VERTEX, t0);
}

void sph_solver_forces(struct sph_solver *sv) {
  const double t0 = cmn_wall_time();
  forces_impl(sv);
  timed(sv, SPH_PHASE_FORCES, t0);
}

static int continuity(struct sph_solver *sv, double fac, int corrector) {
  const double t0 = cmn_wall_time();
  const int leaving = continuity_impl(sv, fac, corrector);
  timed(sv, SPH_PHASE_CONTINUITY, t0);
  return leaving;
}

void sph_solver_evaluate(struct sph_solver *sv) {
  sv->stage_time = sv->time;
  neighbours(sv);
  sph_solver_boundary_values(sv);
  sph_solver_forces(sv);
  sv->evaluated_step = sv->step;
}

/* Kernel completeness below which a particle is on a free surface (the top row has about 0.55;
 * holes next to walls in a closed tank stay above 0.8). */
#define SPH_REPACK_SURFACE 0.75

/* Kernel completeness Σ_{b∈P} V_b w_ab / γ_a of fluid particle a (1 inside the fluid and next to
 * walls, up to the quadrature error; about 1/2 on a free surface). */
static double completeness(const struct sph_solver *sv, size_t a) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  double sum = f->mass[a] / f->rho[a] * sph_kernel_w_inline(&sv->kernel, 0.0);
  for (int kind = SPH_KIND_FLUID; kind <= SPH_KIND_VERTEX; kind++) {
    const struct sph_parts *pb = &sv->sys.part[kind];
    const struct sph_nlist *nl = &sv->nb.list[kind];
    for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
      struct sph_pair pr;
      const size_t b = nl->index[q];
      if (sph_pair_eval(&sv->kernel, &sv->sys, f, a, pb, b, &pr))
        sum += pb->mass[b] / pb->rho[b] * pr.w;
    }
  }
  return sum / f->gamma[a];
}

int sph_solver_repack(struct sph_solver *sv, long steps, char *msg, size_t msglen) {
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const size_t n = f->n;
  const double h = sv->sys.h;
  const double rho_r = (1.0 + 1e-6) * sv->cfg.rho0, vol = pow(sv->sys.dr, sv->sys.dim);
  double gravity[3];
  memcpy(gravity, sv->cfg.gravity, sizeof gravity);
  for (int c = 0; c < 3; c++) sv->cfg.gravity[c] = 0.0;
  sv->open_off = 1; /* open segments are walls at the repacking's uniform pressure */
  /* The repacking moves towards zero defect at rest: no term that depends on the pseudo-velocities
   * (viscosity, the wall impedance), whose forces would balance the defect's while the particles
   * still move and end it elsewhere. */
  const double nu = sv->cfg.nu;
  const int impedance = sv->cfg.wall_impedance;
  sv->cfg.nu = 0.0;
  sv->cfg.wall_impedance = SPH_IMPEDANCE_NONE;
  for (size_t a = 0; a < n; a++) {
    f->rho[a] = rho_r;
    f->mass[a] = rho_r * vol;
    for (int c = 0; c < 3; c++) f->v[c][a] = 0.0;
  }
  /* The vertices keep their volumes m_v/ρ_v of the initial state at the repacking's density. */
  struct sph_parts *vx = &sv->sys.part[SPH_KIND_VERTEX];
  double *mass_v = cmn_malloc((vx->n + 1) * sizeof *mass_v);
  for (size_t i = 0; i < vx->n; i++) {
    mass_v[i] = vx->mass[i];
    vx->mass[i] *= rho_r / vx->rho[i];
  }
  /* The lid: particles on a free surface and their neighbours within 2h stay put. */
  sv->gamma_current = 0;
  sph_solver_evaluate(sv);
  unsigned char *fixed = cmn_calloc(n + 1, 1);
  for (size_t a = 0; a < n; a++) fixed[a] = completeness(sv, a) < SPH_REPACK_SURFACE;
  const struct sph_nlist *nl = &sv->nb.list[SPH_KIND_FLUID];
  for (size_t a = 0; a < n; a++) {
    for (size_t q = nl->offset[a]; q < nl->offset[a + 1] && fixed[a] == 0; q++) {
      struct sph_pair pr;
      const size_t b = nl->index[q];
      if (fixed[b] == 1 && sph_pair_eval(&sv->kernel, &sv->sys, f, a, f, b, &pr)) fixed[a] = 2;
    }
  }
  sv->repack_fixed = 0;
  for (size_t a = 0; a < n; a++) sv->repack_fixed += fixed[a] != 0;
  /* The start perturbed: on the lattice the defect's potential has a symmetric critical point that
   * FIRE leaves slowly and not always towards the deepest minimum (docs/sph-solver.md §8). */
  const double eps = sv->cfg.repack_perturbation * sv->sys.dr;
  if (eps > 0.0) {
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (rng == NULL) cmn_error("repacking: out of memory for the random generator");
    for (size_t a = 0; a < n; a++)
      for (int c = 0; c < sv->sys.dim; c++) {
        const double u = gsl_rng_uniform(rng);
        if (!fixed[a]) f->x[c][a] += eps * (2.0 * u - 1.0);
      }
    gsl_rng_free(rng);
    wrap(sv);
    sv->gamma_current = 0;
    sph_solver_evaluate(sv);
  }
  const double p_r = rmn_eos_pressure(&sv->eos, rho_r);
  const double v_ref = sqrt(2.0 * p_r / rho_r);
  /* FIRE (Bitzek et al. 2006, Phys. Rev. Lett. 97:170201) with its usual constants: the velocity
   * is turned towards the force, the step grows while the power F·v stays positive, and the
   * motion stops and restarts slower when it turns negative. */
  const int fire_nmin = 5;
  const double fire_inc = 1.1, fire_dec = 0.5, fire_alpha0 = 0.1, fire_falpha = 0.99;
  double dt = 0.0, dt_max = 0.0, alpha = fire_alpha0;
  int npos = 0;
  /* FIRE's residual is not monotone (each restart loses some of the way): the configuration of
   * least residual met is the one kept, so that more steps never end worse and the result does
   * not hang on where the last restart fell. */
  double best = INFINITY, *xbest[3];
  for (int c = 0; c < 3; c++) xbest[c] = cmn_malloc((n + 1) * sizeof *xbest[c]);
  struct cmn_progress prog;
  cmn_progress_start(&prog, 0.0, (double)steps);
  for (long it = 0;; it++) {
    double amax = 0.0, power = 0.0, fnorm2 = 0.0, vnorm2 = 0.0;
    for (size_t a = 0; a < n; a++) {
      if (fixed[a])
        for (int c = 0; c < 3; c++) sv->acc[c][a] = f->v[c][a] = 0.0;
      double a2 = 0.0;
      for (int c = 0; c < 3; c++) {
        a2 += sv->acc[c][a] * sv->acc[c][a];
        vnorm2 += f->v[c][a] * f->v[c][a];
        power += sv->acc[c][a] * f->v[c][a];
      }
      fnorm2 += a2;
      amax = fmax(amax, sqrt(a2));
    }
    /* Residual in units of the defect: max |Σ_{b∈P} V_b ∇w_ab − ∇γ_a| h (a = −2 p_r/ρ D_a). */
    const double residual = amax * h / (2.0 * p_r / rho_r);
    if (it == 0) {
      sv->repack_residual[0] = residual;
      dt = fmin(sv->cfg.force_factor * sqrt(h / amax), sv->cfg.cfl * h / v_ref);
      dt_max = 10.0 * dt;
    }
    sv->repack_residual[1] = residual;
    if (residual < best) {
      best = residual;
      for (int c = 0; c < 3; c++) memcpy(xbest[c], f->x[c], n * sizeof(double));
    }
    if (it == steps || !(amax > 0.0)) break;
    cmn_progress_task(&prog, (double)it, 0,
                      "repacking: step %ld of %ld  largest defect %.3g (least %.3g)", it, steps,
                      residual, best);
    const double mix = sqrt(vnorm2 / fnorm2);
    if (power > 0.0) {
      for (int c = 0; c < 3; c++)
        for (size_t a = 0; a < n; a++)
          f->v[c][a] = (1.0 - alpha) * f->v[c][a] + alpha * mix * sv->acc[c][a];
      if (++npos > fire_nmin) {
        dt = fmin(dt * fire_inc, dt_max);
        alpha *= fire_falpha;
      }
    } else {
      npos = 0;
      dt *= fire_dec;
      alpha = fire_alpha0;
      for (int c = 0; c < 3; c++)
        for (size_t a = 0; a < n; a++) f->v[c][a] = 0.0;
    }
    double vmax = 0.0;
    for (size_t a = 0; a < n; a++) {
      double v2 = 0.0;
      for (int c = 0; c < 3; c++) {
        f->v[c][a] += dt * sv->acc[c][a];
        v2 += f->v[c][a] * f->v[c][a];
      }
      vmax = fmax(vmax, sqrt(v2));
    }
    /* At most h/10 of displacement per step. */
    const double step = vmax > 0.0 ? fmin(dt, 0.1 * h / vmax) : dt;
    for (int c = 0; c < 3; c++)
      for (size_t a = 0; a < n; a++) f->x[c][a] += step * f->v[c][a];
    wrap(sv);
    sv->gamma_current = 0;
    sph_solver_evaluate(sv);
  }
  if (sv->repack_residual[1] > best) { /* back to the best configuration met */
    for (int c = 0; c < 3; c++) memcpy(f->x[c], xbest[c], n * sizeof(double));
    sv->repack_residual[1] = best;
    sv->gamma_current = 0;
    sph_solver_evaluate(sv);
  }
  for (int c = 0; c < 3; c++) free(xbest[c]);
  free(fixed);
  for (size_t i = 0; i < vx->n; i++) vx->mass[i] = mass_v[i];
  free(mass_v);
  memcpy(sv->cfg.gravity, gravity, sizeof gravity);
  sv->cfg.nu = nu;
  sv->cfg.wall_impedance = impedance;
  sv->open_off = 0;
  for (int c = 0; c < 3; c++)
    for (size_t a = 0; a < n; a++) f->v[c][a] = 0.0;
  size_t behind = 0, first = 0;
  for (size_t a = 0; a < n; a++)
    if (sv->nb.behind[a] && behind++ == 0) first = a;
  sph_solver_sync(sv);
  if (behind == 0) return 0;
  snprintf(msg, msglen,
           "repacking: %zu fluid particles left the fluid domain through a wall, the first "
           "(index %zu) at (%.9g, %.9g, %.9g); check that the fluid regions lie inside the walls, "
           "or set fewer repack.steps",
           behind, first, f->x[0][first], f->x[1][first], f->x[2][first]);
  return -1;
}

/* Stop the step when a vertex value could not be computed (docs/sph-robin.md §5). */
static int vertex_failed(const struct sph_solver *sv, char *msg, size_t msglen) {
  if (sv->open && sv->open->fail && !sv->open_off) { /* a failed open-boundary solve */
    snprintf(msg, msglen, "step %ld, t = %.9g s: %s", sv->step + 1, sv->time, sv->open->fail_msg);
    return -1;
  }
  if (sv->vertex_fail < 0) return 0;
  snprintf(msg, msglen, "step %ld, t = %.9g s: %s", sv->step + 1, sv->time, sv->vertex_fail_msg);
  return -1;
}

/* Uniform driving acceleration F n_A of the imposed flux, added to the momentum equation M(14). */
static void add_flux_force(struct sph_solver *sv) {
  if (sv->cfg.flux_method == SPH_FLUXSEL_OFF) return;
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  for (int c = 0; c < sv->sys.dim; c++) {
    const double fc = sv->flux_force * sv->cfg.flux_normal[c];
    for (size_t a = 0; a < f->n; a++) sv->acc[c][a] += fc;
  }
}

double sph_solver_flux_measure(const struct sph_solver *sv) {
  const struct sph_config *cfg = &sv->cfg;
  struct sph_flux_slice sl;
  for (int c = 0; c < 3; c++) {
    sl.point[c] = cfg->flux_point[c];
    sl.normal[c] = cfg->flux_normal[c];
  }
  sl.width = cfg->flux_width;
  sl.area = cfg->flux_area;
  double q, vt;
  if (sph_flux_measure_parts(sv->sys.dim, &sl, &sv->sys.domain, &sv->sys.part[SPH_KIND_FLUID], &q,
                             &vt) != 0)
    cmn_error("imposed flux: invalid measuring slice (normal, width %g m, area %g)", sl.width,
              sl.area);
  return vt;
}

static int step_impl(struct sph_solver *sv, double dt_limit, char *msg, size_t msglen);

/*
 * numerics.wall_vertex_mass: density (docs/sph-solver.md §4, "Flow along a wall", items 2 and 5):
 * at the start of the step every wall vertex (not open: those carry the open boundary's mass,
 * §10) takes the mass m_v = V_v ρ_v of its wall layer at the density of its last evaluation, so
 * that the layer compresses with the fluid next to it, and the change enters the time summation
 * of §3 as a change of state n: γ_a ρ_a^n gains Σ_v Δm_v w(r_av) (the continuity then goes on
 * from that ρ^n with the new masses). Sums over the fluid → vertex lists, one fluid particle per
 * iteration (the same bits whatever the threads); the carried sums of §3 are formed afresh.
 */
static void wall_vertex_masses(struct sph_solver *sv) {
  struct sph_system *s = &sv->sys;
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  struct sph_parts *v = &s->part[SPH_KIND_VERTEX];
  if (v->n + 1 > sv->cap_vertex_dm) {
    sv->vertex_dm = cmn_realloc(sv->vertex_dm, (v->n + 1) * sizeof *sv->vertex_dm);
    sv->cap_vertex_dm = v->n + 1;
  }
  double *dm = sv->vertex_dm;
  for (size_t i = 0; i < v->n; i++) {
    dm[i] = 0.0;
    if (v->flags[i] & SPH_FLAG_OPEN) continue;
    const double m = v->volume[i] * v->rho[i];
    dm[i] = m - v->mass[i];
    v->mass[i] = m;
  }
  const struct sph_nlist *nl = &sv->nb.list[SPH_KIND_VERTEX];
  const size_t n = f->n;
#ifdef _OPENMP
#pragma omp parallel for schedule(static)
#endif
  for (size_t a = 0; a < n; a++) {
    double sum = 0.0;
    for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
      const size_t b = nl->index[q];
      struct sph_pair pr;
      if (dm[b] != 0.0 && sph_pair_eval(&sv->kernel, s, f, a, v, b, &pr)) sum += dm[b] * pr.w;
    }
    sv->rho_n[a] += sum / sv->gamma_n[a];
  }
  sv->sum_w_valid = 0;
}

int sph_solver_step(struct sph_solver *sv, double dt_limit, char *msg, size_t msglen) {
  const double t0 = cmn_wall_time();
  const int rc = step_impl(sv, dt_limit, msg, msglen);
  timed(sv, SPH_PHASE_STEP, t0);
  return rc;
}

static int step_impl(struct sph_solver *sv, double dt_limit, char *msg, size_t msglen) {
  struct sph_system *s = &sv->sys;
  struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  /* State n: lists, γ^n, boundary values, a^n, D^n, then Δt. */
  if (sv->evaluated_step != sv->step) sph_solver_evaluate(sv);
  sv->evaluated_step = -1;
  if (vertex_failed(sv, msg, msglen)) return -1;
  sv->gamma_current = 0; /* positions move from here; the corrector's γ sets it again */
  double dt = fmin(sph_solver_timestep(sv), dt_limit);
  if (!(dt > 0.0)) {
    char why[768];
    sph_solver_explain_dt(sv, dt, why, sizeof why);
    snprintf(msg, msglen, "step %ld, t = %.9g s: %s", sv->step + 1, sv->time, why);
    return -1;
  }
  sv->dt = dt;
  if (sv->cfg.flux_method != SPH_FLUXSEL_OFF) {
    /* ṽ^{n−1} at the start of the step, M(56–57), then F^n by M(63) (variable-step form M 62) or
     * M(58); F^n acts during the whole step (both stages). */
    if (sv->flux_ctrl.steps == 0)
      sph_flux_ctrl_init(&sv->flux_ctrl,
                         sv->cfg.flux_method == SPH_FLUXSEL_M58 ? SPH_FLUX_M58 : SPH_FLUX_M63,
                         sv->cfg.flux_velocity, sv->cfg.flux_force0);
    sv->flux_v = sph_solver_flux_measure(sv);
    sv->flux_force = sph_flux_ctrl_update(&sv->flux_ctrl, sv->flux_v, dt);
    add_flux_force(sv);
  }
  const size_t n = f->n;
  for (int c = 0; c < 3; c++) {
    memcpy(sv->x0[c], f->x[c], n * sizeof(double));
    memcpy(sv->v0[c], f->v[c], n * sizeof(double));
  }
  memcpy(sv->rho_n, f->rho, n * sizeof(double));
  memcpy(sv->gamma_n, f->gamma, n * sizeof(double));
  if (sv->cfg.wall_vertex_mass_density) wall_vertex_masses(sv);
  sph_open_mass_begin(sv->open, sv); /* open boundaries: m_v^n, J(14) (§10) */
  for (int c = 0; c < 3; c++) memcpy(sv->grad_gamma_n[c], f->grad_gamma[c], n * sizeof(double));

  /* Predictor to t + Δt/2. */
  for (int c = 0; c < 3; c++)
    for (size_t a = 0; a < n; a++) {
      f->v[c][a] = sv->v0[c][a] + 0.5 * dt * sv->acc[c][a];
      f->x[c][a] = sv->x0[c][a] + 0.5 * dt * sv->v0[c][a];
    }
  wrap(sv);
  lists_check(sv);
  refresh_gamma(sv);
  if (sv->cfg.gamma_dynamic) gamma_dynamic(sv, (const double *const *)sv->v0, 0.5 * dt);
  continuity(sv, 0.5 * dt, 0);
  sph_open_mass_set(sv->open, sv, 0.5 * dt); /* open vertices: m* = m^n + Δt/2 ṁ^n (§10) */
  sv->stage_time = sv->time + 0.5 * dt;      /* the predictor's state (open-boundary data) */
  sph_solver_boundary_values(sv);
  if (vertex_failed(sv, msg, msglen)) return -1;
  sph_solver_forces(sv);
  add_flux_force(sv);
  sph_open_mass_set(sv->open, sv, 0.0); /* m^n back for the corrector's continuity (§3) */

  /* Corrector to t + Δt. */
  for (int c = 0; c < 3; c++)
    for (size_t a = 0; a < n; a++) {
      f->v[c][a] = sv->v0[c][a] + dt * sv->acc[c][a];
      f->x[c][a] = sv->x0[c][a] + 0.5 * dt * (sv->v0[c][a] + f->v[c][a]);
    }
  double dmax = 0.0;
  for (size_t a = 0; a < n; a++) {
    double d2 = 0.0;
    for (int c = 0; c < 3; c++) d2 += (f->x[c][a] - sv->x0[c][a]) * (f->x[c][a] - sv->x0[c][a]);
    dmax = fmax(dmax, d2);
  }
  wrap(sv);
  lists_check(sv);
  refresh_gamma(sv);
  sv->gamma_current = 1;
  if (sv->cfg.gamma_dynamic) gamma_dynamic(sv, (const double *const *)f->v, dt);
  const int leaving = continuity(sv, dt, 1);
  sph_open_mass_end(sv->open, sv, dt); /* m^{n+1} = m^n + Δt ṁ*, J(14) (§10) */
  if (sqrt(dmax) > 0.5 * skin(sv)) {
    snprintf(msg, msglen,
             "step %ld, t = %.9g s: a particle moved %g m in one step, more than half the "
             "neighbour skin (%g m)",
             sv->step + 1, sv->time, sqrt(dmax), 0.5 * skin(sv));
    return -1;
  }
  /* Open boundaries (§10): particles that left through an open segment are deleted (their mass
   * to its vertices) before the checks, and vertices whose mass passed the threshold create one
   * after them; the store changed: sync. */
  const size_t ndel = sv->open_off ? 0 : sph_open_delete_particles(sv->open, sv);
  int rc = check_state(sv, msg, msglen);
  const size_t nnew = sv->open_off || rc ? 0 : sph_open_create_particles(sv->open, sv);
  /* The corrector's sums are the next step's sums at x0 while the masses stay (no open
   * boundaries) and the store is not changed by hand (sph_solver_sync drops them); their fluid
   * parts while the store is not changed (fluid masses are constant) and every particle's sums
   * were formed (none leaving). */
  for (int k = 0; k < 2; k++) {
    double **sw = k == 0 ? sv->sum_w : sv->sum_wf, *t = sw[0];
    sw[0] = sw[1];
    sw[1] = t;
  }
  sv->sum_w_valid = rc == 0 && !leaving;
  if (ndel || nnew) sph_solver_sync(sv);
  sv->time += dt;
  sv->step++;
  return rc;
}
