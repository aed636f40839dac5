/*
 * `sabre-sph wave stokes5|solitary`: the wave generators of sabre/sph_waves.h at given points, one
 * JSON object per point on stdout (docs/sph-waves.md §4). A public diagnostic: keep its options and
 * output keys stable. Bad input exits with CMN_EXIT_INPUT and a message naming the option.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_waves.h"

static const char wave_usage[] =
    "usage: sabre-sph wave stokes5 --depth D (--height H | --amplitude A) (--length L | --period "
    "T)\n"
    "                              [--current U] [--rho0 R] [--g G] --at X,Z,T [--at ...]\n"
    "       sabre-sph wave solitary --depth D --amplitude A [--angle DEG] [--x0 X0] [--rho0 R]\n"
    "                               [--g G] --at X,Y,Z,T [--at ...]\n"
    "\n"
    "Print the wave at each point (x, [y,] z) and time t as one JSON object per line:\n"
    "  stokes5:  {\"x\", \"z\", \"t\", \"eta\", \"u\", \"w\", \"p\", \"c\", \"k\", \"L\", \"T\", "
    "\"in_water\"}\n"
    "  solitary: {\"x\", \"y\", \"z\", \"t\", \"eta\", \"u\", \"v\", \"w\", \"p\", \"c\", \"k\", "
    "\"in_water\"}\n"
    "The bed is z = 0, z points up. eta is the surface elevation above the bed (m); u, v, w the\n"
    "velocity in the fixed frame (m/s); p the gauge pressure (Pa, zero on the surface); c the "
    "phase\n"
    "speed (m/s); k the wave number (1/m); L, T the wave length (m) and period (s).\n"
    "\n"
    "stokes5: Fenton's (1985) fifth-order Stokes wave travelling towards +x, crest at x = c t.\n"
    "  --depth D       mean water depth (m)\n"
    "  --height H      crest-to-trough height (m), or --amplitude A = H/2\n"
    "  --length L      wave length (m), or --period T (s): the dispersion relation is solved\n"
    "  --current U     mean Eulerian current (Stokes' first definition, m/s), default 0\n"
    "  Valid for H/L <= 0.142 tanh(kd) (breaking) and H L^2/d^3 <= 20 (longer waves need a "
    "cnoidal\n"
    "  theory); outside these the command refuses the wave.\n"
    "solitary: the solitary wave of Joly et al. (2016), eqs. (42)-(47), eta = D + A sech^2(k xi),\n"
    "  xi = x cos(angle) + y sin(angle) - c t - x0, k = sqrt(3A/(4D^3)), c = sqrt(g(A + D)),\n"
    "  p = rho0 g (eta - z).\n"
    "  --depth D       still water depth (m)\n"
    "  --amplitude A   crest above the still water level (m), A/D <= 0.78\n"
    "  --angle DEG     direction of travel from +x towards +y (degrees), default 0\n"
    "  --x0 X0         crest position at t = 0 along the direction of travel (m), default 0\n"
    "Both: --rho0 R density (kg/m^3), default 1000; --g G gravity (m/s^2), default 9.81.\n"
    "Points above the surface or below the bed get \"in_water\": false (and a warning): their "
    "values\n"
    "are the formulas evaluated as written. Each option is given once; --at may repeat.\n"
    "See docs/sph-waves.md.\n";

/* A numeric option: its value, whether it was given, and what it expects. */
struct wave_opt {
  const char *name;
  const char *expect;
  int positive; /* 1: must be > 0 */
  int given;
  double value;
};

static struct wave_opt *find_opt(struct wave_opt *opts, size_t n, const char *name) {
  for (size_t i = 0; i < n; i++)
    if (strcmp(opts[i].name, name) == 0) return &opts[i];
  return NULL;
}

/* Parse argv[2..] into opts and the --at points (dim numbers each, allocated into *at; the caller
 * checks that there is at least one, after its required options). */
static void parse_options(const char *cmd, int argc, char **argv, struct wave_opt *opts, size_t n,
                          int dim, const char *at_form, double **at, size_t *nat) {
  *at = NULL;
  *nat = 0;
  for (int i = 2; i < argc; i++) {
    const char *o = argv[i];
    struct wave_opt *opt = find_opt(opts, n, o);
    if (opt == NULL && strcmp(o, "--at") != 0)
      cmn_input_error("%s: unknown option '%s' (see sabre-sph wave --help)", cmd, o);
    if (i + 1 >= argc) cmn_input_error("%s: %s needs a value (see sabre-sph wave --help)", cmd, o);
    const char *v = argv[++i];
    if (opt == NULL) { /* --at */
      double x[4];
      if (cmn_parse_doubles(v, x, dim) != dim)
        cmn_input_error("%s: --at '%s': expected %s (%d comma-separated numbers)", cmd, v, at_form,
                        dim);
      *at = cmn_realloc(*at, (*nat + 1) * (size_t)dim * sizeof **at);
      memcpy(*at + *nat * (size_t)dim, x, (size_t)dim * sizeof *x);
      (*nat)++;
      continue;
    }
    if (opt->given) cmn_input_error("%s: %s given twice: give each option once", cmd, o);
    opt->given = 1;
    if (cmn_parse_double(v, &opt->value) || (opt->positive && !(opt->value > 0.0)))
      cmn_input_error("%s: %s '%s': expected %s", cmd, o, v, opt->expect);
  }
}

static int wants_help(int argc, char **argv) {
  for (int i = 1; i < argc; i++)
    if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) return 1;
  return 0;
}

static void print_number(const char *key, double v) {
  if (isfinite(v))
    printf("\"%s\": %.17g", key, v);
  else
    printf("\"%s\": null", key);
}

/* One output line: the JSON object of the given keys and values, then "in_water"; a point outside
 * the water is still evaluated, with a warning naming its --at (the first nx values). */
static void print_point(const char *const *keys, const double *vals, size_t n, size_t nx,
                        int status, double eta) {
  if (status == SPH_WAVE_EOUTSIDE) {
    char at[160] = "";
    size_t len = 0;
    for (size_t j = 0; j < nx && len < sizeof at; j++)
      len += (size_t)snprintf(at + len, sizeof at - len, "%s%g", j ? "," : "", vals[j]);
    cmn_warning("--at %s: the point is %s (eta = %.6g m): values evaluated as written", at,
                vals[nx - 2] < 0.0 ? "below the bed" : "above the free surface", eta);
  }
  printf("{");
  for (size_t j = 0; j < n; j++) {
    if (j) printf(", ");
    print_number(keys[j], vals[j]);
  }
  printf(", \"in_water\": %s}\n", status == SPH_WAVE_SUCCESS ? "true" : "false");
}

/* The library's "<field>: why" as "--<field>: why" (the fields are named as the options). */
static _Noreturn void library_error(const char *cmd, const char *msg, int amplitude_given) {
  if (amplitude_given && strncmp(msg, "height:", 7) == 0)
    cmn_input_error("%s: --amplitude (H = 2A):%s", cmd, msg + 7);
  cmn_input_error("%s: --%s", cmd, msg);
}

static int cmd_stokes5(int argc, char **argv) {
  const char *cmd = "wave stokes5";
  struct wave_opt opts[] = {
      {"--depth", "a positive number (mean water depth, m)", 1, 0, 0},
      {"--height", "a positive number (crest-to-trough height, m)", 1, 0, 0},
      {"--amplitude", "a positive number (half the height, m)", 1, 0, 0},
      {"--length", "a positive number (wave length, m)", 1, 0, 0},
      {"--period", "a positive number (period, s)", 1, 0, 0},
      {"--current", "a number (mean Eulerian current, m/s)", 0, 0, 0},
      {"--rho0", "a positive number (density, kg/m^3)", 1, 0, 0},
      {"--g", "a positive number (gravity, m/s^2)", 1, 0, 0},
  };
  const size_t n = sizeof opts / sizeof opts[0];
  double *at;
  size_t nat;
  parse_options(cmd, argc, argv, opts, n, 3, "X,Z,T", &at, &nat);
  struct sph_stokes5_params p;
  sph_stokes5_params_init(&p);
  struct wave_opt *o = find_opt(opts, n, "--depth");
  if (!o->given) cmn_input_error("%s needs --depth D (mean water depth, m)", cmd);
  p.depth = o->value;
  struct wave_opt *oh = find_opt(opts, n, "--height"), *oa = find_opt(opts, n, "--amplitude");
  if (oh->given == oa->given)
    cmn_input_error("%s needs one of --height H or --amplitude A (= H/2), not %s", cmd,
                    oh->given ? "both" : "neither");
  p.height = oh->given ? oh->value : 2.0 * oa->value;
  struct wave_opt *ol = find_opt(opts, n, "--length"), *ot = find_opt(opts, n, "--period");
  if (ol->given == ot->given)
    cmn_input_error("%s needs one of --length L or --period T, not %s", cmd,
                    ol->given ? "both" : "neither");
  p.length = ol->given ? ol->value : 0.0;
  p.period = ot->given ? ot->value : 0.0;
  if ((o = find_opt(opts, n, "--current"))->given) p.current = o->value;
  if ((o = find_opt(opts, n, "--rho0"))->given) p.rho0 = o->value;
  if ((o = find_opt(opts, n, "--g"))->given) p.g = o->value;
  if (nat == 0) cmn_input_error("%s needs at least one --at X,Z,T", cmd);

  struct sph_stokes5 w;
  char msg[512];
  if (sph_stokes5_init(&w, &p, msg, sizeof msg) != SPH_WAVE_SUCCESS)
    library_error(cmd, msg, oa->given);
  for (size_t i = 0; i < nat; i++) {
    const double *x = at + 3 * i;
    struct sph_wave_point pt;
    const int status = sph_stokes5_eval(&w, x[0], x[1], x[2], &pt);
    const char *keys[] = {"x", "z", "t", "eta", "u", "w", "p", "c", "k", "L", "T"};
    const double vals[] = {x[0], x[1], x[2], pt.eta, pt.u, pt.w, pt.p, w.c, w.k, w.L, w.T};
    print_point(keys, vals, sizeof keys / sizeof keys[0], 3, status, pt.eta);
  }
  free(at);
  return 0;
}

static int cmd_solitary(int argc, char **argv) {
  const char *cmd = "wave solitary";
  struct wave_opt opts[] = {
      {"--depth", "a positive number (still water depth, m)", 1, 0, 0},
      {"--amplitude", "a positive number (crest above the still level, m)", 1, 0, 0},
      {"--angle", "a number (direction of travel, degrees)", 0, 0, 0},
      {"--x0", "a number (crest position at t = 0, m)", 0, 0, 0},
      {"--rho0", "a positive number (density, kg/m^3)", 1, 0, 0},
      {"--g", "a positive number (gravity, m/s^2)", 1, 0, 0},
  };
  const size_t n = sizeof opts / sizeof opts[0];
  double *at;
  size_t nat;
  parse_options(cmd, argc, argv, opts, n, 4, "X,Y,Z,T", &at, &nat);
  struct sph_solitary_params p;
  sph_solitary_params_init(&p);
  struct wave_opt *o = find_opt(opts, n, "--depth");
  if (!o->given) cmn_input_error("%s needs --depth D (still water depth, m)", cmd);
  p.depth = o->value;
  if (!(o = find_opt(opts, n, "--amplitude"))->given)
    cmn_input_error("%s needs --amplitude A (crest above the still water level, m)", cmd);
  p.amplitude = o->value;
  if ((o = find_opt(opts, n, "--angle"))->given) p.angle = o->value * (M_PI / 180.0);
  if ((o = find_opt(opts, n, "--x0"))->given) p.x0 = o->value;
  if ((o = find_opt(opts, n, "--rho0"))->given) p.rho0 = o->value;
  if ((o = find_opt(opts, n, "--g"))->given) p.g = o->value;
  if (nat == 0) cmn_input_error("%s needs at least one --at X,Y,Z,T", cmd);

  struct sph_solitary s;
  char msg[512];
  if (sph_solitary_init(&s, &p, msg, sizeof msg) != SPH_WAVE_SUCCESS) library_error(cmd, msg, 0);
  for (size_t i = 0; i < nat; i++) {
    const double *x = at + 4 * i;
    struct sph_wave_point pt;
    const int status = sph_solitary_eval(&s, x[0], x[1], x[2], x[3], &pt);
    const char *keys[] = {"x", "y", "z", "t", "eta", "u", "v", "w", "p", "c", "k"};
    const double vals[] = {x[0], x[1], x[2], x[3], pt.eta, pt.u, pt.v, pt.w, pt.p, s.c, s.k};
    print_point(keys, vals, sizeof keys / sizeof keys[0], 4, status, pt.eta);
  }
  free(at);
  return 0;
}

int sph_cmd_wave(int argc, char **argv) {
  gsl_set_error_handler_off(); /* GSL failures come back as statuses (sabre/sph_waves.h) */
  if (wants_help(argc, argv)) {
    fputs(wave_usage, stdout);
    return cmn_stdout_status(0);
  }
  if (argc < 2)
    cmn_input_error("wave needs a kind: stokes5 or solitary (see sabre-sph wave --help)");
  if (strcmp(argv[1], "stokes5") == 0) return cmn_stdout_status(cmd_stokes5(argc, argv));
  if (strcmp(argv[1], "solitary") == 0) return cmn_stdout_status(cmd_solitary(argc, argv));
  cmn_input_error(
      "wave: unknown kind '%s' (expected stokes5 or solitary; see sabre-sph wave --help)", argv[1]);
}
