/*
 * `sabre-sph run CASE.yaml [--set key=value]... [--output DIR] [--restart FILE] [--threads N]`:
 * reads the case (docs/sph-case-file.md), builds the particles, integrates to time.end and writes
 * into DIR: used_case.yaml, particles.pvd + fluid_/boundary_NNNNNN.vtu, diagnostics.csv,
 * probes.csv, forces.csv, open_<name>.csv per open boundary, checkpoint.bin (every N steps or
 * minutes, at the end, on SIGINT/SIGTERM). A failed step (NaN, particle through a wall, density out
 * of band) writes a last output and a diagnostics row, then stops with the message (exit code 1).
 */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "cli.h"
#include "sabre/common.h"
#include "sabre/sph_solver.h"

static volatile sig_atomic_t stop_signal = 0;
static void on_signal(int sig) { stop_signal = sig; }

static const char usage[] =
    "usage: sabre-sph run CASE.yaml [--set key=value]... [--output DIR] [--restart FILE]\n"
    "                     [--threads N]\n"
    "Run the simulation of a case into DIR (default sph-output).\n"
    "  --set key=value  override a key of the case file (repeatable)\n"
    "  --restart FILE   continue from a checkpoint of the same case (only the time section\n"
    "                   may change)\n"
    "  --threads N      OpenMP threads; default 1 (or OMP_NUM_THREADS when set): on a machine\n"
    "                   shared with other jobs, more threads than idle cores slow the run down\n"
    "                   many times over. Give N up to the number of idle cores for speed.\n"
    "Each option is given once (--set may repeat). Exit status: 0 done, 2 bad input, 1 failed\n"
    "run, 3 stopped at time.max_steps before time.end (checkpoint written: continue with\n"
    "--restart DIR/checkpoint.bin), 128+N stopped by signal N (checkpoint written).\n"
    "See docs/sph-case-file.md for the case-file keys and docs/sph-solver.md for the outputs.\n";

struct run_files {
  struct cmn_csv *diag, *probes, *forces;
  struct cmn_csv *open[SPH_MAX_OPEN_GROUPS]; /**< open_<name>.csv per open boundary */
  struct sph_output vtu;
  char *dir;
};

/*
 * Open a CSV; on restart keep the rows of the previous run with time ≤ t_keep (first column), so
 * that the file reads as if the run had not been interrupted.
 */
static struct cmn_csv *csv_open(const char *dir, const char *name, int ncols,
                                const char *const *names, int restart, double t_keep) {
  char *path = sph_cli_join(dir, name);
  double *rows = NULL;
  size_t nrows = 0, cap = 0;
  if (restart) {
    FILE *in = fopen(path, "r");
    char line[65536];
    if (in && fgets(line, sizeof line, in)) {
      while (fgets(line, sizeof line, in)) {
        double vals[1024];
        int n = 0;
        char *p = line;
        while (n < ncols && n < 1024) {
          char *end;
          vals[n++] = strtod(p, &end);
          if (end == p) break;
          p = end;
          if (*p == ',') p++;
        }
        if (n != ncols || vals[0] > t_keep) continue;
        if (nrows == cap) {
          cap = cap ? 2 * cap : 64;
          rows = cmn_realloc(rows, cap * (size_t)ncols * sizeof *rows);
        }
        memcpy(rows + nrows * (size_t)ncols, vals, (size_t)ncols * sizeof *rows);
        nrows++;
      }
    }
    if (in) fclose(in);
  }
  struct cmn_csv *csv = cmn_csv_open(path, ncols, names);
  if (!csv) cmn_input_error("cannot write '%s': %s", path, strerror(errno));
  for (size_t r = 0; r < nrows; r++) cmn_csv_row(csv, rows + r * (size_t)ncols);
  free(rows);
  free(path);
  return csv;
}

static void open_files(struct run_files *rf, const struct sph_solver *sv,
                       const struct sph_run_counters *rc, int restart) {
  const struct sph_config *cfg = &sv->cfg;
  const int dim = sv->sys.dim;
  static const char *const dnames[] = {
      "time",     "dt",        "particles", "mass",          "kinetic",   "potential",
      "internal", "max_speed", "max_drho",  "flux_velocity", "flux_force"};
  /* with an imposed flux: ṽ in the slice and the driving acceleration (docs/sph-case-file.md) */
  const int ndiag = cfg->flux_method != SPH_FLUXSEL_OFF ? 11 : 9;
  rf->diag = csv_open(rf->dir, "diagnostics.csv", ndiag, dnames, restart, sv->time);
  int np = 1 + cfg->nprobes + 2 * cfg->ngauges;
  char **pn = cmn_malloc((size_t)np * sizeof *pn);
  pn[0] = "time";
  for (int i = 0; i < cfg->nprobes; i++) {
    pn[1 + i] = cmn_malloc(32);
    snprintf(pn[1 + i], 32, "p%d", i);
  }
  for (int i = 0; i < cfg->ngauges; i++) {
    pn[1 + cfg->nprobes + i] = cmn_malloc(32);
    snprintf(pn[1 + cfg->nprobes + i], 32, "eta%d", i);
    pn[1 + cfg->nprobes + cfg->ngauges + i] = cmn_malloc(32);
    snprintf(pn[1 + cfg->nprobes + cfg->ngauges + i], 32, "level%d", i);
  }
  rf->probes = np > 1
                   ? csv_open(rf->dir, "probes.csv", np, (const char *const *)pn, restart, sv->time)
                   : NULL;
  for (int i = 1; i < np; i++) free(pn[i]);
  free(pn);
  int nf = 1 + dim * cfg->nforces;
  char **fn = cmn_malloc((size_t)nf * sizeof *fn);
  fn[0] = "time";
  for (int g = 0; g < cfg->nforces; g++)
    for (int c = 0; c < dim; c++) {
      fn[1 + g * dim + c] = cmn_malloc(96);
      snprintf(fn[1 + g * dim + c], 96, "%s_f%c", cfg->forces[g].name, "xyz"[c]);
    }
  rf->forces = nf > 1
                   ? csv_open(rf->dir, "forces.csv", nf, (const char *const *)fn, restart, sv->time)
                   : NULL;
  for (int i = 1; i < nf; i++) free(fn[i]);
  free(fn);
  for (int g = 0; g < cfg->open.ngroups; g++) {
    char name[96];
    snprintf(name, sizeof name, "open_%s.csv", cfg->open.group[g].name);
    rf->open[g] =
        csv_open(rf->dir, name, SPH_OPEN_CSV_COLUMNS, sph_open_csv_columns(), restart, sv->time);
  }
  if (sph_output_open(&rf->vtu, rf->dir, "particles") != 0)
    cmn_input_error("cannot create the output directory '%s': %s", rf->dir, strerror(errno));
  if (restart && rc->outputs > 0) {
    rf->vtu.cap = (int)rc->outputs;
    rf->vtu.count = (int)rc->outputs;
    rf->vtu.times = cmn_malloc((size_t)rc->outputs * sizeof(double));
    memcpy(rf->vtu.times, rc->output_times, (size_t)rc->outputs * sizeof(double));
  }
}

/* One row of each CSV file for the current state (failed: the state of a failed step, not
 * evaluated again). */
static void write_rows(struct run_files *rf, struct sph_solver *sv, int failed) {
  const struct sph_config *cfg = &sv->cfg;
  struct sph_diagnostics d;
  sph_solver_diagnostics(sv, &d);
  /* imposed flux: ṽ of the state at this time (M 56–57) and F of the step that ended here */
  const double vt = cfg->flux_method != SPH_FLUXSEL_OFF ? sph_solver_flux_measure(sv) : 0.0;
  const double row[11] = {d.time,     d.dt,        d.count,    d.mass, d.kinetic,     d.potential,
                          d.internal, d.max_speed, d.max_drho, vt,     sv->flux_force};
  if (cmn_csv_row(rf->diag, row))
    cmn_error("cannot write %s/diagnostics.csv: %s", rf->dir, strerror(errno));
  if (rf->probes) {
    double vals[1 + 3 * SPH_MAX_PROBES];
    vals[0] = sv->time;
    for (int i = 0; i < cfg->nprobes; i++)
      vals[1 + i] = sph_solver_probe_pressure(sv, cfg->probes[i]);
    for (int i = 0; i < cfg->ngauges; i++) {
      vals[1 + cfg->nprobes + i] = sph_solver_gauge(sv, cfg->gauges[i]);
      vals[1 + cfg->nprobes + cfg->ngauges + i] = sph_solver_level(sv, cfg->gauges[i]);
    }
    if (cmn_csv_row(rf->probes, vals))
      cmn_error("cannot write %s/probes.csv: %s", rf->dir, strerror(errno));
  }
  if (rf->forces) {
    double f[SPH_MAX_FORCE_GROUPS][3], vals[1 + 3 * SPH_MAX_FORCE_GROUPS];
    sph_solver_evaluate(sv); /* forces of the current state (the next step reuses this) */
    sph_solver_wall_forces(sv, f);
    vals[0] = sv->time;
    for (int g = 0; g < cfg->nforces; g++)
      for (int c = 0; c < sv->sys.dim; c++) vals[1 + g * sv->sys.dim + c] = f[g][c];
    if (cmn_csv_row(rf->forces, vals))
      cmn_error("cannot write %s/forces.csv: %s", rf->dir, strerror(errno));
  }
  if (sv->open) {
    /* the open-boundary values of the current state (the next step reuses this evaluation);
     * after a failed step, those of its last evaluation */
    if (!failed && sv->evaluated_step != sv->step) sph_solver_evaluate(sv);
    for (int g = 0; g < sv->open->ngroups; g++) {
      double orow[SPH_OPEN_CSV_COLUMNS];
      sph_open_csv_row(sv->open, g, sv->time, orow);
      if (cmn_csv_row(rf->open[g], orow))
        cmn_error("cannot write %s/open_%s.csv: %s", rf->dir, cfg->open.group[g].name,
                  strerror(errno));
    }
  }
}

static void flush_files(struct run_files *rf) {
  cmn_csv_flush(rf->diag);
  if (rf->probes) cmn_csv_flush(rf->probes);
  if (rf->forces) cmn_csv_flush(rf->forces);
  for (int g = 0; g < SPH_MAX_OPEN_GROUPS; g++)
    if (rf->open[g]) cmn_csv_flush(rf->open[g]);
}

static void close_files(struct run_files *rf) {
  int bad = cmn_csv_close(rf->diag) | cmn_csv_close(rf->probes) | cmn_csv_close(rf->forces);
  for (int g = 0; g < SPH_MAX_OPEN_GROUPS; g++) bad |= cmn_csv_close(rf->open[g]);
  sph_output_close(&rf->vtu);
  if (bad) cmn_error("an output CSV file could not be written completely");
}

/* The store's pressure is that of the last force evaluation (the step's predictor): evaluate the
 * current state first (the next step reuses it), unless the step failed (NaN positions). */
static void write_vtu(struct run_files *rf, struct sph_run_counters *rc, struct sph_solver *sv,
                      int failed) {
  if (!failed && sv->evaluated_step != sv->step) sph_solver_evaluate(sv);
  if (sph_output_write(&rf->vtu, &sv->sys, sv->time) != 0)
    cmn_error("cannot write the particle output in '%s': %s", rf->dir, strerror(errno));
  rc->output_times = cmn_realloc(rc->output_times, (size_t)(rc->outputs + 1) * sizeof(double));
  rc->output_times[rc->outputs++] = sv->time;
}

static void checkpoint(const struct sph_solver *sv, const struct sph_run_counters *rc,
                       const char *dir) {
  char *path = sph_cli_join(dir, "checkpoint.bin");
  if (sph_checkpoint_write(sv, rc, path) != 0)
    cmn_error("cannot write checkpoint '%s': %s", path, strerror(errno));
  free(path);
}

/* Wall index and element number (within its wall) of every segment, from the mesh sources. */
static void segment_sources(const struct sph_geometry *g, struct cmn_case *c, int **wall,
                            long **edge) {
  const struct sph_mesh *m = &g->walls;
  *wall = cmn_malloc((m->nelem + 1) * sizeof **wall);
  *edge = cmn_malloc((m->nelem + 1) * sizeof **edge);
  int nw = cmn_case_seq_length(c, "geometry.walls");
  if (m->nsources != (nw > 0 ? nw : 0) && cmn_case_seq_length(c, "forces") > 0)
    cmn_input_error(
        "%s: forces: the walls could not be matched to geometry.walls entries (%d "
        "sources for %d walls)",
        cmn_case_name(c), m->nsources, nw);
  for (size_t e = 0; e < m->nelem; e++) {
    (*wall)[e] = m->source[e];
    (*edge)[e] = m->source_index[e];
  }
}

/*
 * The solver of a case as `run` and `stability` start it (cli.h).
 */
struct sph_solver *sph_cli_solver(struct cmn_case *c, const char *case_path, const char *dir,
                                  const struct sph_cli_setup *setup) {
  struct sph_geometry g;
  sph_geometry_read(&g, c);
  struct sph_config cfg;
  sph_config_read(&cfg, c, g.dim);
  sph_open_check_mesh(&cfg.open, c, &g.walls); /* every open element in exactly one group */
  cmn_case_check_unused(c);

  struct sph_system s;
  cmn_message("building the particles...");
  sph_system_from_geometry(&s, &g);
  if (s.part[SPH_KIND_FLUID].n == 0)
    cmn_input_error("%s: geometry.fluid: no fluid particles", case_path);
  sph_config_check_initial(&cfg, c, &s);
  sph_config_check_probes(&cfg, c, &s);
  if (setup->closed_only && cfg.open.ngroups > 0)
    cmn_input_error(
        "%s: open_boundaries: %s is for closed domains (the open boundaries' Riemann solves "
        "and particle creation are not linearised); remove the section or close the domain",
        case_path, setup->command);
  const size_t unknowns = s.part[SPH_KIND_FLUID].n * (size_t)s.dim;
  if (setup->max_unknowns > 0 && unknowns > (size_t)setup->max_unknowns)
    cmn_input_error(
        "%s: %zu fluid particles x %d = %zu unknowns, more than the %ld of %s "
        "(--max-unknowns): coarsen geometry.dr or raise the limit",
        case_path, s.part[SPH_KIND_FLUID].n, s.dim, unknowns, setup->max_unknowns, setup->command);
  cmn_cli_write_used(c, dir);
  int *seg_wall;
  long *seg_edge;
  segment_sources(&g, c, &seg_wall, &seg_edge);
  struct sph_solver *sv = cmn_calloc(1, sizeof *sv);
  if (!setup->repack) { /* the checkpoint has the positions */
    cfg.repack_steps = 0;
    cfg.layer_equilibrium = 0;
    cfg.settle = 0.0;
  }
  sph_solver_init(sv, &cfg, &s, seg_wall, seg_edge);
  if (cfg.repack_steps > 0)
    cmn_message(
        "repacking: %ld steps, %zu particles held at the free surface, largest defect "
        "|sum V_b grad w_ab - grad gamma_a| h %.3g -> %.3g",
        cfg.repack_steps, sv->repack_fixed, sv->repack_residual[0], sv->repack_residual[1]);
  if (sv->layer_count > 0) {
    char shifts[160] = "";
    size_t len = 0;
    for (int k = 0; k < sv->layer_count && k < 4 && len < sizeof shifts; k++)
      len += (size_t)snprintf(shifts + len, sizeof shifts - len, "%s%+.3f", k ? ", " : "",
                              sv->layer_shift[k]);
    cmn_message(
        "layer equilibrium: %d layers moved up by %s%s dr (the highest first), largest mean "
        "vertical acceleration of a layer %.2g g",
        sv->layer_count, shifts, sv->layer_count > 4 ? ", ..." : "", sv->layer_residual);
  }
  if (cfg.settle > 0.0)
    cmn_message(
        "settling: %g s of the case's dynamics in %ld steps, largest speed %.3g m/s at "
        "its end, set to zero; the run starts at t = 0",
        cfg.settle, sv->settle_steps, sv->settle_speed);
  free(seg_wall);
  free(seg_edge);
  sph_system_free(&s);
  sph_geometry_free(&g);

  if (sv->sys.part[SPH_KIND_VERTEX].n > 0 && cfg.vertex_volume == SPH_VVOL_FITTED &&
      sv->vertex_phi < 0.25)
    cmn_warning(
        "%s: the fitted wall layer is %.2f dr thick: the first fluid row is about dr/2 "
        "from the walls, where walls attract the fluid (docs/sph-solver.md section 7); "
        "set geometry.first_row: 1 (or move the fluid regions dr/2 away from the walls) so "
        "that it is dr",
        case_path, sv->vertex_phi);
  return sv;
}

/*
 * Thread count: --threads N, else OMP_NUM_THREADS when the user set it, else 1. Not the OpenMP
 * default (one per core): OpenMP threads spin while they wait, and on a machine whose cores are
 * busy with other jobs a team as large as the machine runs many times slower than one thread
 * (the wedge dam break of cases/sph: 162 s against 1.3 s). Returns the count used.
 */
int sph_cli_threads(const char *threads_arg, const char *command) {
  long threads = 0;
  if (threads_arg && cmn_parse_long(threads_arg, 1, 4096, &threads) != 0)
    cmn_input_error("%s: --threads: expected a whole number in [1, 4096], got '%s'", command,
                    threads_arg);
#ifdef _OPENMP
  const char *env = getenv("OMP_NUM_THREADS");
  if (threads == 0 && env != NULL && env[0] != '\0') return omp_get_max_threads();
  if (threads == 0) threads = 1;
  omp_set_num_threads((int)threads);
  return (int)threads;
#else
  if (threads > 1)
    cmn_warning("--threads %ld: built without OpenMP, running on one thread", threads);
  return 1;
#endif
}

int sph_cmd_run(int argc, char **argv) {
  const char *restart = NULL, *threads_arg = NULL;
  const struct cmn_cli_option options[] = {{"--restart", &restart, 0},
                                           {"--threads", &threads_arg, 0}};
  struct cmn_cli cli;
  if (cmn_cli_parse(&cli, argc, argv, argv[0], usage, "sph-output", options, 2))
    return cmn_stdout_status(0);
  const char *case_path = cli.case_path, *output = cli.output;
  const int threads = sph_cli_threads(threads_arg, "run");
  const double wall0 = cmn_wall_time();

  char err[2048];
  struct cmn_case *c = cmn_cli_load(&cli);
  /* the checkpoint has the positions: no repacking on restart */
  const struct sph_cli_setup setup = {"run", restart == NULL, 0, 0};
  struct sph_solver *sv = sph_cli_solver(c, case_path, output, &setup);
  const struct sph_config cfg = sv->cfg; /* read only: owned by the solver */
  struct sph_run_counters rc = {0.0, 0, NULL, 0, {{0}}, {0}};
  sph_run_counters_digest(&rc, c);
  {
    const struct sph_system *sy = &sv->sys;
    const double dt_est = cfg.cfl * sy->h / cfg.c0;
    cmn_message(
        "%dD: %zu fluid particles, %zu vertices, %zu segments; dr = %g m, h = %g m, c0 = %g m/s; "
        "dt about %.3g s (cfl h/c0), %.3g steps to t = %g s; %d thread%s (wait policy %s); "
        "set-up %.2g s",
        sy->dim, sy->part[SPH_KIND_FLUID].n, sy->part[SPH_KIND_VERTEX].n,
        sy->part[SPH_KIND_SEGMENT].n, sy->dr, sy->h, cfg.c0, dt_est, cfg.t_end / dt_est, cfg.t_end,
        threads, threads > 1 ? "s" : "",
        getenv("OMP_WAIT_POLICY") ? getenv("OMP_WAIT_POLICY") : "default", cmn_wall_time() - wall0);
  }
  if (restart) {
    if (sph_checkpoint_read(sv, &rc, restart, err, sizeof err) != 0) cmn_input_error("%s", err);
    cmn_message("restarting from %s at step %ld, t = %.9g s", restart, sv->step, sv->time);
  }
  struct run_files rf = {.dir = (char *)output};
  open_files(&rf, sv, &rc, restart != NULL);
  if (!restart) {
    write_rows(&rf, sv, 0);
    write_vtu(&rf, &rc, sv, 0);
    rc.next_output = cfg.output_interval;
  }

  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);
  struct cmn_progress prog;
  cmn_progress_start(&prog, sv->time, cfg.t_end);
  double last_ckpt = cmn_wall_time();
  const long step0 = sv->step;
  int status = 0;
  const double eps = 1e-12 * cfg.t_end;
  while (sv->time < cfg.t_end - eps) {
    char msg[1024];
    if (sph_solver_step(sv, cfg.t_end - sv->time, msg, sizeof msg) != 0) {
      write_rows(&rf, sv, 1);
      write_vtu(&rf, &rc, sv, 1);
      flush_files(&rf);
      cmn_progress_report(&prog, sv->step, sv->time, sv->dt, (long)sv->sys.part[0].n, 1);
      fprintf(stderr, "sabre-sph: run failed: %s (last state written to %s)\n", msg, output);
      status = CMN_EXIT_FAILURE;
      break;
    }
    int out = sv->time >= rc.next_output - eps || sv->time >= cfg.t_end - eps;
    if (out || sv->step % cfg.diagnostics_every == 0) write_rows(&rf, sv, 0);
    if (out) {
      write_vtu(&rf, &rc, sv, 0);
      /* the next multiple of the interval after now, in one step (no loop that a tiny interval
       * could keep from ending) */
      double k = floor((sv->time + eps) / cfg.output_interval) + 1.0;
      rc.next_output = fmax(k * cfg.output_interval, nextafter(rc.next_output, INFINITY));
      flush_files(&rf);
    }
    cmn_progress_report(&prog, sv->step, sv->time, sv->dt, (long)sv->sys.part[0].n, 0);
    double now = cmn_wall_time();
    if ((cfg.checkpoint_steps > 0 && sv->step % cfg.checkpoint_steps == 0) ||
        (cfg.checkpoint_minutes > 0 && now - last_ckpt >= 60.0 * cfg.checkpoint_minutes)) {
      flush_files(&rf);
      checkpoint(sv, &rc, output);
      last_ckpt = now;
    }
    if (cfg.max_steps > 0 && sv->step >= cfg.max_steps) {
      flush_files(&rf);
      checkpoint(sv, &rc, output);
      cmn_message(
          "time.max_steps = %ld reached at t = %.9g s, before time.end: outputs up to there and "
          "a checkpoint written; continue with --restart %s/checkpoint.bin",
          cfg.max_steps, sv->time, output);
      status = CMN_EXIT_INCOMPLETE;
      break;
    }
    if (stop_signal) {
      flush_files(&rf);
      checkpoint(sv, &rc, output);
      cmn_message(
          "signal %d: checkpoint written at step %ld, t = %.9g s; continue with "
          "--restart %s/checkpoint.bin",
          (int)stop_signal, sv->step, sv->time, output);
      status = 128 + (int)stop_signal;
      break;
    }
  }
  if (status == 0) {
    cmn_progress_report(&prog, sv->step, sv->time, sv->dt, (long)sv->sys.part[0].n, 1);
    checkpoint(sv, &rc, output);
  }
  close_files(&rf);
  {
    const double wall = cmn_wall_time() - wall0, steps = (double)(sv->step - step0);
    cmn_message(
        "%s at t = %.6g s: %.0f steps, %ld outputs, %.3g s wall, %.3g particle-steps/s; "
        "outputs in %s",
        status == 0                     ? "done"
        : status == CMN_EXIT_INCOMPLETE ? "stopped"
        : status == CMN_EXIT_FAILURE    ? "failed"
                                        : "interrupted",
        sv->time, steps, rc.outputs, wall,
        wall > 0 ? steps * (double)sv->sys.part[SPH_KIND_FLUID].n / wall : 0.0, output);
  }
  free(rc.output_times);
  sph_solver_free(sv);
  free(sv);
  cmn_case_free(c);
  return status;
}
