/* Outputs of a run: x, rho, u, p profiles at the output times, the time series of the conserved
 * totals and end-face fluxes, and the run summary (docs/fv1d.md, "Outputs"). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

int fv1d_output_profile(const struct fv1d_solver *s, const char *path) {
  static const char *const names[] = {"x", "rho", "u", "p"};
  struct cmn_csv *csv = cmn_csv_open(path, 4, names);
  if (!csv) return -1;
  int status = 0;
  for (long i = 0; i < s->n && status == 0; ++i) {
    double rho = s->y[2 * i], u = s->y[2 * i + 1] / rho;
    double row[4] = {fv1d_solver_x(s, i), rho, u, rmn_eos_pressure(&s->par.eos, rho)};
    status = cmn_csv_row(csv, row);
  }
  return cmn_csv_close(csv) != 0 || status != 0 ? -1 : 0;
}

enum { NSERIES = 19 };
static const char *const series_names[NSERIES] = {"t",
                                                  "mass",
                                                  "momentum",
                                                  "energy",
                                                  "flux_mass_left",
                                                  "flux_momentum_left",
                                                  "flux_energy_left",
                                                  "flux_mass_right",
                                                  "flux_momentum_right",
                                                  "flux_energy_right",
                                                  "int_mass_left",
                                                  "int_momentum_left",
                                                  "int_energy_left",
                                                  "int_mass_right",
                                                  "int_momentum_right",
                                                  "int_energy_right",
                                                  "mass_balance",
                                                  "momentum_balance",
                                                  "energy_dissipated"};

struct fv1d_output {
  char dir[4096];
  struct cmn_csv *series, *index;
  long nprofile;
  double totals0[3];
  double row[NSERIES];
  double *ydot; /* scratch for the end fluxes at the output state */
  long last_series_step;
  long cells;
};

struct fv1d_output *fv1d_output_open(const char *dir, struct fv1d_solver *s) {
  if (cmn_mkdir_p(dir) != 0) {
    fv1d_set_error(s, "cannot create the output directory '%s': %s", dir, strerror(errno));
    return NULL;
  }
  struct fv1d_output *out = cmn_calloc(1, sizeof *out);
  snprintf(out->dir, sizeof out->dir, "%s", dir);
  char path[4200];
  snprintf(path, sizeof path, "%s/series.csv", dir);
  out->series = cmn_csv_open(path, NSERIES, series_names);
  static const char *const index_names[] = {"index", "t"};
  snprintf(path, sizeof path, "%s/profiles.csv", dir);
  out->index = cmn_csv_open(path, 2, index_names);
  if (!out->series || !out->index) {
    fv1d_set_error(s, "cannot write '%s': %s", path, strerror(errno));
    cmn_csv_close(out->series);
    cmn_csv_close(out->index);
    free(out);
    return NULL;
  }
  out->ydot = cmn_calloc((size_t)fv1d_solver_state_length(s), sizeof(double));
  out->last_series_step = -1;
  out->cells = s->n;
  return out;
}

static int write_series(struct fv1d_solver *s, struct fv1d_output *out, long step, double t) {
  double totals[3];
  fv1d_totals(s, s->y, totals);
  if (step == 0 && out->last_series_step < 0) memcpy(out->totals0, totals, sizeof totals);
  /* the end fluxes at this very state (the last stage of the step was at another state) */
  if (fv1d_rhs_eval(s, t, s->y, out->ydot) != 0) return -1;
  const double *q = s->y + 2 * s->n;
  double *r = out->row;
  r[0] = t;
  for (int k = 0; k < 3; ++k) r[1 + k] = totals[k];
  for (int side = 0; side < 2; ++side) {
    r[4 + 3 * side + 0] = out->ydot[2 * s->n + 3 * side + 0];
    r[4 + 3 * side + 1] = out->ydot[2 * s->n + 3 * side + 1];
    r[4 + 3 * side + 2] = out->ydot[2 * s->n + 3 * side + 2];
  }
  for (int k = 0; k < 6; ++k) r[10 + k] = q[k];
  for (int k = 0; k < 3; ++k) /* change of the total minus what entered through the ends */
    r[16 + k] = totals[k] - out->totals0[k] - (q[k] - q[3 + k]);
  r[18] = 0.0 - r[18]; /* dissipated energy, without printing −0 */
  out->last_series_step = step;
  return cmn_csv_row(out->series, r);
}

static int write_profile(struct fv1d_solver *s, struct fv1d_output *out, double t) {
  char path[4200];
  snprintf(path, sizeof path, "%s/profile_%04ld.csv", out->dir, out->nprofile);
  if (fv1d_output_profile(s, path) != 0) {
    fv1d_set_error(s, "cannot write '%s': %s", path, strerror(errno));
    return -1;
  }
  double row[2] = {(double)out->nprofile, t};
  ++out->nprofile;
  return cmn_csv_row(out->index, row);
}

int fv1d_output_observer(struct fv1d_solver *s, enum fv1d_event event, long step, double t,
                         double dt, void *user) {
  struct fv1d_output *out = user;
  switch (event) {
    case FV1D_EVENT_START:
      if (write_series(s, out, 0, t) != 0) return -1;
      return write_profile(s, out, t);
    case FV1D_EVENT_STEP:
      if (step % s->par.series_every != 0) return 0;
      return write_series(s, out, step, t);
    case FV1D_EVENT_OUTPUT:
      if (out->last_series_step != step && write_series(s, out, step, t) != 0) return -1;
      cmn_csv_flush(out->series);
      return write_profile(s, out, t);
  }
  return 0;
}

int fv1d_output_close(struct fv1d_output *out, const struct fv1d_stats *stats, int status) {
  if (!out) return 0;
  int result = 0;
  if (cmn_csv_close(out->series) != 0) result = -1;
  if (cmn_csv_close(out->index) != 0) result = -1;
  char path[4200];
  snprintf(path, sizeof path, "%s/summary.yaml", out->dir);
  FILE *f = fopen(path, "w");
  if (!f) {
    result = -1;
  } else {
    const double *r = out->row;
    fprintf(f, "# sabre-fv1d run summary\n");
    fprintf(f, "status: %s\n",
            status == 0   ? "success"
            : status == 1 ? "stopped at time.max_steps"
                          : "failure");
    fprintf(f, "final_time: %.17g  # s\n", r[0]);
    fprintf(f, "steps: %ld\n", stats->steps);
    fprintf(f, "rhs_evaluations: %ld\n", stats->rhs_evals);
    fprintf(f, "error_test_failures: %ld\n", stats->failed_steps);
    fprintf(f, "cells: %ld\n", out->cells);
    fprintf(f, "wall_time: %.6g  # s\n", stats->wall_time);
    fprintf(f, "cell_updates_per_second_per_stage: %.6g\n",
            stats->wall_time > 0.0
                ? (double)out->cells * (double)stats->rhs_evals / stats->wall_time
                : 0.0);
    fprintf(f, "profiles: %ld\n", out->nprofile);
    fprintf(f, "mass_initial: %.17g  # kg/m^2\n", out->totals0[0]);
    fprintf(f, "mass_final: %.17g  # kg/m^2\n", r[1]);
    fprintf(f, "mass_balance: %.6e  # kg/m^2, change minus boundary inflow\n", r[16]);
    fprintf(f, "momentum_initial: %.17g  # kg/m/s\n", out->totals0[1]);
    fprintf(f, "momentum_final: %.17g  # kg/m/s\n", r[2]);
    fprintf(f, "momentum_balance: %.6e  # kg/m/s\n", r[17]);
    fprintf(f, "energy_initial: %.17g  # J/m^2\n", out->totals0[2]);
    fprintf(f, "energy_final: %.17g  # J/m^2\n", r[3]);
    fprintf(f, "energy_dissipated: %.6e  # J/m^2\n", r[18]);
    if (fclose(f) != 0) result = -1;
  }
  free(out->ydot);
  free(out);
  return result;
}
