/*
 * Solver set-up: kernel and EOS, initial fluid state (uniform, hydrostatic or expression
 * profiles of velocity and pressure or density, masses m_a = ρ_a Δr^d), vertex masses, force
 * groups; and the solver's own per-particle arrays.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multiroots.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "operators/pair.h"
#include "sabre/common.h"
#include "sabre/sph_solver.h"
#include "sabre/sph_walls.h"

/* An initial profile given as an expression of x, y, z (NULL for ""); sph_config_read() checked
 * the text, so a failure here is an internal error. */
static struct cmn_expr *compile_initial(const char *text, const char *key, int dim) {
  static const char *const xyz[] = {"x", "y", "z"};
  if (!text[0]) return NULL;
  char err[512];
  struct cmn_expr *e = cmn_expr_compile(text, dim, xyz, err, sizeof err);
  if (!e) cmn_error("%s: %s", key, err);
  return e;
}

/*
 * Vertex masses m_v = φ ρ_v A_v Δr, A_v the vertex's share of its segments' measure (Σ_{s∋v}
 * |s|/d): a wall layer φΔr thick, with the one scalar φ fitted by least squares so that the
 * summation density of the fluid at its initial positions equals its initial density, min_φ Σ_{a∈F}
 * (γ_a ρ_a − Σ_{b∈F} m_b w_ab − φ z_a)²,  z_a = Σ_v ρ_v A_v Δr w_av. (A least-squares fit of every
 * vertex mass is ill-posed in 3D with h/Δr = 1.3: the masses oscillate by orders of magnitude.) The
 * time-summation continuity then starts consistently.
 */
static void vertex_masses(struct sph_solver *sv) {
  struct sph_system *s = &sv->sys;
  struct sph_parts *f = &s->part[SPH_KIND_FLUID], *v = &s->part[SPH_KIND_VERTEX];
  const struct sph_parts *sg = &s->part[SPH_KIND_SEGMENT];
  const struct sph_kernel *k = &sv->kernel;
  const struct sph_nlist *fv = &sv->nb.list[SPH_KIND_VERTEX], *ff = &sv->nb.list[SPH_KIND_FLUID];
  const size_t nf = f->n, nv = v->n;
  for (size_t i = 0; i < nv; i++) v->mass[i] = 0.0;
  if (nv == 0 || nf == 0) return;
  double *unit = cmn_calloc(nv, sizeof *unit); /* ρ_v A_v Δr */
  for (size_t j = 0; j < sg->n; j++)
    for (int d = 0; d < s->dim; d++) unit[sg->vertex[d][j]] += sg->measure[j] / s->dim;
  for (size_t i = 0; i < nv; i++) unit[i] *= v->rho[i] * s->dr;
  double yz = 0.0, zz = 0.0;
  for (size_t a = 0; a < nf; a++) {
    if (fv->offset[a] == fv->offset[a + 1]) continue;
    double sum = f->mass[a] * sph_kernel_w_inline(k, 0.0), z = 0.0;
    for (size_t j = ff->offset[a]; j < ff->offset[a + 1]; j++) {
      struct sph_pair pr;
      if (sph_pair_eval(k, s, f, a, f, ff->index[j], &pr)) sum += f->mass[ff->index[j]] * pr.w;
    }
    for (size_t j = fv->offset[a]; j < fv->offset[a + 1]; j++) {
      struct sph_pair pr;
      if (sph_pair_eval(k, s, f, a, v, fv->index[j], &pr)) z += unit[fv->index[j]] * pr.w;
    }
    yz += (f->gamma[a] * f->rho[a] - sum) * z;
    zz += z * z;
  }
  const double phi = zz > 0.0 ? yz / zz : 0.0;
  for (size_t i = 0; i < nv; i++) v->mass[i] = phi * unit[i];
  sv->vertex_phi = phi;
  free(unit);
}

/* The initial pressure and density as functions of position: hydrostatic below a level, a number
 * or expressions of x, y, z (initial.pressure / initial.density). */
struct profile {
  const struct rmn_eos *eos;
  int hydrostatic;
  double gnorm, up[3], level; /* |g|, −g/|g|, the level of p = 0 along up */
  struct cmn_expr *p_expr, *rho_expr;
  const struct sph_open_source *wave; /* initial.wave (NULL: none) */
};

/* Height of fluid particle a along the profile's up [m]. */
static double profile_height(const struct profile *pr, const struct sph_parts *f, size_t a) {
  return pr->up[0] * f->x[0][a] + pr->up[1] * f->x[1][a] + pr->up[2] * f->x[2][a];
}

static void profile_init(struct profile *pr, const struct sph_solver *sv,
                         const struct sph_open_source *wave) {
  const struct sph_config *cfg = &sv->cfg;
  const struct sph_system *sys = &sv->sys;
  const struct sph_parts *f = &sys->part[SPH_KIND_FLUID];
  memset(pr, 0, sizeof *pr);
  pr->eos = &sv->eos;
  pr->hydrostatic = cfg->hydrostatic;
  pr->gnorm = sqrt(cfg->gravity[0] * cfg->gravity[0] + cfg->gravity[1] * cfg->gravity[1] +
                   cfg->gravity[2] * cfg->gravity[2]);
  if (pr->gnorm > 0.0)
    for (int c = 0; c < 3; c++) pr->up[c] = -cfg->gravity[c] / pr->gnorm;
  pr->level = cfg->free_surface;
  if (isnan(pr->level)) {
    pr->level = -INFINITY;
    for (size_t a = 0; a < f->n; a++) pr->level = fmax(pr->level, profile_height(pr, f, a));
    pr->level += 0.5 * sys->dr;
  }
  pr->p_expr = compile_initial(cfg->p0_expr, "initial.pressure", sys->dim);
  pr->rho_expr = compile_initial(cfg->rho0_expr, "initial.density", sys->dim);
  pr->wave = wave;
}

static void profile_free(struct profile *pr) {
  cmn_expr_free(pr->p_expr);
  cmn_expr_free(pr->rho_expr);
}

/* Initial density at x [kg/m³]; stops the program on a value out of range. */
static double profile_density(const struct profile *pr, const double *x) {
  double p = 0.0;
  if (pr->hydrostatic && pr->gnorm > 0.0) {
    double depth = pr->level - (pr->up[0] * x[0] + pr->up[1] * x[1] + pr->up[2] * x[2]);
    p = sph_hydrostatic_pressure(pr->eos, pr->gnorm, fmax(depth, 0.0));
  }
  if (pr->p_expr) p = cmn_expr_eval(pr->p_expr, x);
  if (pr->wave) {
    double u[3];
    sph_open_source_wave(pr->wave, 0.0, x, &p, u);
  }
  const double pmin = rmn_eos_min_pressure(pr->eos);
  if (!(p > pmin) || !isfinite(p))
    cmn_input_error("%s: %g Pa at (%g, %g, %g) is not above the EOS's minimum %g Pa",
                    pr->wave ? "initial.wave (its pressure)" : "initial.pressure", p, x[0], x[1],
                    x[2], pmin);
  const double rho = pr->rho_expr ? cmn_expr_eval(pr->rho_expr, x) : rmn_eos_density(pr->eos, p);
  if (!(rho > 0.0) || !isfinite(rho))
    cmn_input_error("initial.density: %g kg/m^3 at (%g, %g, %g) is not positive", rho, x[0], x[1],
                    x[2]);
  return rho;
}

/* Densities and masses m_a = ρ_a Δr^d of the fluid at its current positions. */
static void fluid_density(struct sph_solver *sv, const struct profile *pr) {
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const double vol = pow(sv->sys.dr, sv->sys.dim);
  for (size_t a = 0; a < f->n; a++) {
    const double x[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
    f->rho[a] = profile_density(pr, x);
    f->mass[a] = f->rho[a] * vol;
  }
}

/* Initial velocities (numbers or expressions of the position, or the wave's). */
static void fluid_velocity(struct sph_solver *sv, const struct sph_open_source *wave) {
  const struct sph_config *cfg = &sv->cfg;
  struct sph_system *sys = &sv->sys;
  struct sph_parts *f = &sys->part[SPH_KIND_FLUID];
  struct cmn_expr *u_expr[3] = {NULL, NULL, NULL};
  for (int c = 0; c < sys->dim; c++)
    u_expr[c] = compile_initial(cfg->u0_expr[c], "initial.velocity", sys->dim);
  for (size_t a = 0; a < f->n; a++) {
    const double x[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
    double uw[3] = {0.0, 0.0, 0.0}, pw;
    if (wave) sph_open_source_wave(wave, 0.0, x, &pw, uw);
    for (int c = 0; c < 3; c++) {
      f->v[c][a] = c >= sys->dim ? 0.0
                   : wave        ? uw[c]
                   : u_expr[c]   ? cmn_expr_eval(u_expr[c], x)
                                 : cfg->u0[c];
      if (!isfinite(f->v[c][a]))
        cmn_input_error("%s[%d]: %g m/s at (%g, %g, %g) is not finite",
                        wave ? "initial.wave (its velocity)" : "initial.velocity", c, f->v[c][a],
                        x[0], x[1], x[2]);
    }
  }
  for (int c = 0; c < 3; c++) cmn_expr_free(u_expr[c]);
}

/* Vertex masses: geometric (the wall layer nearest to each vertex) or fitted (vertex_masses). */
static void vertex_masses_set(struct sph_solver *sv) {
  struct sph_system *sys = &sv->sys;
  struct sph_parts *v = &sys->part[SPH_KIND_VERTEX];
  if (sv->cfg.vertex_volume == SPH_VVOL_FITTED) {
    vertex_masses(sv);
    return;
  }
  if (sph_walls_vertex_volumes(sys, sv->cfg.vertex_layer * sys->dr, v->mass) != 0)
    cmn_error("vertex volumes: bad layer thickness %g m", sv->cfg.vertex_layer * sys->dr);
  for (size_t i = 0; i < v->n; i++) v->mass[i] *= v->rho[i];
  sv->vertex_phi = sv->cfg.vertex_layer;
}

/*
 * The layer equilibrium (repack.layer_equilibrium, docs/sph-solver.md §8): the fluid particles
 * grouped into horizontal layers by their depth below the highest one, rounded to Δr; each layer
 * moved along the vertical by one shift s_k (in Δr) so that its mean vertical acceleration is
 * zero, with the densities and masses of the initial profile at the moved positions. The shifts
 * are the root of L functions of L unknowns, found by GSL's hybrid solver (Jacobian by finite
 * differences, one force evaluation per layer).
 */
#define SPH_LAYER_TOL 1e-9 /* largest |mean a·up| / |g| of a layer at the root */
#define SPH_LAYER_ITER 200 /* hybrid iterations at most */

struct layers {
  struct sph_solver *sv;
  const struct profile *pr;
  double *height0; /* each particle's height along up before the shifts [m] */
  int *layer;      /* each particle's layer, 0 the highest */
  double *count;   /* particles of each layer */
  int n;           /* layers */
};

/* Residual of the shifts u [Δr]: each layer's mean vertical acceleration / |g|. */
static int layers_residual(const gsl_vector *u, void *params, gsl_vector *out) {
  struct layers *ly = params;
  struct sph_solver *sv = ly->sv;
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const double *up = ly->pr->up;
  for (size_t a = 0; a < f->n; a++) {
    const double move = ly->height0[a] + sv->sys.dr * gsl_vector_get(u, (size_t)ly->layer[a]) -
                        profile_height(ly->pr, f, a);
    for (int c = 0; c < 3; c++) f->x[c][a] += move * up[c];
  }
  fluid_density(sv, ly->pr);
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
  gsl_vector_set_zero(out);
  for (size_t a = 0; a < f->n; a++) {
    const double av = up[0] * sv->acc[0][a] + up[1] * sv->acc[1][a] + up[2] * sv->acc[2][a];
    const size_t k = (size_t)ly->layer[a];
    gsl_vector_set(out, k, gsl_vector_get(out, k) + av / (ly->pr->gnorm * ly->count[k]));
  }
  for (int k = 0; k < ly->n; k++)
    if (!isfinite(gsl_vector_get(out, (size_t)k))) return GSL_EBADFUNC;
  return GSL_SUCCESS;
}

static void layer_equilibrium(struct sph_solver *sv, const struct profile *pr) {
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const double dr = sv->sys.dr;
  if (f->n == 0) return;
  struct layers ly = {
      sv,   pr, cmn_malloc((f->n + 1) * sizeof(double)), cmn_malloc((f->n + 1) * sizeof(int)),
      NULL, 0};
  double top = -INFINITY, bottom = INFINITY;
  for (size_t a = 0; a < f->n; a++) {
    ly.height0[a] = profile_height(pr, f, a);
    top = fmax(top, ly.height0[a]);
    bottom = fmin(bottom, ly.height0[a]);
  }
  /* layer numbers by depth; the empty ones (a fluid not filled on a lattice) left out */
  const size_t span = (size_t)lround((top - bottom) / dr) + 1;
  int *number = cmn_malloc(span * sizeof *number);
  for (size_t k = 0; k < span; k++) number[k] = -1;
  for (size_t a = 0; a < f->n; a++) number[lround((top - ly.height0[a]) / dr)] = 0;
  for (size_t k = 0; k < span; k++)
    if (number[k] == 0) number[k] = ly.n++;
  ly.count = cmn_calloc((size_t)ly.n, sizeof *ly.count);
  for (size_t a = 0; a < f->n; a++) {
    ly.layer[a] = number[lround((top - ly.height0[a]) / dr)];
    ly.count[ly.layer[a]] += 1.0;
  }
  free(number);

  gsl_error_handler_t *handler = gsl_set_error_handler_off();
  gsl_multiroot_function fn = {layers_residual, (size_t)ly.n, &ly};
  gsl_vector *u = gsl_vector_calloc((size_t)ly.n);
  gsl_multiroot_fsolver *so =
      gsl_multiroot_fsolver_alloc(gsl_multiroot_fsolver_hybrids, (size_t)ly.n);
  int status = gsl_multiroot_fsolver_set(so, &fn, u), it = 0;
  double res = fmax(gsl_vector_max(so->f), -gsl_vector_min(so->f));
  while (status == GSL_SUCCESS && !(res <= SPH_LAYER_TOL) && it < SPH_LAYER_ITER) {
    status = gsl_multiroot_fsolver_iterate(so);
    it++;
    res = fmax(gsl_vector_max(so->f), -gsl_vector_min(so->f));
  }
  gsl_set_error_handler(handler);
  if (!(res <= SPH_LAYER_TOL))
    cmn_input_error(
        "repack.layer_equilibrium: no equilibrium of the %d layers found (%s after %d "
        "iterations): a layer's mean vertical acceleration is still %.3g |g|",
        ly.n, status ? gsl_strerror(status) : "no convergence", it, res);
  /* the state at the root (the solver's last evaluation may be elsewhere) */
  sv->layer_shift = cmn_malloc((size_t)ly.n * sizeof *sv->layer_shift);
  for (int k = 0; k < ly.n; k++) sv->layer_shift[k] = gsl_vector_get(so->x, (size_t)k);
  sv->layer_count = ly.n;
  sv->layer_residual = res;
  layers_residual(so->x, &ly, so->f);
  gsl_multiroot_fsolver_free(so);
  gsl_vector_free(u);
  free(ly.height0);
  free(ly.layer);
  free(ly.count);
}

/*
 * The settling run (repack.settle): the case's own dynamics from the initial state for cfg.settle
 * seconds, then every fluid velocity set to zero and the clock back to t = 0, step 0
 * (docs/sph-solver.md §8). A failed step stops the set-up with the step's message.
 */
static void settle(struct sph_solver *sv) {
  const double t_end = sv->cfg.settle;
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  struct cmn_progress prog;
  cmn_progress_start(&prog, 0.0, t_end);
  while (sv->time < t_end * (1.0 - 1e-12)) {
    char msg[1024];
    if (sph_solver_step(sv, t_end - sv->time, msg, sizeof msg) != 0)
      cmn_input_error("repack.settle: the settling run failed: %s", msg);
    cmn_progress_task(&prog, sv->time, 0, "settling: t = %.4g s of %g s, step %ld", sv->time, t_end,
                      sv->step);
  }
  struct sph_diagnostics d;
  sph_solver_diagnostics(sv, &d);
  sv->settle_steps = sv->step;
  sv->settle_speed = d.max_speed;
  for (int c = 0; c < 3; c++)
    for (size_t a = 0; a < f->n; a++) f->v[c][a] = 0.0;
  sv->time = 0.0;
  sv->step = 0;
  sv->dt = 0.0;
  sph_solver_sync(sv);
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
  /* numerics.artificial_viscosity: the laminar viscosity equivalent to the α term, ν_α = α h c0 /
   * (2(d + 2)), added to the fluid's (docs/sph-solver.md §4) */
  sv->cfg.nu += cfg->artificial_viscosity * sys->h * cfg->c0 / (2.0 * (sys->dim + 2));

  struct sph_parts *f = &sys->part[SPH_KIND_FLUID];
  /* initial.wave: the fluid below the wave's surface at t = 0 (a particle's cell centred below
   * it), with the wave's velocity and pressure */
  struct sph_open_source wave_src, *wave = NULL;
  if (sv->cfg.initial_wave) {
    char msg[512];
    if (sph_open_source_init(&wave_src, &sv->cfg.wave, sys->dim, cfg->gravity, &sv->eos, msg,
                             sizeof msg) != 0)
      cmn_input_error("initial.wave: %s", msg);
    wave = &wave_src;
    uint8_t *drop = cmn_malloc((f->n + 1) * sizeof *drop);
    for (size_t a = 0; a < f->n; a++) {
      const double x[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
      double p, u[3];
      const double top = sph_open_source_wave(wave, 0.0, x, &p, u);
      drop[a] = !(wave_src.up[0] * x[0] + wave_src.up[1] * x[1] + wave_src.up[2] * x[2] < top);
    }
    sph_parts_remove(f, drop);
    free(drop);
    if (f->n == 0)
      cmn_input_error(
          "initial.wave: no fluid particle lies below the wave's surface (check "
          "the fluid regions, the wave's bed and depth)");
  }
  struct profile prof;
  profile_init(&prof, sv, wave);
  fluid_density(sv, &prof);
  for (int c = 0; c < 3; c++)
    for (size_t a = 0; a < f->n; a++) f->v[c][a] = 0.0;
  struct sph_parts *v = &sys->part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++) v->rho[i] = cfg->rho0;

  sph_nbrs_build(&sv->nb, sys, cfg->skin_over_h * sys->h);
  sph_nbrs_gamma(&sv->nb, sys, &sv->kernel);
  sph_solver_sync(sv);
  sph_solver_vertex_groups(sv, seg_wall, seg_edge);
  {
    char msg[1024];
    int failed;
    sv->open = sph_open_create(sv, seg_wall, seg_edge, &failed, msg, sizeof msg);
    if (failed) cmn_input_error("%s", msg);
  }
  sph_solver_boundary_values(sv);
  vertex_masses_set(sv);
  sph_solver_boundary_values(sv);
  if (cfg->repack_steps > 0) {
    char msg[512];
    if (sph_solver_repack(sv, cfg->repack_steps, msg, sizeof msg) != 0) cmn_input_error("%s", msg);
    fluid_density(sv, &prof);
    sph_nbrs_build(&sv->nb, sys, cfg->skin_over_h * sys->h);
    sph_nbrs_gamma(&sv->nb, sys, &sv->kernel);
    sph_solver_sync(sv);
    sph_solver_boundary_values(sv);
    if (cfg->vertex_volume == SPH_VVOL_FITTED) vertex_masses(sv);
    sph_solver_boundary_values(sv);
  }
  if (cfg->layer_equilibrium) layer_equilibrium(sv, &prof);
  profile_free(&prof);
  fluid_velocity(sv, wave);
  if (wave) sph_open_source_free(wave);
  /* the wall masses, final now (the open vertices' creation threshold and outflow floor,
   * docs/sph-solver.md §10), and the wall layers' volumes (§4): in the store, so that a restart,
   * which does not repeat the set-up, has them */
  for (size_t i = 0; i < v->n; i++) {
    v->wall_mass[i] = v->mass[i];
    v->volume[i] = v->mass[i] / v->rho[i];
  }

  sv->evaluated_step = -1;

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
      for (int e = 0; e < fg->nedges && !match; e++)
        match = seg_edge && fg->edges[e] == seg_edge[j];
      if (match) sv->seg_group[j] = g;
    }
    for (int k = 0; k < sys->dim; k++) {
      size_t iv = sg->vertex[k][j];
      if (sv->vert_group[iv] < 0) sv->vert_group[iv] = sv->seg_group[j];
    }
  }
  /* last: the settling run steps a solver that is set up in full */
  if (cfg->settle > 0.0) settle(sv);
}

void sph_solver_free(struct sph_solver *sv) {
  for (int k = 0; k < SPH_NKINDS; k++) {
    free(sv->mu[k]);
  }
  for (int c = 0; c < 3; c++) {
    free(sv->acc[c]);
    free(sv->x0[c]);
    free(sv->x_list[c]);
    free(sv->v0[c]);
    free(sv->grad_gamma_n[c]);
  }
  free(sv->rho_n);
  free(sv->sum_w[0]);
  free(sv->sum_w[1]);
  free(sv->sum_wf[0]);
  free(sv->sum_wf[1]);
  free(sv->gamma_n);
  free(sv->diff);
  free(sv->csound);
  free(sv->vol);
  free(sv->inv_rho2);
  free(sv->impedance);
  free(sv->seg_group);
  free(sv->vert_group);
  free(sv->vert_bc);
  free(sv->vertex_dm);
  free(sv->layer_shift);
  sph_open_free(sv->open);
  sph_nbrs_free(&sv->nb);
  sph_system_free(&sv->sys);
  memset(sv, 0, sizeof *sv);
}
