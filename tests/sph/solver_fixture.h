/* Small systems for the solver tests: a 2D fluid lattice, with or without the walls of a channel
 * periodic in x, and a configuration with the documented defaults. Header-only (each test is one
 * program). */
#ifndef SABRE_TESTS_SPH_SOLVER_FIXTURE_H
#define SABRE_TESTS_SPH_SOLVER_FIXTURE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geometry/geometry.h"
#include "sabre/common.h"
#include "sabre/sph.h"
#include "sabre/sph_open.h"
#include "sabre/sph_solver.h"
#include "testutil.h"

/* The system of a case given as YAML text (its geometry section; the case and geometry are freed).
 */
static inline void fixture_system_from_yaml(struct sph_system *s, const char *text) {
  char err[512];
  struct cmn_case *c = cmn_case_parse(text, "test.yaml", err, sizeof err);
  if (c == NULL) fail_msg("%s", err);
  struct sph_geometry g;
  sph_geometry_read(&g, c);
  sph_system_from_geometry(s, &g);
  sph_geometry_free(&g);
  cmn_case_free(c);
}

/* A flow at 0.5 m/s through a 2D box 0.4 m × 0.3 m open at both ends (velocity inlet on x−,
 * outlet at p = 0 on x+), Δr = 0.025 m: particles created at the inlet, deleted at the outlet
 * (tests/sph/test_open_mass.c, tests/sph/test_list_reuse.c). */
#define FIXTURE_THROUGH_CASE                                                       \
  "geometry:\n"                                                                    \
  "  dimension: 2\n"                                                               \
  "  dr: 0.025\n"                                                                  \
  "  first_row: 1\n"                                                               \
  "  walls: [{type: box, lo: [0, 0], hi: [0.4, 0.3], open: [x-, x+]}]\n"           \
  "  fluid: [{type: box, lo: [0, 0], hi: [0.4, 0.3]}]\n"                           \
  "fluid: {rho0: 1000, c0: 20}\n"                                                  \
  "initial: {velocity: [0.5, 0]}\n"                                                \
  "time: {end: 1}\n"                                                               \
  "open_boundaries:\n"                                                             \
  "  - {name: in, wall: 0, faces: [x-], impose: velocity, normal_velocity: 0.5}\n" \
  "  - {name: out, wall: 0, faces: [x+], impose: pressure, pressure: 0}\n"

/* A solver from a whole case text with its force and open-boundary groups resolved against the
 * mesh, as `sabre-sph run` sets it up (fatal mode: the case is good). Free with
 * fixture_solver_destroy(). */
static inline struct sph_solver *fixture_solver_from_case(const char *text) {
  char err[512];
  struct cmn_case *c = cmn_case_parse(text, "case.yaml", err, sizeof err);
  if (!c) fail_msg("%s", err);
  struct sph_geometry g;
  sph_geometry_read(&g, c);
  struct sph_config *cfg = calloc(1, sizeof *cfg);
  sph_config_read(cfg, c, g.dim);
  sph_open_check_mesh(&cfg->open, c, &g.walls);
  cmn_case_check_unused(c);
  struct sph_system s;
  sph_system_from_geometry(&s, &g);
  struct sph_solver *sv = calloc(1, sizeof *sv);
  /* segment j is mesh element j: the mesh's own wall index and element number of each */
  sph_solver_init(sv, cfg, &s, g.walls.source, g.walls.source_index);
  free(cfg);
  sph_system_free(&s);
  sph_geometry_free(&g);
  cmn_case_free(c);
  return sv;
}

static inline void fixture_solver_destroy(struct sph_solver *sv) {
  sph_solver_free(sv);
  free(sv);
}

/* Parse base + extra as case.yaml and read the solver's sections in non-fatal mode; with extra
 * "--set key=value" the override is applied to base instead. Returns sph_config_read()'s rc (or
 * the unused-key check's) and leaves the case's message in msg. */
static inline int fixture_read_case(const char *base, const char *extra, struct sph_config *cfg,
                                    char *msg, size_t len) {
  const int is_set = strncmp(extra, "--set ", 6) == 0;
  char text[4096];
  snprintf(text, sizeof text, "%s%s", base, is_set ? "" : extra);
  char err[512];
  struct cmn_case *c = cmn_case_parse(text, "case.yaml", err, sizeof err);
  assert_non_null(c);
  cmn_case_set_fatal(c, 0);
  int rc = is_set ? cmn_case_set(c, extra + 6) : 0;
  if (rc == 0) rc = sph_config_read(cfg, c, 2);
  if (rc == 0) {
    cmn_case_mark_used(c, "geometry");
    rc = cmn_case_check_unused(c);
  }
  snprintf(msg, len, "%s", cmn_case_error(c));
  cmn_case_free(c);
  return rc;
}

/* The defaults of docs/sph-case-file.md (what sph_config_read() gives for a minimal case). */
static inline void fixture_config(struct sph_config *cfg) {
  memset(cfg, 0, sizeof *cfg);
  cfg->rho0 = 1000.0;
  cfg->c0 = 20.0;
  cfg->xi = 7.0;
  cfg->nu = 0.0;
  cfg->free_surface = NAN;
  cfg->grad_k = 1.0;
  cfg->diffusion = SPH_DIFFUSION_FERRARI;
  cfg->diffusion_speed = SPH_DSPEED_MAX;
  cfg->eta = 20.0;
  cfg->brezzi_lambda = 1.0;
  cfg->gravity_correction = 2;
  cfg->vertex_hydro = SPH_VHYDRO_FULL;
  cfg->vertex_volume = SPH_VVOL_FITTED;
  cfg->vertex_layer = 0.5;
  cfg->repack_steps = 0;
  cfg->cfl = 0.3;
  cfg->viscous_factor = 0.125;
  cfg->force_factor = 0.25;
  cfg->gamma_factor = 0.05;
  cfg->skin_over_h = 0.2;
  cfg->list_rebuild = SPH_LISTS_WHEN_NEEDED;
  cfg->open_gradient_difference = 0;
  cfg->dt_max = INFINITY;
  cfg->wall_impedance = SPH_IMPEDANCE_CONTACT; /* the case file's defaults */
  cfg->wall_impedance_reach = 1.0;
  cfg->density_band[0] = 0.5;
  cfg->density_band[1] = 1.5;
  cfg->t_end = 1.0;
  cfg->output_interval = 0.01;
  cfg->diagnostics_every = 1;
}

enum fixture_walls { FIX_NONE = 0, FIX_CHANNEL = 1, FIX_PERIODIC = 2 };

/*
 * nx × ny fluid particles at ((i + 1/2) dr, (j + 1/2) dr), h = h_over_dr · dr.
 * FIX_NONE: no walls, not periodic (an open lattice). FIX_CHANNEL: walls at y = 0 and y = ny dr,
 * periodic in x. FIX_PERIODIC: periodic in x and y, no walls.
 */
static inline void fixture_lattice_offset(struct sph_system *s, int nx, int ny, double dr,
                                          double h_over_dr, enum fixture_walls walls,
                                          double y_offset);
static inline void fixture_lattice(struct sph_system *s, int nx, int ny, double dr,
                                   double h_over_dr, enum fixture_walls walls) {
  fixture_lattice_offset(s, nx, ny, dr, h_over_dr, walls, 0.5);
}

/* The same with the rows at y = (j + y_offset) dr, j = 0..ny−1 (walls at 0 and (ny − 1 + 2
 * y_offset) dr): y_offset = 1 puts the first row one Δr from the wall. */
static inline void fixture_lattice_offset(struct sph_system *s, int nx, int ny, double dr,
                                          double h_over_dr, enum fixture_walls walls,
                                          double y_offset) {
  sph_system_init(s, 2);
  s->dr = dr;
  s->h = h_over_dr * dr;
  s->domain.dim = 2;
  s->domain.lo[0] = 0.0;
  s->domain.lo[1] = 0.0;
  s->domain.hi[0] = nx * dr;
  s->domain.hi[1] = (ny - 1 + 2 * y_offset) * dr;
  s->domain.periodic[0] = walls != FIX_NONE;
  s->domain.periodic[1] = walls == FIX_PERIODIC;
  if (walls == FIX_CHANNEL) {
    struct sph_mesh m;
    sph_mesh_init(&m, 2);
    const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {nx * dr, s->domain.hi[1], 0.0};
    sph_mesh_box(&m, lo, hi, dr, 0, 3u, sph_mesh_add_source(&m, "channel"));
    sph_mesh_merge_vertices(&m, 1e-9 * dr);
    sph_mesh_refine(&m, dr);
    geom_mesh_identify_periodic(&m, &s->domain, 1e-6 * dr);
    sph_system_add_walls(s, &m);
    sph_mesh_free(&m);
  }
  size_t f0 = sph_system_append(s, SPH_KIND_FLUID, (size_t)nx * (size_t)ny);
  struct sph_parts *f = &s->part[SPH_KIND_FLUID];
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      size_t a = f0 + (size_t)j * (size_t)nx + (size_t)i;
      f->x[0][a] = (i + 0.5) * dr;
      f->x[1][a] = (j + y_offset) * dr;
    }
}

/* A closed tank [0, width] × [0, height] in 2D with its walls meshed at dr (box edges 1 bottom, 2
 * right, 3 top, 4 left) and nx × ny fluid particles at ((i + 1) dr, (j + 1) dr): first row and
 * column Δr from the walls. The caller owns *s (sph_system_free). */
static inline void fixture_tank(struct sph_system *s, double width, double height, double dr,
                                int nx, int ny) {
  sph_system_init(s, 2);
  s->dr = dr;
  s->h = 2 * dr;
  s->domain.dim = 2;
  s->domain.hi[0] = width;
  s->domain.hi[1] = height;
  struct sph_mesh m;
  sph_mesh_init(&m, 2);
  const double lo[3] = {0, 0, 0}, hi[3] = {width, height, 0};
  sph_mesh_box(&m, lo, hi, dr, 0, 0, sph_mesh_add_source(&m, "box"));
  sph_mesh_refine(&m, dr);
  sph_system_add_walls(s, &m);
  sph_mesh_free(&m);
  size_t f0 = sph_system_append(s, SPH_KIND_FLUID, (size_t)(nx * ny));
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      s->part[SPH_KIND_FLUID].x[0][f0 + (size_t)(j * nx + i)] = (i + 1) * dr;
      s->part[SPH_KIND_FLUID].x[1][f0 + (size_t)(j * nx + i)] = (j + 1) * dr;
    }
}

#endif
