/*
 * `sabre-sph stability CASE.yaml [--set key=value]... [--output DIR] [--modes N] [--eps E]
 * [--min-rate R] [--max-unknowns N] [--from FILE] [--threads N]`: the linearised dynamics of a
 * case's fluid about its start (docs/sph-solver.md §7.1, "The free surface's static states are
 * linearly unstable"). The solver is built as `run` builds it (repacking and settling
 * included), J = ∂a/∂x by sph_solver_jacobian(), and the modes of ẍ = J x by
 * sph_stability_modes(). Prints a summary and the fastest-growing modes on stdout and writes every
 * mode into DIR/stability.csv.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "sabre/common.h"
#include "sabre/sph_solver.h"

static const char usage[] =
    "usage: sabre-sph stability CASE.yaml [--set key=value]... [--output DIR] [--modes N]\n"
    "                           [--eps E] [--min-rate R] [--max-unknowns N] [--from FILE]\n"
    "                           [--threads N]\n"
    "The linearised dynamics of a closed case's fluid about its start (after the case's\n"
    "repacking and settling): J = da/dx by central differences of the solver's\n"
    "accelerations, each density following the time summation, and the modes of x'' = J x\n"
    "from J's eigenvalues lambda and eigenvectors (GSL). A mode grows at the rate\n"
    "Re sqrt(lambda) [1/s]: a real lambda > 0 is a static instability, a complex lambda an\n"
    "oscillation that grows or decays (flutter).\n"
    "Prints a summary and the N fastest-growing modes on stdout, and writes every mode into\n"
    "DIR/stability.csv (default DIR sph-stability) with DIR/used_case.yaml.\n"
    "  --set key=value    override a key of the case file (repeatable)\n"
    "  --modes N          modes printed on stdout (default 10; 0: the summary only)\n"
    "  --eps E            displacement of the central differences in units of dr (default 1e-7)\n"
    "  --min-rate R       growth rate [1/s] below which the summary does not count a mode\n"
    "                     (default 1e-3: the round-off of J splits degenerate and neutral\n"
    "                     eigenvalues into rates of order 1e-8 1/s); the file lists every mode\n"
    "  --max-unknowns N   refuse cases with more than N unknowns, dim x fluid particles\n"
    "                     (default 6000: J, the eigenvectors and GSL's workspace take about\n"
    "                     40 N^2 bytes, 1.4 GB at 6000, and the eigenproblem grows as N^3)\n"
    "  --from FILE        linearise about the state of a checkpoint of this case (written by\n"
    "                     run: positions, densities, velocities) instead of the start; the\n"
    "                     velocities are kept, so the analysis means most for a state near rest\n"
    "  --threads N        OpenMP threads for the force evaluations (as for run)\n"
    "Closed domains only: a case with open boundaries is refused. Cost: 2 x unknowns force\n"
    "evaluations and one eigenproblem; 1176 unknowns (the 3D still-water tank) take about 1.5\n"
    "minutes on one core. Exit status: 0 done, 2 bad input, 1 eigensolver failure.\n"
    "Columns of stability.csv (one row per mode, fastest growth first): mode, lambda_re,\n"
    "lambda_im [1/s^2], rate [1/s], id, x, y, z [m] of the particle that moves most in the mode,\n"
    "dir_x, dir_y, dir_z (the moduli of its components, unit norm), share (its fraction of the\n"
    "mode's squared norm), participation (1/sum of the squared shares: how many particles move).\n"
    "See docs/sph-solver.md section 7.1.\n";

/* One mode's summary. */
struct mode {
  double re, im, rate;
  size_t particle; /* the particle of the largest share */
  double dir[3];   /* its component moduli, unit norm */
  double share, participation;
};

static int by_rate(const void *pa, const void *pb) {
  const struct mode *a = pa, *b = pb;
  if (a->rate != b->rate) return a->rate < b->rate ? 1 : -1;
  if (a->re != b->re) return a->re < b->re ? 1 : -1;
  return (a->im < b->im) - (a->im > b->im);
}

/* Where mode j of the n × n moduli amp lives: the particle of largest share, its direction, and
 * the participation number. */
static void locate(struct mode *md, const double *amp, size_t n, size_t j, int dim) {
  const size_t np = n / (size_t)dim;
  double total = 0.0, total_sq = 0.0, best = -1.0;
  for (size_t a = 0; a < np; a++) {
    double p = 0.0;
    for (int c = 0; c < dim; c++) p += amp[(a * dim + c) * n + j] * amp[(a * dim + c) * n + j];
    total += p;
    total_sq += p * p;
    if (p > best) {
      best = p;
      md->particle = a;
    }
  }
  md->share = best / total;
  md->participation = total * total / total_sq; /* 1 / Σ (p_a / Σ p)² */
  for (int c = 0; c < 3; c++)
    md->dir[c] = c < dim ? amp[(md->particle * dim + c) * n + j] / sqrt(best) : 0.0;
}

int sph_cmd_stability(int argc, char **argv) {
  const char *modes_arg = NULL, *eps_arg = NULL, *max_arg = NULL, *threads_arg = NULL,
             *min_rate_arg = NULL, *from = NULL;
  const struct cmn_cli_option options[] = {
      {"--modes", &modes_arg, 0},       {"--eps", &eps_arg, 0}, {"--max-unknowns", &max_arg, 0},
      {"--min-rate", &min_rate_arg, 0}, {"--from", &from, 0},   {"--threads", &threads_arg, 0}};
  struct cmn_cli cli;
  if (cmn_cli_parse(&cli, argc, argv, argv[0], usage, "sph-stability", options, 6))
    return cmn_stdout_status(0);
  long nprint = 10, max_unknowns = 6000;
  double eps_dr = 1e-7, min_rate = 1e-3;
  if (modes_arg && cmn_parse_long(modes_arg, 0, 1000000000L, &nprint) != 0)
    cmn_input_error("stability: --modes: expected a whole number >= 0, got '%s'", modes_arg);
  if (eps_arg && (cmn_parse_double(eps_arg, &eps_dr) != 0 || !(eps_dr > 0.0) || eps_dr > 1e-2))
    cmn_input_error("stability: --eps: expected a number in (0, 0.01] (units of dr), got '%s'",
                    eps_arg);
  if (min_rate_arg && (cmn_parse_double(min_rate_arg, &min_rate) != 0 || !(min_rate >= 0.0)))
    cmn_input_error("stability: --min-rate: expected a number >= 0 (1/s), got '%s'", min_rate_arg);
  if (max_arg && cmn_parse_long(max_arg, 1, 1000000L, &max_unknowns) != 0)
    cmn_input_error("stability: --max-unknowns: expected a whole number in [1, 1000000], got '%s'",
                    max_arg);
  const int threads = sph_cli_threads(threads_arg, "stability");
  const double wall0 = cmn_wall_time();

  struct cmn_case *c = cmn_cli_load(&cli);
  const char *case_path = cli.case_path, *output = cli.output;
  /* from a checkpoint: its positions, densities and velocities, no repacking */
  const struct sph_cli_setup setup = {"stability", from == NULL, 1, max_unknowns};
  struct sph_solver *sv = sph_cli_solver(c, case_path, output, &setup);
  if (from) {
    char err[2048];
    struct sph_run_counters rc = {0.0, 0, NULL, 0, {{0}}, {0}};
    sph_run_counters_digest(&rc, c);
    if (sph_checkpoint_read(sv, &rc, from, err, sizeof err) != 0)
      cmn_input_error("stability: --from: %s", err);
    free(rc.output_times);
  }
  sph_solver_evaluate(sv); /* the accelerations of the state analysed */
  const int dim = sv->sys.dim;
  const size_t np = sv->sys.part[SPH_KIND_FLUID].n, n = np * (size_t)dim;
  int status = 0;
  const double eps = eps_dr * sv->sys.dr;
  double vmax0 = 0.0, amax0 = 0.0; /* how far the state is from rest: speeds and residual forces */
  for (size_t a = 0; a < np; a++) {
    double v2 = 0.0, a2 = 0.0;
    for (int c2 = 0; c2 < dim; c2++) {
      const double v = sv->sys.part[SPH_KIND_FLUID].v[c2][a];
      const double r = sv->acc[c2][a];
      v2 += v * v;
      a2 += r * r;
    }
    vmax0 = fmax(vmax0, sqrt(v2));
    amax0 = fmax(amax0, sqrt(a2));
  }
  cmn_message(
      "%dD: %zu fluid particles, %zu unknowns; %zu force evaluations (eps = %.3g m); %d "
      "thread%s",
      dim, np, n, 2 * n, eps, threads, threads > 1 ? "s" : "");
  double *J = cmn_malloc((n * n + 1) * sizeof *J), *amp = cmn_malloc((n * n + 1) * sizeof *amp);
  double *re = cmn_malloc((n + 1) * sizeof *re), *im = cmn_malloc((n + 1) * sizeof *im),
         *rate = cmn_malloc((n + 1) * sizeof *rate);
  sph_solver_jacobian(sv, eps, J);
  double asym = 0.0, sym = 0.0;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      const double d = J[i * n + j] - J[j * n + i], s = J[i * n + j] + J[j * n + i];
      asym += d * d;
      sym += s * s;
    }
  cmn_message("J formed (%.3g s); eigenvalues and eigenvectors...", cmn_wall_time() - wall0);
  struct mode *md = cmn_calloc(n + 1, sizeof *md);
  if (sph_stability_modes(n, J, re, im, rate, amp) != 0) {
    fprintf(stderr, "sabre-sph: stability: the eigensolver (GSL nonsymmv) did not converge\n");
    status = CMN_EXIT_FAILURE;
  } else {
    for (size_t j = 0; j < n; j++) {
      md[j].re = re[j];
      md[j].im = im[j];
      md[j].rate = rate[j];
      locate(&md[j], amp, n, j, dim);
    }
    qsort(md, n, sizeof *md, by_rate);
    /* modes growing slower than min_rate are not counted: the round-off of J splits degenerate
     * and neutral eigenvalues (symmetric lattices, periodic translations) into rates of order
     * 1e-8 1/s */
    size_t nstatic = 0, nflutter = 0;
    double lmax = -INFINITY, fmax = 0.0;
    for (size_t j = 0; j < n; j++) {
      if (md[j].im == 0.0 && md[j].rate > min_rate) nstatic++;
      if (md[j].im != 0.0 && md[j].rate > min_rate) {
        nflutter++;
        fmax = fmax > md[j].rate ? fmax : md[j].rate;
      }
      if (md[j].im == 0.0 && md[j].re > lmax) lmax = md[j].re;
    }
    const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
    printf("case: %s\n", case_path);
    if (from) printf("state: %s\n", from);
    printf("state at t = %.6g s (step %ld): largest speed %.4g m/s, largest |a| %.4g m/s^2\n",
           sv->time, sv->step, vmax0, amax0);
    printf("unknowns: %zu (%zu fluid particles x %d), eps = %.3g m\n", n, np, dim, eps);
    printf("asymmetry of J: |J - J^T| / |J + J^T| = %.3g\n", sqrt(asym / (sym > 0 ? sym : 1)));
    printf("static instabilities (real lambda > 0, growth above %g 1/s): %zu", min_rate, nstatic);
    if (nstatic > 0) printf(", largest lambda %.4g 1/s^2 (growth %.4g 1/s)", lmax, sqrt(lmax));
    printf(
        "\ngrowing oscillations (complex lambda, growth above %g 1/s, conjugates counted apart): "
        "%zu",
        min_rate, nflutter);
    if (nflutter > 0) printf(", fastest %.4g 1/s", fmax);
    printf("\nlargest growth rate: %.4g 1/s", md[0].rate);
    if (md[0].rate > 0.0) printf(" (e-folding time %.4g s)", 1.0 / md[0].rate);
    printf("\n");
    if (nprint > 0) {
      printf("%5s %12s %12s %10s %8s %10s %10s %10s %6s %6s %6s %6s %8s\n", "mode", "lambda_re",
             "lambda_im", "rate", "id", "x", "y", "z", "dir_x", "dir_y", "dir_z", "share",
             "particip");
      for (size_t j = 0; j < n && j < (size_t)nprint; j++) {
        const size_t a = md[j].particle;
        printf(
            "%5zu %12.5g %12.5g %10.4g %8lld %10.4g %10.4g %10.4g %6.3f %6.3f %6.3f %6.3f %8.1f\n",
            j + 1, md[j].re, md[j].im, md[j].rate, (long long)f->id[a], f->x[0][a], f->x[1][a],
            f->x[2][a], md[j].dir[0], md[j].dir[1], md[j].dir[2], md[j].share, md[j].participation);
      }
    }
    static const char *const names[] = {
        "mode",  "lambda_re", "lambda_im", "rate",  "id",           "x", "y", "z",
        "dir_x", "dir_y",     "dir_z",     "share", "participation"};
    char *path = sph_cli_join(output, "stability.csv");
    struct cmn_csv *csv = cmn_csv_open(path, 13, names);
    if (!csv) cmn_error("stability: cannot write '%s'", path);
    for (size_t j = 0; j < n; j++) {
      const size_t a = md[j].particle;
      const double row[13] = {(double)(j + 1),    md[j].re,     md[j].im,     md[j].rate,
                              (double)f->id[a],   f->x[0][a],   f->x[1][a],   f->x[2][a],
                              md[j].dir[0],       md[j].dir[1], md[j].dir[2], md[j].share,
                              md[j].participation};
      if (cmn_csv_row(csv, row) != 0) cmn_error("stability: cannot write '%s'", path);
    }
    if (cmn_csv_close(csv) != 0) cmn_error("stability: cannot write '%s'", path);
    cmn_message("done in %.3g s: %zu modes in %s", cmn_wall_time() - wall0, n, path);
    free(path);
  }
  free(md);
  free(J);
  free(amp);
  free(re);
  free(im);
  free(rate);
  sph_solver_free(sv);
  free(sv);
  cmn_case_free(c);
  return status != 0 ? status : cmn_stdout_status(0);
}
