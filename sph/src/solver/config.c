/* The solver's sections of a case file: fluid, gravity, initial, numerics, time, probes, forces
 * (reference with units and defaults: docs/sph-case-file.md; `geometry` is read by
 * sph_geometry_read()). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_robin.h"
#include "sabre/sph_solver.h"

#define TRY(x)               \
  do {                       \
    if ((x) != 0) return -1; \
  } while (0)

/* Optional number in (0, 1]. */
static int opt_fraction(struct cmn_case *c, const char *path, double def, double *x) {
  TRY(cmn_case_opt_positive(c, path, def, x));
  if (*x > 1.0) return cmn_case_fail(c, path, "expected a number in (0, 1], got %g", *x);
  return 0;
}

static int opt_vector(struct cmn_case *c, const char *path, int dim, double *x) {
  const double zero[3] = {0.0, 0.0, 0.0};
  x[0] = x[1] = x[2] = 0.0;
  return cmn_case_opt_doubles(c, path, dim, zero, x);
}

static int read_points(struct cmn_case *c, const char *path, int dim, double (*pts)[3], int *n) {
  int len = cmn_case_seq_length(c, path);
  if (len < 0) return -1;
  if (len > SPH_MAX_PROBES)
    return cmn_case_fail(c, path, "at most %d points are supported", SPH_MAX_PROBES);
  for (int i = 0; i < len; i++) {
    char q[128];
    snprintf(q, sizeof q, "%s[%d]", path, i);
    pts[i][0] = pts[i][1] = pts[i][2] = 0.0;
    TRY(cmn_case_get_doubles(c, q, dim, dim, pts[i], NULL));
  }
  *n = len;
  return 0;
}

/* A number, or an expression of the coordinates checked here and kept as text (compiled again by
 * the set-up): *number or expr (256 characters, "" for a number). */
static int read_number_or_expr(struct cmn_case *c, const char *path, int dim, double *number,
                               char *expr) {
  static const char *const xyz[] = {"x", "y", "z"};
  const char *text;
  expr[0] = '\0';
  TRY(cmn_case_get_string(c, path, &text));
  if (cmn_parse_double(text, number) == 0) return 0;
  char err[512];
  struct cmn_expr *e = cmn_expr_compile(text, dim, xyz, err, sizeof err);
  if (!e) return cmn_case_fail(c, path, "expected a number or an expression: %s", err);
  cmn_expr_free(e);
  if (strlen(text) >= 256) return cmn_case_fail(c, path, "expression longer than 255 characters");
  snprintf(expr, 256, "%s", text);
  return 0;
}

/* initial.velocity (numbers or expressions), initial.pressure (zero, hydrostatic or an
 * expression), initial.density (an expression, instead of the pressure). */
static int read_initial_fields(struct cmn_case *c, struct sph_config *cfg, int dim) {
  if (cmn_case_has(c, "initial.velocity")) {
    int n = cmn_case_seq_length(c, "initial.velocity");
    if (n < 0) return -1;
    if (n != dim)
      return cmn_case_fail(c, "initial.velocity", "expected %d numbers or expressions, got %d", dim,
                           n);
    for (int i = 0; i < dim; i++) {
      char q[64];
      snprintf(q, sizeof q, "initial.velocity[%d]", i);
      TRY(read_number_or_expr(c, q, dim, &cfg->u0[i], cfg->u0_expr[i]));
    }
  } else {
    TRY(opt_vector(c, "initial.velocity", dim, cfg->u0));
  }
  const char *pressure;
  TRY(cmn_case_opt_string(c, "initial.pressure", "zero", &pressure));
  cfg->hydrostatic = strcmp(pressure, "hydrostatic") == 0;
  if (!cfg->hydrostatic && strcmp(pressure, "zero") != 0) {
    double p0;
    TRY(read_number_or_expr(c, "initial.pressure", dim, &p0, cfg->p0_expr));
    if (!cfg->p0_expr[0]) snprintf(cfg->p0_expr, sizeof cfg->p0_expr, "%.17g", p0);
  }
  if (cmn_case_has(c, "initial.density")) {
    if (strcmp(pressure, "zero") != 0)
      return cmn_case_fail(c, "initial.density",
                           "give initial.pressure or initial.density, not both");
    double rho0;
    TRY(read_number_or_expr(c, "initial.density", dim, &rho0, cfg->rho0_expr));
    if (!cfg->rho0_expr[0]) snprintf(cfg->rho0_expr, sizeof cfg->rho0_expr, "%.17g", rho0);
  }
  return 0;
}

/* The walls a group names: `<base>.wall` (index into geometry.walls) and optional
 * `<base>.edges` (1-based element numbers within that wall; none: the whole wall). Shared by
 * force groups and vertex-value groups. */
static int read_wall_selection(struct cmn_case *c, const char *base, int nwalls, int *wall_out,
                               long *edges, int max_edges, int *nedges_out) {
  char p[128];
  long wall;
  snprintf(p, sizeof p, "%s.wall", base);
  TRY(cmn_case_get_long(c, p, 0, nwalls > 0 ? nwalls - 1 : 0, &wall));
  if (nwalls <= 0) return cmn_case_fail(c, p, "there are no geometry.walls");
  *wall_out = (int)wall;
  snprintf(p, sizeof p, "%s.edges", base);
  int ne = cmn_case_seq_length(c, p);
  if (ne < 0) return -1;
  if (ne > max_edges) return cmn_case_fail(c, p, "at most %d edges", max_edges);
  *nedges_out = ne;
  for (int e = 0; e < ne; e++) {
    char q[160];
    snprintf(q, sizeof q, "%s[%d]", p, e);
    TRY(cmn_case_get_long(c, q, 1, 1000000000L, &edges[e]));
  }
  return 0;
}

static int read_forces(struct cmn_case *c, struct sph_config *cfg) {
  int n = cmn_case_seq_length(c, "forces");
  if (n < 0) return -1;
  if (n > SPH_MAX_FORCE_GROUPS)
    return cmn_case_fail(c, "forces", "at most %d force groups are supported",
                         SPH_MAX_FORCE_GROUPS);
  int nwalls = cmn_case_seq_length(c, "geometry.walls");
  for (int i = 0; i < n; i++) {
    struct sph_force_group *g = &cfg->forces[i];
    char p[128];
    const char *name;
    snprintf(p, sizeof p, "forces[%d].name", i);
    TRY(cmn_case_get_string(c, p, &name));
    if (strlen(name) == 0 || strlen(name) >= sizeof g->name || strpbrk(name, ", \"\n"))
      return cmn_case_fail(c, p,
                           "expected a name of 1 to %zu characters without spaces, commas "
                           "or quotes",
                           sizeof g->name - 1);
    for (int j = 0; j < i; j++)
      if (strcmp(cfg->forces[j].name, name) == 0)
        return cmn_case_fail(c, p, "duplicate force group name '%s'", name);
    snprintf(g->name, sizeof g->name, "%s", name);
    snprintf(p, sizeof p, "forces[%d]", i);
    TRY(read_wall_selection(c, p, nwalls, &g->wall, g->edges,
                            (int)(sizeof g->edges / sizeof g->edges[0]), &g->nedges));
  }
  cfg->nforces = n;
  return 0;
}

/* Keys of one vertex_values entry under `base` ("vertex_values" or "vertex_values.groups[i]"),
 * each defaulting to *def (docs/sph-case-file.md). */
static int read_vertex_bc(struct cmn_case *c, const char *base, const struct sph_vertex_bc *def,
                          struct sph_vertex_bc *bc) {
  char p[160];
  *bc = *def;
  static const char *const methods[] = {"shepard", "least_squares", NULL};
  snprintf(p, sizeof p, "%s.method", base);
  TRY(cmn_case_opt_choice(c, p, methods, def->method, &bc->method));
  long order;
  snprintf(p, sizeof p, "%s.order", base);
  TRY(cmn_case_opt_long(c, p, def->order, 1, SPH_ROBIN_M_MAX, &order));
  bc->order = (int)order;
  snprintf(p, sizeof p, "%s.mu", base);
  TRY(cmn_case_opt_doubles(c, p, 3, def->mu, bc->mu));
  if (!(bc->mu[1] != 0.0) || !isfinite(bc->mu[0]) || !isfinite(bc->mu[1]) || !isfinite(bc->mu[2]))
    return cmn_case_fail(c, p,
                         "expected [mu1, mu2, mu3] with mu2 != 0 (M 64: Dirichlet is outside "
                         "the method)");
  snprintf(p, sizeof p, "%s.gravity_flux", base);
  TRY(cmn_case_opt_bool(c, p, def->gravity_flux, &bc->gravity_flux));
  static const char *const constraints[] = {"M82", "M83", NULL};
  snprintf(p, sizeof p, "%s.constraint", base);
  TRY(cmn_case_opt_choice(c, p, constraints, def->tangential, &bc->tangential));
  static const char *const too_few[] = {"error", "lower", NULL};
  snprintf(p, sizeof p, "%s.too_few", base);
  TRY(cmn_case_opt_choice(c, p, too_few, def->too_few, &bc->too_few));
  return 0;
}

static int read_vertex_values(struct cmn_case *c, struct sph_config *cfg) {
  const struct sph_vertex_bc def = {.method = SPH_VVALUES_SHEPARD,
                                    .order = 1,
                                    .mu = {0.0, 1.0, 0.0},
                                    .gravity_flux = 1,
                                    .tangential = 1,
                                    .too_few = SPH_VTOOFEW_ERROR,
                                    .wall = -1};
  TRY(read_vertex_bc(c, "vertex_values", &def, &cfg->vertex_bc));
  int n = cmn_case_seq_length(c, "vertex_values.groups");
  if (n < 0) return -1;
  if (n > SPH_MAX_VERTEX_GROUPS)
    return cmn_case_fail(c, "vertex_values.groups", "at most %d groups are supported",
                         SPH_MAX_VERTEX_GROUPS);
  int nwalls = cmn_case_seq_length(c, "geometry.walls");
  for (int i = 0; i < n; i++) {
    struct sph_vertex_bc *g = &cfg->vertex_groups[i];
    char base[64];
    snprintf(base, sizeof base, "vertex_values.groups[%d]", i);
    TRY(read_vertex_bc(c, base, &cfg->vertex_bc, g));
    TRY(read_wall_selection(c, base, nwalls, &g->wall, g->edges,
                            (int)(sizeof g->edges / sizeof g->edges[0]), &g->nedges));
  }
  cfg->nvertex_groups = n;
  return 0;
}

/* imposed_flux: absent = off; otherwise M63 unless `method` says M58 or off (M §5). */
static int read_imposed_flux(struct cmn_case *c, struct sph_config *cfg, int dim) {
  cfg->flux_method = SPH_FLUXSEL_OFF;
  if (!cmn_case_has(c, "imposed_flux")) return 0;
  static const char *const methods[] = {"off", "M63", "M58", NULL};
  TRY(cmn_case_opt_choice(c, "imposed_flux.method", methods, SPH_FLUXSEL_M63, &cfg->flux_method));
  const double ex[3] = {1.0, 0.0, 0.0}, zero[3] = {0.0, 0.0, 0.0};
  TRY(cmn_case_opt_doubles(c, "imposed_flux.direction", dim, ex, cfg->flux_normal));
  double len = 0.0;
  for (int k = 0; k < dim; k++) len += cfg->flux_normal[k] * cfg->flux_normal[k];
  len = sqrt(len);
  if (!(len > 0.0) || !isfinite(len))
    return cmn_case_fail(c, "imposed_flux.direction", "expected a non-zero vector");
  for (int k = 0; k < 3; k++) cfg->flux_normal[k] = k < dim ? cfg->flux_normal[k] / len : 0.0;
  TRY(cmn_case_opt_doubles(c, "imposed_flux.point", dim, zero, cfg->flux_point));
  double dr;
  TRY(cmn_case_get_positive(c, "geometry.dr", &dr));
  TRY(cmn_case_opt_positive(c, "imposed_flux.width", 2.0 * dr, &cfg->flux_width));
  if (dim == 1)
    TRY(cmn_case_opt_positive(c, "imposed_flux.area", 1.0, &cfg->flux_area));
  else
    TRY(cmn_case_get_positive(c, "imposed_flux.area", &cfg->flux_area));
  const int has_v = cmn_case_has(c, "imposed_flux.velocity"),
            has_q = cmn_case_has(c, "imposed_flux.flux");
  if (has_v == has_q)
    return cmn_case_fail(c, "imposed_flux",
                         "give exactly one of 'velocity' (bulk velocity Q/A, m/s) and 'flux' (Q)");
  if (has_v) {
    TRY(cmn_case_get_double(c, "imposed_flux.velocity", -INFINITY, INFINITY, &cfg->flux_velocity));
  } else {
    double q;
    TRY(cmn_case_get_double(c, "imposed_flux.flux", -INFINITY, INFINITY, &q));
    cfg->flux_velocity = q / cfg->flux_area;
  }
  TRY(cmn_case_opt_double(c, "imposed_flux.force0", 0.0, -INFINITY, INFINITY, &cfg->flux_force0));
  return 0;
}

int sph_config_read(struct sph_config *cfg, struct cmn_case *c, int dim) {
  memset(cfg, 0, sizeof *cfg);
  /* fluid */
  TRY(cmn_case_get_positive(c, "fluid.rho0", &cfg->rho0));
  TRY(cmn_case_get_positive(c, "fluid.c0", &cfg->c0));
  TRY(cmn_case_opt_double(c, "fluid.xi", 7.0, 1.0, 100.0, &cfg->xi));
  TRY(cmn_case_opt_double(c, "fluid.nu", 0.0, 0.0, INFINITY, &cfg->nu));
  TRY(opt_vector(c, "gravity", dim, cfg->gravity));
  /* initial state: a wave (read with the open boundaries below), or the fields */
  cfg->initial_wave = cmn_case_has(c, "initial.wave");
  if (cfg->initial_wave) {
    static const char *const others[] = {"initial.velocity", "initial.pressure", "initial.density",
                                         "initial.free_surface"};
    for (int i = 0; i < 4; i++)
      if (cmn_case_has(c, others[i]))
        return cmn_case_fail(c, others[i],
                             "initial.wave gives the free surface, velocity and pressure: "
                             "remove this key or the wave");
  } else {
    TRY(read_initial_fields(c, cfg, dim));
  }
  cfg->free_surface = NAN;
  if (cmn_case_has(c, "initial.free_surface"))
    TRY(cmn_case_get_double(c, "initial.free_surface", -INFINITY, INFINITY, &cfg->free_surface));
  const double g2 = cfg->gravity[0] * cfg->gravity[0] + cfg->gravity[1] * cfg->gravity[1] +
                    cfg->gravity[2] * cfg->gravity[2];
  if (cfg->hydrostatic && !(g2 > 0.0))
    return cmn_case_fail(c, "initial.pressure", "hydrostatic pressure needs a non-zero gravity");
  /* numerics */
  TRY(cmn_case_opt_double(c, "numerics.gradient_k", 1.0, 0.0, 2.0, &cfg->grad_k));
  static const char *const diffusions[] = {"none", "ferrari", "brezzi", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.diffusion", diffusions, SPH_DIFFUSION_FERRARI,
                          &cfg->diffusion));
  static const char *const speeds[] = {"max", "eta", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.diffusion_speed", speeds, SPH_DSPEED_MAX,
                          &cfg->diffusion_speed));
  TRY(cmn_case_opt_positive(c, "numerics.eta", 20.0, &cfg->eta));
  TRY(cmn_case_opt_double(c, "numerics.brezzi_lambda", 1.0, 0.0, INFINITY, &cfg->brezzi_lambda));
  static const char *const gcorr[] = {"none", "linear", "local", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.gravity_correction", gcorr, 2, &cfg->gravity_correction));
  static const char *const hydros[] = {"none", "full", "tangential", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.vertex_hydrostatic", hydros, SPH_VHYDRO_FULL,
                          &cfg->vertex_hydro));
  static const char *const impedances[] = {"none", "acoustic", "contact", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.wall_impedance", impedances, SPH_IMPEDANCE_CONTACT,
                          &cfg->wall_impedance));
  const int reach_given = cmn_case_has(c, "numerics.wall_impedance_reach"); /* before its default */
  TRY(cmn_case_opt_double(c, "numerics.wall_impedance_reach", 1.0, 1e-3, 4.0,
                          &cfg->wall_impedance_reach));
  if (cfg->wall_impedance != SPH_IMPEDANCE_CONTACT && reach_given)
    return cmn_case_fail(c, "numerics.wall_impedance_reach",
                         "applies to the contact form only (numerics.wall_impedance: contact)");
  TRY(cmn_case_opt_double(c, "numerics.artificial_viscosity", 0.0, 0.0, INFINITY,
                          &cfg->artificial_viscosity));
  static const char *const ograds[] = {"symmetric", "difference", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.open_gradient", ograds, 0, &cfg->open_gradient_difference));
  static const char *const pulls[] = {"radial", "normal", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.no_pull", pulls, 0, &cfg->no_pull_normal));
  static const char *const lones[] = {"eos", "ambient", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.lone_particle", lones, 0, &cfg->lone_ambient));
  const int fraction_given = cmn_case_has(c, "numerics.lone_fraction"); /* before its default */
  TRY(cmn_case_opt_double(c, "numerics.lone_fraction", 0.35, 1e-3, 0.999, &cfg->lone_fraction));
  if (!cfg->lone_ambient && fraction_given)
    return cmn_case_fail(c, "numerics.lone_fraction",
                         "applies with numerics.lone_particle: ambient only");
  static const char *const vmasses[] = {"constant", "density", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.wall_vertex_mass", vmasses, 0,
                          &cfg->wall_vertex_mass_density));
  static const char *const gammas[] = {"analytic", "dynamic", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.gamma", gammas, 0, &cfg->gamma_dynamic));
  static const char *const vvols[] = {"geometric", "fitted", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.vertex_volume", vvols, SPH_VVOL_FITTED,
                          &cfg->vertex_volume));
  TRY(cmn_case_opt_double(c, "numerics.vertex_layer", 0.5, 0.0, 1.0, &cfg->vertex_layer));
  TRY(cmn_case_opt_long(c, "repack.steps", 0, 0, 10000000L, &cfg->repack_steps));
  TRY(cmn_case_opt_double(c, "repack.perturbation", 0.0, 0.0, 0.25, &cfg->repack_perturbation));
  TRY(cmn_case_opt_bool(c, "repack.layer_equilibrium", 0, &cfg->layer_equilibrium));
  TRY(cmn_case_opt_double(c, "repack.settle", 0.0, 0.0, 1e4, &cfg->settle));
  TRY(opt_fraction(c, "numerics.cfl", 0.3, &cfg->cfl));
  TRY(opt_fraction(c, "numerics.viscous_factor", 0.125, &cfg->viscous_factor));
  TRY(opt_fraction(c, "numerics.force_factor", 0.25, &cfg->force_factor));
  TRY(opt_fraction(c, "numerics.gamma_factor", 0.05, &cfg->gamma_factor));
  TRY(opt_fraction(c, "numerics.skin", 0.2, &cfg->skin_over_h));
  static const char *const rebuilds[] = {"when_needed", "every_step", NULL};
  TRY(cmn_case_opt_choice(c, "numerics.list_rebuild", rebuilds, SPH_LISTS_WHEN_NEEDED,
                          &cfg->list_rebuild));
  cfg->dt_max = INFINITY;
  if (cmn_case_has(c, "numerics.dt_max"))
    TRY(cmn_case_get_positive(c, "numerics.dt_max", &cfg->dt_max));
  const double band[2] = {0.5, 1.5};
  TRY(cmn_case_opt_doubles(c, "numerics.density_band", 2, band, cfg->density_band));
  if (!(cfg->density_band[0] > 0.0 && cfg->density_band[0] < 1.0 && cfg->density_band[1] > 1.0))
    return cmn_case_fail(c, "numerics.density_band", "expected [lo, hi] with 0 < lo < 1 < hi");
  /* time and output */
  TRY(cmn_case_get_positive(c, "time.end", &cfg->t_end));
  TRY(cmn_case_opt_positive(c, "time.output_interval", cfg->t_end / 100.0, &cfg->output_interval));
  /* each output is a VTU file pair: more than 1e6 of them is a typo (1e-300), not a wish */
  if (cfg->t_end / cfg->output_interval > SPH_MAX_OUTPUTS)
    return cmn_case_fail(c, "time.output_interval",
                         "%g s would write %.3g outputs up to time.end = %g s; at most %g: "
                         "expected at least %g s",
                         cfg->output_interval, cfg->t_end / cfg->output_interval, cfg->t_end,
                         (double)SPH_MAX_OUTPUTS, cfg->t_end / SPH_MAX_OUTPUTS);
  TRY(cmn_case_opt_long(c, "time.diagnostics_every", 1, 1, 1000000000L, &cfg->diagnostics_every));
  TRY(cmn_case_opt_long(c, "time.checkpoint_steps", 0, 0, 1000000000L, &cfg->checkpoint_steps));
  TRY(cmn_case_opt_double(c, "time.checkpoint_minutes", 0.0, 0.0, INFINITY,
                          &cfg->checkpoint_minutes));
  TRY(cmn_case_opt_long(c, "time.max_steps", 0, 0, 1000000000000L, &cfg->max_steps));
  /* probes and forces */
  TRY(read_points(c, "probes.pressure", dim, cfg->probes, &cfg->nprobes));
  TRY(read_points(c, "probes.gauges", dim, cfg->gauges, &cfg->ngauges));
  TRY(read_forces(c, cfg));
  /* vertex values and imposed flux (docs/sph-robin.md) */
  TRY(read_vertex_values(c, cfg));
  TRY(read_imposed_flux(c, cfg, dim));
  /* open boundaries (sabre/sph_open.h) */
  struct rmn_eos eos;
  if (rmn_eos_init(&eos, cfg->rho0, cfg->c0, cfg->xi) != RMN_SUCCESS)
    return cmn_case_fail(c, "fluid", "invalid equation of state");
  TRY(sph_open_config_read(&cfg->open, c, dim, cfg->gravity, &eos));
  /* the settling run and the layer equilibrium are for closed set-ups at rest: open boundaries
   * would create and delete particles and the imposed flux would drive a flow before the start */
  const char *driven = cfg->open.ngroups > 0                 ? "open_boundaries"
                       : cfg->flux_method != SPH_FLUXSEL_OFF ? "imposed_flux"
                                                             : NULL;
  if (cfg->settle > 0.0 && driven)
    return cmn_case_fail(c, "repack.settle",
                         "a settling run is for closed domains at rest: not with %s; remove the "
                         "key or set it to 0",
                         driven);
  /* the layer equilibrium balances gravity in a fluid at rest with horizontal layers */
  if (cfg->layer_equilibrium && (!(g2 > 0.0) || cfg->initial_wave || driven))
    return cmn_case_fail(c, "repack.layer_equilibrium",
                         "the layer equilibrium of water at rest needs %s%s; remove the key or "
                         "set it to false",
                         !(g2 > 0.0) ? "a non-zero gravity" : "no ",
                         !(g2 > 0.0)         ? ""
                         : cfg->initial_wave ? "initial.wave"
                                             : driven);
  if (cfg->initial_wave)
    TRY(sph_open_wave_read(c, "initial.wave", dim, cfg->gravity, &eos, &cfg->wave));
  return 0;
}

/* One initial expression over the fluid: the first position where it is not finite, or not in
 * range, is reported at the key's file and line. */
static int check_expr(struct cmn_case *c, const char *path, const char *text, int dim,
                      const struct sph_parts *f, double lo, const char *what, const char *unit) {
  static const char *const xyz[] = {"x", "y", "z"};
  if (!text[0]) return 0;
  char err[512];
  struct cmn_expr *e = cmn_expr_compile(text, dim, xyz, err, sizeof err);
  if (!e) return cmn_case_fail(c, path, "expected a number or an expression: %s", err);
  int rc = 0;
  for (size_t a = 0; a < f->n && rc == 0; a++) {
    const double x[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
    const double v = cmn_expr_eval(e, x);
    if (!isfinite(v) || !(v > lo))
      rc = cmn_case_fail(c, path, "'%s' is %g %s at the fluid particle (%g, %g, %g): expected %s",
                         text, v, unit, x[0], x[1], x[2], what);
  }
  cmn_expr_free(e);
  return rc;
}

int sph_config_check_initial(const struct sph_config *cfg, struct cmn_case *c,
                             const struct sph_system *s) {
  const struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  struct rmn_eos eos;
  if (rmn_eos_init(&eos, cfg->rho0, cfg->c0, cfg->xi) != RMN_SUCCESS) return 0; /* read checked */
  char above[128];
  const double pmin = rmn_eos_min_pressure(&eos);
  snprintf(above, sizeof above, "a finite pressure above the EOS's minimum %g Pa", pmin);
  TRY(check_expr(c, "initial.pressure", cfg->p0_expr, s->dim, f, pmin, above, "Pa"));
  TRY(check_expr(c, "initial.density", cfg->rho0_expr, s->dim, f, 0.0, "a finite positive density",
                 "kg/m^3"));
  for (int i = 0; i < s->dim; i++) {
    char q[64];
    snprintf(q, sizeof q, "initial.velocity[%d]", i);
    TRY(check_expr(c, q, cfg->u0_expr[i], s->dim, f, -INFINITY, "a finite velocity", "m/s"));
  }
  return 0;
}

int sph_config_check_probes(const struct sph_config *cfg, struct cmn_case *c,
                            const struct sph_system *s) {
  if (cfg->nprobes + cfg->ngauges == 0) return 0;
  const int dim = s->dim;
  const double h = s->h;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int kind = 0; kind < SPH_NKINDS; kind++) {
    const struct sph_parts *p = &s->part[kind];
    for (size_t i = 0; i < p->n; i++)
      for (int k = 0; k < dim; k++) {
        lo[k] = fmin(lo[k], p->x[k][i]);
        hi[k] = fmax(hi[k], p->x[k][i]);
      }
  }
  for (int k = 0; k < dim; k++) {
    lo[k] -= h;
    hi[k] += h;
  }
  char box[256];
  int len = snprintf(box, sizeof box, "the fluid and the walls (widened by h = %g m) span", h);
  for (int k = 0; k < dim && len > 0 && (size_t)len < sizeof box; k++)
    len += snprintf(box + len, sizeof box - (size_t)len, "%s %c %g ... %g m", k ? "," : "",
                    "xyz"[k], lo[k], hi[k]);
  for (int i = 0; i < cfg->nprobes; i++) {
    const double *x = cfg->probes[i];
    for (int k = 0; k < dim; k++) {
      if (s->domain.periodic[k] || (x[k] >= lo[k] && x[k] <= hi[k])) continue;
      char q[64];
      snprintf(q, sizeof q, "probes.pressure[%d]", i);
      return cmn_case_fail(c, q, "the point %c = %g m is outside the case's domain: %s", "xyz"[k],
                           x[k], box);
    }
  }
  /* A gauge's vertical line x + t up must cross the box: the slabs' parameter intervals meet. */
  double up[3];
  sph_gauge_up(cfg->gravity, up);
  for (int i = 0; i < cfg->ngauges; i++) {
    const double *x = cfg->gauges[i];
    double t0 = -INFINITY, t1 = INFINITY;
    for (int k = 0; k < dim; k++) {
      if (s->domain.periodic[k]) continue;
      if (fabs(up[k]) < 1e-12) {
        if (!(x[k] >= lo[k] && x[k] <= hi[k])) t0 = INFINITY;
        continue;
      }
      const double a = (lo[k] - x[k]) / up[k], b = (hi[k] - x[k]) / up[k];
      t0 = fmax(t0, fmin(a, b));
      t1 = fmin(t1, fmax(a, b));
    }
    if (t0 <= t1) continue;
    char q[64];
    snprintf(q, sizeof q, "probes.gauges[%d]", i);
    return cmn_case_fail(c, q,
                         "the vertical line through (%g, %g, %g) m (along -g) misses the case's "
                         "domain: %s",
                         x[0], x[1], x[2], box);
  }
  return 0;
}
