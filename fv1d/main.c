/* sabre-fv1d: the 1D finite-volume reference solver.
 *   sabre-fv1d CASE.yaml [--set key=value]... [--output DIR] [--quiet]
 *   sabre-fv1d --version
 *   sabre-fv1d riemann --xi X --rho0 R --c0 C --left RHO,U --right RHO,U --cells N --time T
 *                      [--flux godunov|hll|rusanov] [--reconstruction none|minmod|mc] [--cfl K]
 *                      [--domain A:B] [--x0 X0] --output FILE.csv
 * Bad command lines and case files end with a one-line error and exit status 2; failed runs with
 * exit status 1; a run stopped at time.max_steps with exit status 3 (CMN_EXIT_INCOMPLETE). */
#include <errno.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <sabre/fv1d.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char usage[] =
    "usage: sabre-fv1d CASE.yaml [--set key=value]... [--output DIR] [--quiet]\n"
    "       sabre-fv1d riemann --xi X --rho0 R --c0 C --left RHO,U --right RHO,U --cells N\n"
    "                  --time T [--flux godunov|hll|rusanov] [--reconstruction none|minmod|mc]\n"
    "                  [--cfl K] [--domain A:B] [--x0 X0] --output FILE.csv\n"
    "       sabre-fv1d --version\n"
    "Each option is given once (--set may repeat). 1 <= X <= 100. A CASE run stopped at\n"
    "time.max_steps before time.end exits with status 3 (outputs complete up to there).\n"
    "See docs/fv1d.md for the case-file keys and the outputs.\n";

static int choice_index(const char *const *names, const char *value) {
  for (int k = 0; names[k]; ++k)
    if (strcmp(names[k], value) == 0) return k;
  return -1;
}

static double parse_number(const char *flag, const char *text) {
  double v;
  if (cmn_parse_double(text, &v) != 0)
    cmn_input_error("%s: expected a number, got '%s'", flag, text);
  return v;
}

static int run_riemann(int argc, char **argv) {
  double xi = NAN, rho0 = NAN, c0 = NAN, t_end = NAN, cfl = 0.5, x0 = 0.0, a = -0.5, b = 0.5;
  double left[2], right[2];
  int have_left = 0, have_right = 0;
  long cells = 0;
  const char *output = NULL;
  struct fv1d_params p;
  fv1d_params_default(&p);
  for (int k = 2; k < argc; ++k) {
    const char *flag = argv[k];
    if (strcmp(flag, "--help") == 0 || strcmp(flag, "-h") == 0) {
      fputs(usage, stdout);
      return cmn_stdout_status(0);
    }
    if (k + 1 >= argc) cmn_input_error("%s: missing value (see --help)", flag);
    /* each option once: a second value would silently replace the first */
    for (int j = 2; j < k; j += 2)
      if (strcmp(argv[j], flag) == 0)
        cmn_input_error("%s given twice: give each option once", flag);
    const char *v = argv[++k];
    if (strcmp(flag, "--xi") == 0)
      xi = parse_number(flag, v);
    else if (strcmp(flag, "--rho0") == 0)
      rho0 = parse_number(flag, v);
    else if (strcmp(flag, "--c0") == 0)
      c0 = parse_number(flag, v);
    else if (strcmp(flag, "--time") == 0)
      t_end = parse_number(flag, v);
    else if (strcmp(flag, "--cfl") == 0)
      cfl = parse_number(flag, v);
    else if (strcmp(flag, "--x0") == 0)
      x0 = parse_number(flag, v);
    else if (strcmp(flag, "--left") == 0 || strcmp(flag, "--right") == 0) {
      double *st = flag[2] == 'l' ? left : right;
      if (cmn_parse_doubles(v, st, 2) != 2)
        cmn_input_error("%s: expected RHO,U (two numbers), got '%s'", flag, v);
      if (!(st[0] > 0.0)) cmn_input_error("%s: density must be positive, got %g", flag, st[0]);
      *(flag[2] == 'l' ? &have_left : &have_right) = 1;
    } else if (strcmp(flag, "--cells") == 0) {
      if (cmn_parse_long(v, 2, 100000000L, &cells) != 0)
        cmn_input_error("--cells: expected an integer in [2, 1e8], got '%s'", v);
    } else if (strcmp(flag, "--flux") == 0) {
      int i = choice_index(fv1d_flux_names, v);
      if (i < 0) cmn_input_error("--flux: expected godunov, hll or rusanov, got '%s'", v);
      p.flux = (enum fv1d_flux)i;
    } else if (strcmp(flag, "--reconstruction") == 0) {
      int i = choice_index(fv1d_recon_names, v);
      if (i < 0) cmn_input_error("--reconstruction: expected none, minmod or mc, got '%s'", v);
      p.recon = (enum fv1d_recon)i;
    } else if (strcmp(flag, "--domain") == 0) {
      char *end;
      a = strtod(v, &end);
      if (end == v || *end != ':' || cmn_parse_double(end + 1, &b) != 0 || !isfinite(a))
        cmn_input_error("--domain: expected A:B, got '%s'", v);
    } else if (strcmp(flag, "--output") == 0)
      output = v;
    else
      cmn_input_error("unknown option '%s' (see --help)", flag);
  }
  if (isnan(xi) || isnan(rho0) || isnan(c0) || isnan(t_end) || !have_left || !have_right ||
      cells == 0 || !output)
    cmn_input_error(
        "riemann: --xi, --rho0, --c0, --left, --right, --cells, --time and --output "
        "are required (see --help)");
  /* xi in [1, 100], as fluid.xi in a case file */
  if (!(xi <= 100.0) || rmn_eos_init(&p.eos, rho0, c0, xi) != RMN_SUCCESS)
    cmn_input_error("riemann: need rho0 > 0, c0 > 0 and 1 <= xi <= 100 (got %g, %g, %g)", rho0, c0,
                    xi);
  if (!(t_end > 0.0)) cmn_input_error("--time: must be positive, got %g", t_end);
  if (!(cfl > 0.0 && cfl <= 2.0)) cmn_input_error("--cfl: must lie in (0, 2], got %g", cfl);
  if (!(b > a)) cmn_input_error("--domain: B must exceed A (got %g:%g)", a, b);
  if (cfl > 1.0)
    cmn_warning(
        "--cfl %g: beyond 1 the fixed explicit step is unstable for every flux; expect a "
        "blow-up, or use --cfl <= 1",
        cfl);
  p.x_min = a, p.x_max = b, p.cells = cells, p.cfl = cfl, p.t_end = t_end, p.progress = 0;
  struct fv1d_region regions[2] = {{-INFINITY, x0, left[0], left[1]},
                                   {x0, INFINITY, right[0], right[1]}};
  p.initial.rho = left[0], p.initial.u = left[1];
  p.initial.regions = regions, p.initial.nregions = 2;
  double tout = t_end;
  p.output_times = &tout, p.noutput = 1;

  struct fv1d_solver *s = fv1d_solver_create(&p);
  struct fv1d_stats stats;
  if (fv1d_integrate(s, NULL, NULL, &stats) != 0) cmn_error("run failed: %s", fv1d_solver_error(s));
  if (fv1d_output_profile(s, output) != 0)
    cmn_error("cannot write '%s': %s", output, strerror(errno));
  fv1d_solver_destroy(s);
  return 0;
}

int main(int argc, char **argv) {
  cmn_set_program_name("sabre-fv1d");
  gsl_set_error_handler_off();
  if (argc >= 2 && strcmp(argv[1], "riemann") == 0) return run_riemann(argc, argv);

  const char *quiet = NULL;
  const struct cmn_cli_option options[] = {{"--quiet", &quiet, 1}};
  struct cmn_cli cli;
  if (cmn_cli_parse(&cli, argc, argv, NULL, usage, "fv1d-output", options, 1))
    return cmn_stdout_status(0); /* --help or --version */
  const char *case_path = cli.case_path, *output = cli.output;
  struct cmn_case *c = cmn_cli_load(&cli);
  char base_dir[4096];
  snprintf(base_dir, sizeof base_dir, "%s", case_path);
  char *slash = strrchr(base_dir, '/');
  if (slash)
    *slash = '\0';
  else
    snprintf(base_dir, sizeof base_dir, ".");
  struct fv1d_params p;
  fv1d_case_read(c, base_dir, &p); /* fatal mode: exits with the message on bad input */
  if (quiet) p.progress = 0;
  cmn_cli_write_used(c, output);

  struct fv1d_solver *s = fv1d_solver_create(&p);
  struct fv1d_output *out = fv1d_output_open(output, s);
  if (!out) cmn_error("%s", fv1d_solver_error(s));
  struct fv1d_stats stats;
  int status = fv1d_integrate(s, fv1d_output_observer, out, &stats);
  if (fv1d_output_close(out, &stats, status) != 0)
    cmn_error("cannot write the outputs in '%s'", output);
  if (status < 0) cmn_error("run failed: %s", fv1d_solver_error(s));
  if (status > 0) /* time.max_steps: outputs complete up to the time reached */
    cmn_message("%s; outputs up to that time in %s", fv1d_solver_error(s), output);
  if (!quiet)
    cmn_message(
        "%ld steps, %ld RHS evaluations, %.3g s wall, %.3g cell updates/s per stage; "
        "outputs in %s",
        stats.steps, stats.rhs_evals, stats.wall_time,
        stats.wall_time > 0 ? (double)p.cells * (double)stats.rhs_evals / stats.wall_time : 0.0,
        output);
  fv1d_solver_destroy(s);
  fv1d_params_free(&p);
  cmn_case_free(c);
  return status > 0 ? CMN_EXIT_INCOMPLETE : 0;
}
