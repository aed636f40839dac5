/*
 * `sabre-sph scalar CASE.yaml [--set key=value]... [--output DIR]`: the wave equation
 * u_tt = c² Lap u on fixed particles (sph/src/scalar/scalar.c). Reads the `geometry` section
 * (sph_geometry_read) and the `scalar`, `time` and `output` sections (docs/sph-scalar.md), then
 * writes used_case.yaml, vertices.csv, series.csv (vertex values, the reference and the errors
 * at every step) and profiles.csv (every particle at the requested times) into DIR.
 */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "sabre/common.h"
#include "sabre/sph_analytic.h"
#include "sabre/sph_scalar.h"

#define PI 3.14159265358979323846
#define MAX_COEF 16
#define MAX_SERIES_VERTICES 64
#define MAX_PROFILE_TIMES 256

static const char usage[] =
    "usage: sabre-sph scalar CASE.yaml [--set key=value]... [--output DIR]\n"
    "Wave equation u_tt = c^2 Lap u on fixed particles with Robin/Neumann/Dirichlet walls.\n"
    "See docs/sph-scalar.md for the case-file keys and the outputs.\n";

/* ------------------------------------------------------------------------------------------ */
/* Initial profiles                                                                            */
/* ------------------------------------------------------------------------------------------ */

enum profile_type { PROFILE_POLYNOMIAL = 0, PROFILE_SIN = 1, PROFILE_COS = 2 };
static const char *const profile_types[] = {"polynomial", "sin", "cos", NULL};
static const char *const axis_names[] = {"x", "y", "z", NULL};

struct profile {
  int type, axis, ncoef;
  double coef[MAX_COEF];
  double amplitude, wavelength;
};

static void read_profile(struct cmn_case *c, const char *path, int dim, struct profile *p) {
  char k[256];
  memset(p, 0, sizeof *p);
  p->ncoef = 1; /* absent: u = 0 */
  if (!cmn_case_has(c, path)) return;
  cmn_case_is_map(c, path);
  snprintf(k, sizeof k, "%s.type", path);
  cmn_case_get_choice(c, k, profile_types, &p->type);
  snprintf(k, sizeof k, "%s.axis", path);
  cmn_case_opt_choice(c, k, axis_names, 0, &p->axis);
  if (p->axis >= dim) cmn_case_fail(c, k, "no such axis in %dD", dim);
  if (p->type == PROFILE_POLYNOMIAL) {
    snprintf(k, sizeof k, "%s.coefficients", path);
    cmn_case_get_doubles(c, k, 0, MAX_COEF, p->coef, &p->ncoef);
  } else {
    snprintf(k, sizeof k, "%s.amplitude", path);
    cmn_case_opt_double(c, k, 1.0, -INFINITY, INFINITY, &p->amplitude);
    snprintf(k, sizeof k, "%s.wavelength", path);
    cmn_case_get_positive(c, k, &p->wavelength);
  }
}

static double profile_eval(const struct profile *p, const double *x) {
  const double s = x[p->axis];
  if (p->type == PROFILE_POLYNOMIAL) {
    double v = 0.0;
    for (int i = p->ncoef - 1; i >= 0; i--) v = v * s + p->coef[i];
    return v;
  }
  const double arg = 2.0 * PI * s / p->wavelength;
  return p->amplitude * (p->type == PROFILE_SIN ? sin(arg) : cos(arg));
}

/* ------------------------------------------------------------------------------------------ */
/* Case                                                                                        */
/* ------------------------------------------------------------------------------------------ */

enum reference_type { REF_NONE = 0, REF_ROBIN_WAVE = 1 };
static const char *const reference_types[] = {"none", "robin_wave", NULL};
static const char *const bc_types[] = {"robin", "neumann", "dirichlet", NULL};

struct bc_entry {
  struct sph_scalar_bc bc;
  long wall; /* −1: every wall */
  int nedges;
  long *edges;
};

struct scalar_case {
  double c, phi;
  struct profile u0, ut0;
  int nbc;
  struct bc_entry *bc;
  int reference;
  long terms;
  double t_end, dt, cfl;
  long power_iterations, series_every;
  int nprofiles;
  double profile_times[MAX_PROFILE_TIMES];
};

static void read_boundaries(struct cmn_case *c, struct scalar_case *sc, int nwalls) {
  int n = cmn_case_seq_length(c, "scalar.boundaries");
  sc->nbc = n > 0 ? n : 0;
  sc->bc = cmn_calloc((size_t)sc->nbc + 1, sizeof *sc->bc);
  for (int i = 0; i < sc->nbc; i++) {
    struct bc_entry *e = &sc->bc[i];
    char p[128], k[192];
    snprintf(p, sizeof p, "scalar.boundaries[%d]", i);
    cmn_case_is_map(c, p);
    sph_scalar_bc_init(&e->bc);
    snprintf(k, sizeof k, "%s.wall", p);
    cmn_case_opt_long(c, k, -1, -1, nwalls - 1, &e->wall);
    snprintf(k, sizeof k, "%s.edges", p);
    e->nedges = cmn_case_seq_length(c, k);
    if (e->nedges > 0) {
      if (e->wall < 0) cmn_case_fail(c, k, "edges need a wall (the element numbers are per wall)");
      e->edges = cmn_malloc((size_t)e->nedges * sizeof *e->edges);
      for (int j = 0; j < e->nedges; j++) {
        char q[224];
        snprintf(q, sizeof q, "%s[%d]", k, j);
        cmn_case_get_long(c, q, 1, 1000000000L, &e->edges[j]);
      }
    }
    int type;
    snprintf(k, sizeof k, "%s.type", p);
    cmn_case_get_choice(c, k, bc_types, &type);
    long order;
    snprintf(k, sizeof k, "%s.order", p);
    cmn_case_opt_long(c, k, 1, 1, SPH_ROBIN_M_MAX, &order);
    e->bc.robin.m = (int)order;
    e->bc.order = (int)order;
    if (type == 0) { /* robin */
      double mu[3];
      snprintf(k, sizeof k, "%s.mu", p);
      cmn_case_get_doubles(c, k, 3, 3, mu, NULL);
      if (mu[1] == 0.0)
        cmn_case_fail(c, k, "mu2 must not be 0 (a Dirichlet wall is type: dirichlet)");
      e->bc.robin.mu1 = mu[0];
      e->bc.robin.mu2 = mu[1];
      e->bc.robin.mu3 = mu[2];
    } else if (type == 1) { /* neumann: (0, 1, g) */
      snprintf(k, sizeof k, "%s.gradient", p);
      cmn_case_opt_double(c, k, 0.0, -INFINITY, INFINITY, &e->bc.robin.mu3);
    } else {
      e->bc.type = SPH_SCALAR_DIRICHLET;
      snprintf(k, sizeof k, "%s.value", p);
      cmn_case_opt_double(c, k, 0.0, -INFINITY, INFINITY, &e->bc.value);
    }
  }
}

static void read_case(struct cmn_case *c, struct scalar_case *sc, int dim, int nwalls) {
  memset(sc, 0, sizeof *sc);
  cmn_case_is_map(c, "scalar");
  cmn_case_opt_positive(c, "scalar.c", 1.0, &sc->c);
  const char *layer;
  cmn_case_opt_string(c, "scalar.vertex_layer", "auto", &layer);
  if (strcmp(layer, "auto") == 0) {
    sc->phi = -1.0;
  } else if (cmn_parse_double(layer, &sc->phi) != 0 || sc->phi < 0.0) {
    cmn_case_fail(c, "scalar.vertex_layer", "expected 'auto' or a number >= 0, got '%s'", layer);
  }
  read_profile(c, "scalar.initial.u", dim, &sc->u0);
  read_profile(c, "scalar.initial.u_t", dim, &sc->ut0);
  read_boundaries(c, sc, nwalls);
  cmn_case_opt_choice(c, "scalar.reference.type", reference_types, REF_NONE, &sc->reference);
  cmn_case_opt_long(c, "scalar.reference.terms", 1000, 1, 1000000, &sc->terms);
  if (sc->reference == REF_ROBIN_WAVE && (dim != 1 || sc->c != 1.0))
    cmn_case_fail(c, "scalar.reference.type",
                  "robin_wave is the series M(78) for d = 1 and c = 1 (here d = %d, c = %g)", dim,
                  sc->c);
  cmn_case_get_positive(c, "time.end", &sc->t_end);
  cmn_case_opt_double(c, "time.dt", 0.0, 0.0, INFINITY, &sc->dt);
  cmn_case_opt_double(c, "time.cfl", 0.5, 1e-6, 1.0, &sc->cfl);
  cmn_case_opt_long(c, "time.power_iterations", 300, 1, 100000, &sc->power_iterations);
  cmn_case_opt_long(c, "output.series_every", 1, 1, 1000000000L, &sc->series_every);
  sc->nprofiles = cmn_case_seq_length(c, "output.profile_times");
  if (sc->nprofiles > 0) {
    cmn_case_get_doubles(c, "output.profile_times", 0, MAX_PROFILE_TIMES, sc->profile_times,
                         &sc->nprofiles);
    for (int i = 0; i < sc->nprofiles; i++)
      if (!(sc->profile_times[i] > (i ? sc->profile_times[i - 1] : 0.0)) ||
          sc->profile_times[i] > sc->t_end)
        cmn_case_fail(c, "output.profile_times",
                      "times must increase strictly within (0, time.end = %g]", sc->t_end);
  } else {
    sc->nprofiles = 0;
  }
}

/* Boundary group of every segment: the first entry naming its wall (and element). */
static int *segment_groups(const struct sph_geometry *g, struct cmn_case *c,
                           const struct scalar_case *sc) {
  const struct sph_mesh *m = &g->walls;
  int *grp = cmn_malloc((m->nelem + 1) * sizeof *grp);
  int nw = cmn_case_seq_length(c, "geometry.walls");
  for (size_t e = 0; e < m->nelem; e++) {
    grp[e] = -1;
    for (int i = 0; i < sc->nbc && grp[e] < 0; i++) {
      const struct bc_entry *b = &sc->bc[i];
      if (b->wall >= 0 && (m->nsources != nw || b->wall != m->source[e])) continue;
      int match = b->nedges == 0;
      for (int j = 0; j < b->nedges && !match; j++) match = b->edges[j] == m->source_index[e];
      if (match) grp[e] = i;
    }
    if (grp[e] < 0) {
      const double *x = m->vert[m->elem[e][0]];
      cmn_input_error(
          "%s: scalar.boundaries: no entry covers element %ld of %s (at %g, %g, %g); add one "
          "(an entry without `wall` covers every wall)",
          cmn_case_name(c), m->source_index[e], m->sources[m->source[e]], x[0], x[1], x[2]);
    }
  }
  return grp;
}

/* ------------------------------------------------------------------------------------------ */
/* Reference solution                                                                          */
/* ------------------------------------------------------------------------------------------ */

struct reference {
  int type;
  struct sph_robin_wave wave;
};

static int reference_eval(const struct reference *r, const double *x, double t, double *u,
                          double *ut) {
  if (u) *u = NAN;
  if (ut) *ut = NAN;
  if (r->type == REF_NONE) return 0;
  sph_robin_wave_eval(&r->wave, x[0], t, u, ut, NULL);
  return 1;
}

/* The reference holds for its own initial data only: compare them on the particles. */
static void check_reference_data(const struct reference *r, const struct sph_scalar *s,
                                 const char *case_name) {
  const struct sph_parts *f = &s->sys.part[SPH_KIND_FLUID];
  double du = 0.0, dut = 0.0, scale = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    const double x[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
    double u, ut;
    reference_eval(r, x, 0.0, &u, &ut);
    du = fmax(du, fabs(u - s->u[SPH_KIND_FLUID][a]));
    dut = fmax(dut, fabs(ut - s->ut[a]));
    scale = fmax(scale, fmax(fabs(u), fabs(ut)));
  }
  if (du > 1e-6 * fmax(scale, 1.0) || dut > 1e-6 * fmax(scale, 1.0))
    cmn_input_error(
        "%s: scalar.reference.type: the initial data differ from the reference's at t = 0 "
        "(max |u - u_ref| = %g, max |u_t - u_t,ref| = %g); robin_wave needs u = 0, "
        "u_t = sin(2 pi x) on [0, 1]",
        case_name, du, dut);
  const struct sph_parts *v = &s->sys.part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++)
    if (!(fabs(v->x[0][i]) < 1e-12 || fabs(v->x[0][i] - 1.0) < 1e-12))
      cmn_input_error(
          "%s: scalar.reference.type: robin_wave needs walls at x = 0 and x = 1 "
          "(vertex at x = %g)",
          case_name, v->x[0][i]);
}

/* ------------------------------------------------------------------------------------------ */
/* Outputs                                                                                     */
/* ------------------------------------------------------------------------------------------ */

static struct cmn_csv *open_csv(const char *dir, const char *name, int ncols, char **names) {
  char *path = sph_cli_join(dir, name);
  struct cmn_csv *csv = cmn_csv_open(path, ncols, (const char *const *)names);
  if (!csv) cmn_input_error("cannot write '%s'", path);
  free(path);
  return csv;
}

static void write_vertices(const char *dir, const struct sph_scalar *s) {
  static const char *const names[] = {"vertex", "x",   "y",     "z",     "n_x",
                                      "n_y",    "n_z", "group", "volume"};
  struct cmn_csv *csv = open_csv(dir, "vertices.csv", 9, (char **)names);
  const struct sph_parts *v = &s->sys.part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++) {
    const double row[9] = {(double)i,       v->x[0][i],      v->x[1][i],
                           v->x[2][i],      v->normal[0][i], v->normal[1][i],
                           v->normal[2][i], s->vert_bc[i],   v->mass[i] / v->rho[i]};
    cmn_csv_row(csv, row);
  }
  if (cmn_csv_close(csv)) cmn_error("cannot write %s/vertices.csv", dir);
}

struct series {
  struct cmn_csv *csv;
  int per_vertex, ref;
  int ncols;
  double *row;
  /* time integral of err_mean (trapezoid), max of err, max |u_ref| at the vertices */
  double t_last, e_last, integral, e_max, ref_max;
  long rows;
};

static void series_open(struct series *sr, const char *dir, const struct sph_scalar *s, int ref) {
  const size_t nv = s->sys.part[SPH_KIND_VERTEX].n;
  memset(sr, 0, sizeof *sr);
  sr->per_vertex = nv <= MAX_SERIES_VERTICES;
  sr->ref = ref;
  const int npv = sr->per_vertex ? (int)nv : 0;
  sr->ncols = 1 + npv * (ref ? 3 : 1) + (ref ? 2 : 0);
  char **names = cmn_malloc((size_t)sr->ncols * sizeof *names);
  int k = 0;
  names[k++] = strdup("time");
  for (int i = 0; i < npv; i++) {
    names[k] = cmn_malloc(32);
    snprintf(names[k++], 32, "u_v%d", i);
  }
  if (ref) {
    for (int i = 0; i < npv; i++) {
      names[k] = cmn_malloc(32);
      snprintf(names[k++], 32, "ref_v%d", i);
    }
    for (int i = 0; i < npv; i++) {
      names[k] = cmn_malloc(32);
      snprintf(names[k++], 32, "err_v%d", i);
    }
    names[k++] = strdup("err_mean");
    names[k++] = strdup("err_max");
  }
  sr->csv = open_csv(dir, "series.csv", sr->ncols, names);
  for (int i = 0; i < sr->ncols; i++) free(names[i]);
  free(names);
  sr->row = cmn_malloc((size_t)sr->ncols * sizeof *sr->row);
}

static void series_write(struct series *sr, const struct sph_scalar *s, const struct reference *r) {
  const struct sph_parts *v = &s->sys.part[SPH_KIND_VERTEX];
  const size_t nv = v->n;
  const int npv = sr->per_vertex ? (int)nv : 0;
  int k = 0;
  sr->row[k++] = s->time;
  for (int i = 0; i < npv; i++) sr->row[k++] = s->u[SPH_KIND_VERTEX][i];
  if (sr->ref) {
    double sum = 0.0, emax = 0.0;
    for (size_t i = 0; i < nv; i++) {
      const double x[3] = {v->x[0][i], v->x[1][i], v->x[2][i]};
      double u;
      reference_eval(r, x, s->time, &u, NULL);
      const double e = s->u[SPH_KIND_VERTEX][i] - u;
      sum += fabs(e);
      emax = fmax(emax, fabs(e));
      sr->ref_max = fmax(sr->ref_max, fabs(u));
      if ((int)i < npv) {
        sr->row[k + (int)i] = u;
        sr->row[k + npv + (int)i] = e;
      }
    }
    k += 2 * npv;
    const double mean = nv ? sum / (double)nv : 0.0;
    sr->row[k++] = mean;
    sr->row[k++] = emax;
    if (sr->rows > 0) sr->integral += 0.5 * (mean + sr->e_last) * (s->time - sr->t_last);
    sr->t_last = s->time;
    sr->e_last = mean;
    sr->e_max = fmax(sr->e_max, emax);
  }
  sr->rows++;
  if (cmn_csv_row(sr->csv, sr->row)) cmn_error("cannot write series.csv");
}

static void profiles_write(struct cmn_csv *csv, const struct sph_scalar *s,
                           const struct reference *r) {
  for (int kind = SPH_KIND_FLUID; kind <= SPH_KIND_VERTEX; kind++) {
    const struct sph_parts *p = &s->sys.part[kind];
    for (size_t i = 0; i < p->n; i++) {
      const double x[3] = {p->x[0][i], p->x[1][i], p->x[2][i]};
      double ur = NAN;
      if (r->type != REF_NONE) reference_eval(r, x, s->time, &ur, NULL);
      const double row[8] = {s->time,
                             (double)kind,
                             x[0],
                             x[1],
                             x[2],
                             s->u[kind][i],
                             kind == SPH_KIND_FLUID ? s->ut[i] : NAN,
                             ur};
      if (cmn_csv_row(csv, row)) cmn_error("cannot write profiles.csv");
    }
  }
}

/* ------------------------------------------------------------------------------------------ */
/* Command                                                                                     */
/* ------------------------------------------------------------------------------------------ */

int sph_cmd_scalar(int argc, char **argv) {
  gsl_set_error_handler_off(); /* GSL failures come back as statuses (sabre/sph_robin.h) */
  struct cmn_cli cli;
  if (cmn_cli_parse(&cli, argc, argv, argv[0], usage, "scalar-output", NULL, 0))
    return cmn_stdout_status(0);
  const char *case_path = cli.case_path, *output = cli.output;
  struct cmn_case *c = cmn_cli_load(&cli);
  struct sph_geometry g;
  sph_geometry_read(&g, c);
  struct scalar_case cs;
  int nw = cmn_case_seq_length(c, "geometry.walls");
  read_case(c, &cs, g.dim, nw > 0 ? nw : 0);
  cmn_case_check_unused(c);
  if (g.walls.nelem > 0 && cs.nbc == 0)
    cmn_input_error("%s: scalar.boundaries: the walls need at least one boundary entry", case_path);
  int *seg_bc = segment_groups(&g, c, &cs);

  struct sph_system sys;
  sph_system_from_geometry(&sys, &g);
  if (sys.part[SPH_KIND_FLUID].n == 0)
    cmn_input_error("%s: geometry.fluid: no fluid particles", case_path);
  struct sph_scalar_bc *bcs = cmn_malloc(((size_t)cs.nbc + 1) * sizeof *bcs);
  for (int i = 0; i < cs.nbc; i++) bcs[i] = cs.bc[i].bc;
  struct sph_scalar *s = cmn_calloc(1, sizeof *s);
  sph_scalar_init(s, &sys, cs.c, cs.phi, cs.nbc, bcs, seg_bc);
  free(bcs);
  free(seg_bc);
  sph_system_free(&sys);
  sph_geometry_free(&g);

  const struct sph_parts *f = &s->sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < f->n; a++) {
    const double x[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
    s->u[SPH_KIND_FLUID][a] = profile_eval(&cs.u0, x);
    s->ut[a] = profile_eval(&cs.ut0, x);
  }
  struct reference ref = {.type = cs.reference};
  if (ref.type == REF_ROBIN_WAVE) {
    int st = sph_robin_wave_init(&ref.wave, (size_t)cs.terms);
    if (st != SPH_ROBIN_SUCCESS)
      cmn_error("robin_wave series with %ld terms: %s", cs.terms, sph_robin_strerror(st));
    check_reference_data(&ref, s, case_path);
  }

  /* Stability: velocity Verlet needs Δt < 2/(c √ρ(−Lap)). */
  const double radius = sph_scalar_spectral_radius(s, (int)cs.power_iterations);
  long bad;
  int st = sph_scalar_laplacian(s, &bad);
  if (st != SPH_ROBIN_SUCCESS || !isfinite(radius)) {
    const struct sph_parts *v = &s->sys.part[SPH_KIND_VERTEX];
    if (st == SPH_ROBIN_SUCCESS) st = SPH_ROBIN_ESINGULAR;
    cmn_input_error("%s: boundary value at vertex %ld (%g, %g, %g), group %d: %s", case_path, bad,
                    bad >= 0 ? v->x[0][bad] : NAN, bad >= 0 ? v->x[1][bad] : NAN,
                    bad >= 0 ? v->x[2][bad] : NAN, bad >= 0 ? s->vert_bc[bad] : -1,
                    sph_robin_strerror(st));
  }
  const double limit = sph_scalar_dt_limit(s, radius);
  double dt = cs.dt > 0.0 ? cs.dt : cs.cfl * limit;
  if (dt > limit)
    cmn_input_error(
        "%s: time.dt = %g s exceeds the stability limit %g s of velocity Verlet "
        "(2/(c sqrt(rho)), spectral radius rho = %g 1/m^2)",
        case_path, dt, limit, radius);
  cmn_message("%dD, dr = %g m, h = %g m: %zu fluid particles, %zu vertices; vertex layer %g dr",
              s->sys.dim, s->sys.dr, s->sys.h, f->n, s->sys.part[SPH_KIND_VERTEX].n, s->phi);
  cmn_message("spectral radius of Lap %.6g 1/m^2: dt limit %.6g s, dt = %.6g s (%.3g of it)",
              radius, limit, dt, dt / limit);

  cmn_cli_write_used(c, output);
  write_vertices(output, s);
  struct series sr;
  series_open(&sr, output, s, ref.type != REF_NONE);
  static const char *const pnames[] = {"time", "kind", "x", "y", "z", "u", "u_t", "u_ref"};
  struct cmn_csv *prof = open_csv(output, "profiles.csv", 8, (char **)pnames);
  series_write(&sr, s, &ref);
  profiles_write(prof, s, &ref);

  struct cmn_progress prog;
  cmn_progress_start(&prog, 0.0, cs.t_end);
  int next_profile = 0, status = 0;
  while (s->time < cs.t_end * (1.0 - 1e-12)) {
    const double target = next_profile < cs.nprofiles ? cs.profile_times[next_profile] : cs.t_end;
    double step = dt;
    if (target - s->time < dt * (1.0 + 1e-9)) step = target - s->time;
    char msg[1024];
    if (sph_scalar_step(s, step, msg, sizeof msg) != 0) {
      series_write(&sr, s, &ref);
      profiles_write(prof, s, &ref);
      fprintf(stderr, "sabre-sph: scalar run failed: %s (last state written to %s)\n", msg, output);
      status = CMN_EXIT_FAILURE;
      break;
    }
    const int at_target = fabs(s->time - target) <= 1e-9 * dt;
    if (at_target) s->time = target;
    if (s->step % cs.series_every == 0 || at_target) series_write(&sr, s, &ref);
    if (at_target) {
      profiles_write(prof, s, &ref);
      if (next_profile < cs.nprofiles) next_profile++;
    }
    cmn_progress_report(&prog, s->step, s->time, step, (long)f->n, 0);
  }
  cmn_progress_report(&prog, s->step, s->time, dt, (long)f->n, 1);
  if (cmn_csv_close(sr.csv) | cmn_csv_close(prof))
    cmn_error("an output CSV file in '%s' could not be written completely", output);
  if (ref.type != REF_NONE && sr.t_last > 0.0) {
    const double mean = sr.integral / sr.t_last;
    cmn_message(
        "boundary error |u_v - u_ref| over t in [0, %g]: time mean %.6e, max %.6e; "
        "relative to max |u_ref| at the vertices (%.6g): %.6e, %.6e",
        sr.t_last, mean, sr.e_max, sr.ref_max, mean / sr.ref_max, sr.e_max / sr.ref_max);
  }
  cmn_message("wrote %s/{used_case.yaml, vertices.csv, series.csv, profiles.csv}", output);
  free(sr.row);
  if (ref.type == REF_ROBIN_WAVE) sph_robin_wave_free(&ref.wave);
  for (int i = 0; i < cs.nbc; i++) free(cs.bc[i].edges);
  free(cs.bc);
  sph_scalar_free(s);
  free(s);
  cmn_case_free(c);
  return status;
}
