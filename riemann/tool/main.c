/*
 * sabre-riemann — unit studies of boundary and full Riemann problems (JSON/CSV on stdout).
 *
 *   sabre-riemann boundary --xi X --rho0 R --c0 C --interior RHO,UN[,UT1[,UT2]]
 *                          (--pressure P | --velocity UN) [--tangential UT1[,UT2]]
 *                          [--shock exact|linearised] [--tol T] [--max-iter N]
 *   sabre-riemann exact --xi X --rho0 R --c0 C --left RHO,U --right RHO,U [--at S]...
 *   sabre-riemann sweep --xi X --rho0 R --c0 C --rho-int R --un-int A:B:N
 *                       (--pressure A:B:N | --velocity A:B:N) [--shock exact|linearised]
 *
 * and `sabre-riemann --version`; --help after any command prints the usage. The interface is public
 * and stable. Bad input (including a repeated option): one line on stderr, exit 2. Solver failure
 * (non-convergence) or an output error: exit 1. This tool depends on the riemann/ library only.
 */
#include <errno.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/riemann.h"

#define EXIT_INPUT 2
#define MAX_AT 1024

static _Noreturn __attribute__((format(printf, 1, 2))) void die_input(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("sabre-riemann: error: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  exit(EXIT_INPUT);
}

static _Noreturn void die_status(const char *what, int status) {
  fprintf(stderr, "sabre-riemann: error: %s: %s (%s)%s\n", what, rmn_strerror(status),
          rmn_status_name(status),
          status == RMN_ENOCONV ? "; a very strong shock? try --max-iter or a weaker jump" : "");
  exit(status == RMN_ENOCONV || status == RMN_ENOMEM ? EXIT_FAILURE : EXIT_INPUT);
}

static double parse_number(const char *flag, const char *text) {
  char *end;
  errno = 0;
  double v = strtod(text, &end);
  if (end == text || *end != '\0' || errno == ERANGE || !isfinite(v))
    die_input("%s: expected a finite number, got '%s'", flag, text);
  return v;
}

/* Comma-separated list of between lo and hi numbers; returns the count. Every item must be a
 * number: "1000,,5" is an error, not the list 1000,5. */
static int parse_list(const char *flag, const char *text, double *v, int lo, int hi) {
  char buf[512];
  if (strlen(text) >= sizeof buf) die_input("%s: value too long", flag);
  strcpy(buf, text);
  int n = 0;
  for (char *tok = buf;;) {
    char *comma = strchr(tok, ',');
    if (comma) *comma = '\0';
    if (*tok == '\0')
      die_input("%s: empty item in '%s' (expected %d to %d comma-separated numbers)", flag, text,
                lo, hi);
    if (n == hi)
      die_input("%s: expected at most %d comma-separated numbers, got '%s'", flag, hi, text);
    v[n++] = parse_number(flag, tok);
    if (!comma) break;
    tok = comma + 1;
  }
  if (n < lo)
    die_input("%s: expected %d to %d comma-separated numbers, got '%s'", flag, lo, hi, text);
  return n;
}

/* Every option may be given once (except --at): a repeated option is an error rather than a
 * silent override of the first value. */
static void check_once(const char *flag) {
  static const char *seen[64];
  static int nseen = 0;
  if (!strcmp(flag, "--at")) return;
  for (int k = 0; k < nseen; ++k)
    if (!strcmp(seen[k], flag)) die_input("%s given twice: give each option once", flag);
  if (nseen < 64) seen[nseen++] = flag;
}

/* A:B:N range with N ≥ 1 points (N = 1 gives A). */
struct range {
  double a, b;
  long n;
};

static struct range parse_range(const char *flag, const char *text) {
  char buf[256];
  if (strlen(text) >= sizeof buf) die_input("%s: value too long", flag);
  strcpy(buf, text);
  char *c1 = strchr(buf, ':');
  char *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
  if (!c1 || !c2 || strchr(c2 + 1, ':')) die_input("%s: expected A:B:N, got '%s'", flag, text);
  *c1 = *c2 = '\0';
  struct range r = {parse_number(flag, buf), parse_number(flag, c1 + 1), 0};
  char *end;
  errno = 0;
  r.n = strtol(c2 + 1, &end, 10);
  if (end == c2 + 1 || *end || errno || r.n < 1 || r.n > 100000)
    die_input("%s: expected a point count N in [1, 100000] in A:B:N, got '%s'", flag, text);
  return r;
}

static double range_at(const struct range *r, long i) {
  return r->n == 1 ? r->a : r->a + (r->b - r->a) * (double)i / (double)(r->n - 1);
}

static void print_number(double v) {
  if (isfinite(v))
    printf("%.17g", v);
  else
    fputs("null", stdout);
}

/* Options shared by all subcommands. */
struct options {
  double xi, rho0, c0;
  int have_xi, have_rho0, have_c0;
  struct rmn_params params;
};

static const char *need_value(int argc, char **argv, int *i) {
  check_once(argv[*i]);
  if (*i + 1 >= argc) die_input("%s: missing value", argv[*i]);
  return argv[++*i];
}

/* Consume a common option at argv[*i]; 1 if consumed. */
static int common_option(int argc, char **argv, int *i, struct options *o) {
  const char *f = argv[*i];
  if (!strcmp(f, "--xi")) {
    o->xi = parse_number(f, need_value(argc, argv, i));
    o->have_xi = 1;
  } else if (!strcmp(f, "--rho0")) {
    o->rho0 = parse_number(f, need_value(argc, argv, i));
    o->have_rho0 = 1;
  } else if (!strcmp(f, "--c0")) {
    o->c0 = parse_number(f, need_value(argc, argv, i));
    o->have_c0 = 1;
  } else if (!strcmp(f, "--shock")) {
    const char *v = need_value(argc, argv, i);
    if (!strcmp(v, "exact"))
      o->params.shock = RMN_SHOCK_EXACT;
    else if (!strcmp(v, "linearised"))
      o->params.shock = RMN_SHOCK_LINEARISED;
    else
      die_input("--shock: expected 'exact' or 'linearised', got '%s'", v);
  } else if (!strcmp(f, "--tol")) {
    o->params.tol_rel = parse_number(f, need_value(argc, argv, i));
  } else if (!strcmp(f, "--max-iter")) {
    double v = parse_number(f, need_value(argc, argv, i));
    if (v != floor(v) || v < 1 || v > 1e6) die_input("--max-iter: expected an integer in [1, 1e6]");
    o->params.max_iter = (int)v;
  } else {
    return 0;
  }
  return 1;
}

static struct rmn_eos make_eos(const struct options *o) {
  if (!o->have_xi) die_input("missing --xi (Tait exponent, >= 1)");
  if (!o->have_rho0) die_input("missing --rho0 (reference density, kg/m^3, > 0)");
  if (!o->have_c0) die_input("missing --c0 (reference sound speed, m/s, > 0)");
  /* The range of fv1d's and sph's fluid.xi: beyond 100 the EOS is stiffer than any liquid. */
  if (o->xi < 1.0 || o->xi > 100.0) die_input("--xi: expected a number in [1, 100], got %g", o->xi);
  if (o->rho0 <= 0.0) die_input("--rho0: expected a number > 0, got %g", o->rho0);
  if (o->c0 <= 0.0) die_input("--c0: expected a number > 0, got %g", o->c0);
  if (rmn_params_check(&o->params) != RMN_SUCCESS)
    die_input("--tol must lie in (0, 1e-2] and --max-iter be >= 1");
  struct rmn_eos eos;
  rmn_eos_init(&eos, o->rho0, o->c0, o->xi);
  return eos;
}

/*
 * Bounds of the data (input errors, exit 2): densities up to RHO_MAX_RATIO ρ0, speeds up to
 * U_MAX_RATIO c0, imposed pressures up to p(RHO_MAX_RATIO ρ0). Far beyond any weakly-compressible
 * flow, and inside the range where the solvers converge, so that a solver failure (exit 1) is
 * never the answer to a typo such as --pressure 1e300.
 */
#define RHO_MAX_RATIO 100.0
#define U_MAX_RATIO 100.0

static void check_density(const struct rmn_eos *eos, const char *flag, double rho) {
  if (rho > RHO_MAX_RATIO * eos->rho0)
    die_input("%s: density %g kg/m^3 is beyond %g rho0 = %g kg/m^3", flag, rho, RHO_MAX_RATIO,
              RHO_MAX_RATIO * eos->rho0);
}

static void check_velocity(const struct rmn_eos *eos, const char *flag, double u) {
  if (fabs(u) > U_MAX_RATIO * eos->c0)
    die_input("%s: velocity %g m/s is beyond %g c0 = %g m/s in magnitude", flag, u, U_MAX_RATIO,
              U_MAX_RATIO * eos->c0);
}

static void check_pressure(const struct rmn_eos *eos, const char *flag, double p) {
  double pmax = rmn_eos_pressure(eos, RHO_MAX_RATIO * eos->rho0);
  if (p > pmax)
    die_input("%s: pressure %g Pa is beyond p(%g rho0) = %g Pa", flag, p, RHO_MAX_RATIO, pmax);
}

static _Noreturn void unknown(const char *cmd, const char *flag) {
  die_input("%s: unknown option '%s' (see sabre-riemann --help)", cmd, flag);
}

static int cmd_boundary(int argc, char **argv, struct options *o) {
  double interior[4], tangential[2] = {0.0, 0.0}, value = 0.0;
  int n_interior = 0, n_tangential = -1, imposed = -1;
  for (int i = 2; i < argc; ++i) {
    const char *f = argv[i];
    if (common_option(argc, argv, &i, o)) continue;
    if (!strcmp(f, "--interior")) {
      n_interior = parse_list(f, need_value(argc, argv, &i), interior, 2, 4);
    } else if (!strcmp(f, "--pressure") || !strcmp(f, "--velocity")) {
      if (imposed >= 0) die_input("give exactly one of --pressure and --velocity");
      imposed = !strcmp(f, "--pressure") ? RMN_IMPOSE_PRESSURE : RMN_IMPOSE_VELOCITY;
      value = parse_number(f, need_value(argc, argv, &i));
    } else if (!strcmp(f, "--tangential")) {
      n_tangential = parse_list(f, need_value(argc, argv, &i), tangential, 1, 2);
    } else {
      unknown("boundary", f);
    }
  }
  struct rmn_eos eos = make_eos(o);
  if (n_interior == 0) die_input("boundary: missing --interior RHO,UN[,UT1[,UT2]]");
  if (imposed < 0) die_input("boundary: give one of --pressure P or --velocity UN");
  const int dim = n_interior - 1;
  if (n_tangential >= 0 && n_tangential != dim - 1)
    die_input("--tangential: expected %d value(s) for a %dD interior state, got %d", dim - 1, dim,
              n_tangential);
  if (interior[0] <= 0.0) die_input("--interior: density must be > 0, got %g", interior[0]);
  check_density(&eos, "--interior", interior[0]);
  for (int k = 1; k < n_interior; ++k) check_velocity(&eos, "--interior", interior[k]);
  for (int k = 0; k < n_tangential; ++k) check_velocity(&eos, "--tangential", tangential[k]);
  if (imposed == RMN_IMPOSE_PRESSURE)
    check_pressure(&eos, "--pressure", value);
  else
    check_velocity(&eos, "--velocity", value);

  /* The normal is the x axis, so local (n, t1, t2) components are the given ones. */
  struct rmn_boundary_input in = {.normal = {1.0, 0.0, 0.0},
                                  .rho = interior[0],
                                  .imposed = (enum rmn_imposed)imposed,
                                  .value = value,
                                  .ut = {tangential[0], tangential[1]}};
  for (int k = 0; k < dim; ++k) in.u[k] = interior[1 + k];
  struct rmn_workspace *ws = rmn_workspace_alloc();
  if (!ws) die_status("workspace", RMN_ENOMEM);
  struct rmn_boundary_result r;
  int st = rmn_boundary_solve(&eos, &o->params, ws, dim, &in, &r);
  rmn_workspace_free(ws);
  if (st != RMN_SUCCESS) die_status("boundary", st);
  printf("{\"wave\": \"%s\", \"flow\": \"%s\", \"rho\": ", rmn_wave_name(r.wave),
         rmn_flow_name(r.flow));
  print_number(r.rho);
  fputs(", \"p\": ", stdout);
  print_number(r.p);
  fputs(", \"un\": ", stdout);
  print_number(r.un);
  fputs(", \"ut\": [", stdout);
  for (int k = 0; k < dim - 1; ++k) {
    if (k) fputs(", ", stdout);
    print_number(r.ut[k]);
  }
  fputs("], \"shock_speed\": ", stdout);
  print_number(r.shock_speed);
  fputs("}\n", stdout);
  return 0;
}

static int cmd_exact(int argc, char **argv, struct options *o) {
  double left[2], right[2];
  int have_left = 0, have_right = 0, n_at = 0;
  static double at[MAX_AT];
  for (int i = 2; i < argc; ++i) {
    const char *f = argv[i];
    if (common_option(argc, argv, &i, o)) continue;
    if (!strcmp(f, "--left")) {
      parse_list(f, need_value(argc, argv, &i), left, 2, 2);
      have_left = 1;
    } else if (!strcmp(f, "--right")) {
      parse_list(f, need_value(argc, argv, &i), right, 2, 2);
      have_right = 1;
    } else if (!strcmp(f, "--at")) {
      if (n_at == MAX_AT) die_input("--at: at most %d sample points", MAX_AT);
      at[n_at++] = parse_number(f, need_value(argc, argv, &i));
    } else {
      unknown("exact", f);
    }
  }
  struct rmn_eos eos = make_eos(o);
  if (!have_left) die_input("exact: missing --left RHO,U");
  if (!have_right) die_input("exact: missing --right RHO,U");
  if (left[0] < 0.0 || right[0] < 0.0)
    die_input("exact: densities must be >= 0 (0 is a dry state)");
  if (left[0] == 0.0 && right[0] == 0.0) die_input("exact: both states are dry");
  check_density(&eos, "--left", left[0]);
  check_density(&eos, "--right", right[0]);
  check_velocity(&eos, "--left", left[1]);
  check_velocity(&eos, "--right", right[1]);
  struct rmn_workspace *ws = rmn_workspace_alloc();
  if (!ws) die_status("workspace", RMN_ENOMEM);
  struct rmn_exact sol;
  int st = rmn_exact_solve(&eos, &o->params, ws, left[0], left[1], right[0], right[1], &sol);
  rmn_workspace_free(ws);
  if (st != RMN_SUCCESS) die_status("exact", st);
  fputs("{\"rho_star\": ", stdout);
  print_number(sol.rho_star);
  fputs(", \"u_star\": ", stdout);
  print_number(sol.u_star);
  fputs(", \"p_star\": ", stdout);
  print_number(sol.p_star);
  printf(", \"waves\": [\"%s\", \"%s\"], \"vacuum\": %s, \"speeds\": [",
         rmn_exact_wave_name(sol.left), rmn_exact_wave_name(sol.right),
         sol.vacuum ? "true" : "false");
  const double speeds[4] = {sol.left_head, sol.left_tail, sol.right_tail, sol.right_head};
  for (int k = 0; k < 4; ++k) {
    if (k) fputs(", ", stdout);
    print_number(speeds[k]);
  }
  fputs("], \"samples\": [", stdout);
  for (int k = 0; k < n_at; ++k) {
    double rho, u;
    rmn_exact_sample(&sol, at[k], &rho, &u);
    fputs(k ? ", {\"s\": " : "{\"s\": ", stdout);
    print_number(at[k]);
    fputs(", \"rho\": ", stdout);
    print_number(rho);
    fputs(", \"u\": ", stdout);
    print_number(rho > 0.0 ? u : NAN);
    fputs(", \"p\": ", stdout);
    print_number(rmn_eos_pressure(&eos, rho));
    fputc('}', stdout);
  }
  fputs("]}\n", stdout);
  return 0;
}

static int cmd_sweep(int argc, char **argv, struct options *o) {
  double rho_int = 0.0;
  int have_rho = 0, have_un = 0, imposed = -1;
  struct range un = {0}, val = {0};
  for (int i = 2; i < argc; ++i) {
    const char *f = argv[i];
    if (common_option(argc, argv, &i, o)) continue;
    if (!strcmp(f, "--rho-int")) {
      rho_int = parse_number(f, need_value(argc, argv, &i));
      have_rho = 1;
    } else if (!strcmp(f, "--un-int")) {
      un = parse_range(f, need_value(argc, argv, &i));
      have_un = 1;
    } else if (!strcmp(f, "--pressure") || !strcmp(f, "--velocity")) {
      if (imposed >= 0) die_input("give exactly one of --pressure and --velocity");
      imposed = !strcmp(f, "--pressure") ? RMN_IMPOSE_PRESSURE : RMN_IMPOSE_VELOCITY;
      val = parse_range(f, need_value(argc, argv, &i));
    } else {
      unknown("sweep", f);
    }
  }
  struct rmn_eos eos = make_eos(o);
  if (!have_rho) die_input("sweep: missing --rho-int RHO");
  if (rho_int <= 0.0) die_input("--rho-int: expected a density > 0, got %g", rho_int);
  if (!have_un) die_input("sweep: missing --un-int A:B:N");
  if (imposed < 0) die_input("sweep: give one of --pressure A:B:N or --velocity A:B:N");
  if (un.n * val.n > 10000000L) die_input("sweep: at most 1e7 grid points");
  check_density(&eos, "--rho-int", rho_int);
  check_velocity(&eos, "--un-int", un.a);
  check_velocity(&eos, "--un-int", un.b);
  if (imposed == RMN_IMPOSE_PRESSURE) {
    check_pressure(&eos, "--pressure", val.a);
    check_pressure(&eos, "--pressure", val.b);
  } else {
    check_velocity(&eos, "--velocity", val.a);
    check_velocity(&eos, "--velocity", val.b);
  }
  struct rmn_workspace *ws = rmn_workspace_alloc();
  if (!ws) die_status("workspace", RMN_ENOMEM);
  printf("imposed,value,rho_int,un_int,status,wave,flow,rho,p,un,shock_speed\n");
  for (long j = 0; j < un.n; ++j) {
    for (long i = 0; i < val.n; ++i) {
      double v = range_at(&val, i), u = range_at(&un, j);
      struct rmn_normal_state s;
      int st = rmn_boundary_solve_normal(&eos, &o->params, ws, rho_int, u,
                                         (enum rmn_imposed)imposed, v, &s);
      printf("%s,%.17g,%.17g,%.17g,%s,", imposed == RMN_IMPOSE_PRESSURE ? "pressure" : "velocity",
             v, rho_int, u, rmn_status_name(st));
      if (st == RMN_SUCCESS)
        printf("%s,%s,%.17g,%.17g,%.17g,%.17g\n", rmn_wave_name(s.wave), rmn_flow_name(s.flow),
               s.rho, s.p, s.un, s.shock_speed);
      else
        printf(",,nan,nan,nan,nan\n");
    }
  }
  rmn_workspace_free(ws);
  return 0;
}

static void usage(FILE *out) {
  fputs(
      "usage:\n"
      "  sabre-riemann boundary --xi X --rho0 R --c0 C --interior RHO,UN[,UT1[,UT2]]\n"
      "                         (--pressure P | --velocity UN) [--tangential UT1[,UT2]]\n"
      "                         [--shock exact|linearised] [--tol T] [--max-iter N]\n"
      "  sabre-riemann exact --xi X --rho0 R --c0 C --left RHO,U --right RHO,U [--at S]...\n"
      "  sabre-riemann sweep --xi X --rho0 R --c0 C --rho-int RHO --un-int A:B:N\n"
      "                      (--pressure A:B:N | --velocity A:B:N) [--shock exact|linearised]\n"
      "  sabre-riemann --version\n"
      "Each option is given once (--at may repeat). Limits: 1 <= X <= 100; densities up to\n"
      "100 R, speeds up to 100 C in magnitude, imposed pressures up to p(100 R).\n"
      "Units: SI (kg/m^3, m/s, Pa relative to p(rho0) = 0). The boundary normal points into the\n"
      "fluid; UN > 0 is inflow. See docs/riemann.md.\n",
      out);
}

/* Output errors (a full disk, a closed pipe, `> /dev/full`) are failures: exit 1, one line. */
static int finish_stdout(int status) {
  if (fflush(stdout) != 0 || ferror(stdout)) {
    fprintf(stderr, "sabre-riemann: error: cannot write the output: %s\n", strerror(errno));
    return EXIT_FAILURE;
  }
  return status;
}

/* --help (or -h) anywhere after the command prints the usage; 1 if it was given. */
static int wants_help(int argc, char **argv) {
  for (int i = 2; i < argc; ++i)
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return 1;
  return 0;
}

int main(int argc, char **argv) {
  gsl_set_error_handler_off();
  if (argc < 2) die_input("missing command: boundary, exact or sweep (see sabre-riemann --help)");
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    usage(stdout);
    return finish_stdout(0);
  }
  if (!strcmp(argv[1], "--version")) {
    printf("sabre-riemann %s\n", SABRE_VERSION);
    return finish_stdout(0);
  }
  struct options o = {0};
  rmn_params_default(&o.params);
  int (*cmd)(int, char **, struct options *) = NULL;
  if (!strcmp(argv[1], "boundary")) cmd = cmd_boundary;
  if (!strcmp(argv[1], "exact")) cmd = cmd_exact;
  if (!strcmp(argv[1], "sweep")) cmd = cmd_sweep;
  if (!cmd) die_input("unknown command '%s' (expected boundary, exact or sweep)", argv[1]);
  if (wants_help(argc, argv)) {
    usage(stdout);
    return finish_stdout(0);
  }
  return finish_stdout(cmd(argc, argv, &o));
}
