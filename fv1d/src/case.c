/* Case-file reading (common/ getters on libyaml): every key of docs/fv1d.md with its default and
 * range; non-physical values and inconsistent keys are reported with the key's name. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

#define TRY(call)               \
  do {                          \
    if ((call) != 0) return -1; \
  } while (0)

void fv1d_params_default(struct fv1d_params *p) {
  memset(p, 0, sizeof *p);
  p->x_min = 0.0;
  p->x_max = 1.0;
  p->cells = 100;
  rmn_params_default(&p->rmn);
  p->flux = FV1D_FLUX_GODUNOV;
  p->recon = FV1D_RECON_MINMOD;
  for (int side = 0; side < 2; ++side) {
    p->bc[side].type = FV1D_BC_TRANSMISSIVE;
    p->bc[side].imposed = RMN_IMPOSE_PRESSURE;
    p->bc[side].signal.kind = FV1D_SIGNAL_CONSTANT;
  }
  snprintf(p->method, sizeof p->method, "ssprk3");
  p->cfl = 0.5;
  p->adaptive = 0;
  p->rtol = 1e-6;
  p->atol = 1e-9;
  p->max_steps = 100000000L;
  p->series_every = 1;
  p->progress = 1;
}

void fv1d_params_free(struct fv1d_params *p) {
  for (int side = 0; side < 2; ++side) {
    free(p->bc[side].signal.table_t);
    free(p->bc[side].signal.table_v);
    p->bc[side].signal.table_t = p->bc[side].signal.table_v = NULL;
  }
  struct fv1d_initial *ini = &p->initial;
  cmn_expr_free(ini->rho_expr);
  cmn_expr_free(ini->p_expr);
  cmn_expr_free(ini->u_expr);
  free(ini->table_x);
  free(ini->table_rho);
  free(ini->table_u);
  free(ini->regions);
  free(p->output_times);
  memset(ini, 0, sizeof *ini);
  p->output_times = NULL;
  p->noutput = 0;
}

/* Read a table file (common/ format: docs/case-files.md) whose header must be exactly `names`
 * (docs/fv1d.md) and whose first column, the interpolation abscissa, must increase strictly.
 * The columns are copied into cols[0..ncols-1] (allocated, owned by the caller). Returns the
 * number of rows (≥ 1), or -1 with a message naming the file and line in err. */
static long read_table(const char *path, int ncols, const char *const *names, double **cols,
                       char *err, size_t errlen) {
  struct cmn_table t;
  if (cmn_table_read(path, &t, err, errlen) != 0) return -1;
  if (cmn_table_expect_columns(&t, ncols, names, err, errlen) != 0 ||
      cmn_table_check_increasing(&t, 0, err, errlen) != 0) {
    cmn_table_free(&t);
    return -1;
  }
  for (int k = 0; k < ncols; ++k) {
    cols[k] = cmn_malloc(t.nrows * sizeof(double));
    for (size_t i = 0; i < t.nrows; ++i) cols[k][i] = t.data[i * (size_t)ncols + (size_t)k];
  }
  long rows = (long)t.nrows;
  cmn_table_free(&t);
  return rows;
}

static void resolve_path(const char *base_dir, const char *file, char *out, size_t outlen) {
  if (file[0] == '/' || !base_dir || !base_dir[0])
    snprintf(out, outlen, "%s", file);
  else
    snprintf(out, outlen, "%s/%s", base_dir, file);
}

static int read_domain(struct cmn_case *c, struct fv1d_params *p) {
  TRY(cmn_case_get_double(c, "domain.x_min", -INFINITY, INFINITY, &p->x_min));
  TRY(cmn_case_get_double(c, "domain.x_max", -INFINITY, INFINITY, &p->x_max));
  if (!(p->x_max > p->x_min))
    return cmn_case_fail(c, "domain.x_max", "must exceed domain.x_min = %g", p->x_min);
  TRY(cmn_case_get_long(c, "domain.cells", 2, 100000000L, &p->cells));
  return 0;
}

static int read_fluid(struct cmn_case *c, struct fv1d_params *p) {
  double rho0, c0, xi;
  TRY(cmn_case_get_positive(c, "fluid.rho0", &rho0));
  TRY(cmn_case_get_positive(c, "fluid.c0", &c0));
  TRY(cmn_case_get_double(c, "fluid.xi", 1.0, 100.0, &xi));
  if (rmn_eos_init(&p->eos, rho0, c0, xi) != RMN_SUCCESS)
    return cmn_case_fail(c, "fluid", "invalid equation of state");
  return 0;
}

static int read_riemann(struct cmn_case *c, struct fv1d_params *p) {
  static const char *const shock_names[] = {"exact", "linearised", NULL};
  int shock;
  long max_iter;
  TRY(cmn_case_opt_choice(c, "riemann.shock", shock_names, 0, &shock));
  p->rmn.shock = shock == 0 ? RMN_SHOCK_EXACT : RMN_SHOCK_LINEARISED;
  TRY(cmn_case_opt_double(c, "riemann.tol_rel", 1e-14, 1e-16, 1e-2, &p->rmn.tol_rel));
  TRY(cmn_case_opt_long(c, "riemann.max_iter", 100, 1, 100000, &max_iter));
  p->rmn.max_iter = (int)max_iter;
  TRY(cmn_case_opt_double(c, "riemann.contact_tol", 1e-12, 0.0, 0.5, &p->rmn.contact_tol));
  if (rmn_params_check(&p->rmn) != RMN_SUCCESS)
    return cmn_case_fail(c, "riemann", "invalid solver parameters");
  return 0;
}

/* A scalar that is either a number or an expression of x. Sets *number or *expr. */
static int read_number_or_expr(struct cmn_case *c, const char *path, double *number,
                               struct cmn_expr **expr) {
  const char *text;
  TRY(cmn_case_get_string(c, path, &text));
  if (cmn_parse_double(text, number) == 0) return 0;
  char err[256];
  static const char *const vars[] = {"x"};
  *expr = cmn_expr_compile(text, 1, vars, err, sizeof err);
  if (!*expr) return cmn_case_fail(c, path, "%s", err);
  return 0;
}

static int read_initial(struct cmn_case *c, const char *base_dir, struct fv1d_params *p) {
  struct fv1d_initial *ini = &p->initial;
  const struct rmn_eos *eos = &p->eos;
  if (cmn_case_has(c, "initial") && cmn_case_is_map(c, "initial") < 0) return -1;
  int has_rho = cmn_case_has(c, "initial.rho"), has_p = cmn_case_has(c, "initial.p");
  if (has_rho && has_p)
    return cmn_case_fail(c, "initial.p", "give initial.rho or initial.p, not both");
  ini->rho = eos->rho0;
  if (has_rho) {
    TRY(read_number_or_expr(c, "initial.rho", &ini->rho, &ini->rho_expr));
  } else if (has_p) {
    double pressure = 0.0;
    TRY(read_number_or_expr(c, "initial.p", &pressure, &ini->p_expr));
    if (!ini->p_expr) {
      if (!(pressure > rmn_eos_min_pressure(eos)))
        return cmn_case_fail(c, "initial.p", "pressure %g Pa is below the vacuum pressure %g Pa",
                             pressure, rmn_eos_min_pressure(eos));
      ini->rho = rmn_eos_density(eos, pressure);
    }
  } else if (!cmn_case_has(c, "initial.table")) {
    TRY(cmn_case_opt_positive(c, "initial.rho", eos->rho0, &ini->rho));
  }
  ini->u = 0.0;
  if (cmn_case_has(c, "initial.u")) {
    TRY(read_number_or_expr(c, "initial.u", &ini->u, &ini->u_expr));
  } else if (!cmn_case_has(c, "initial.table")) {
    TRY(cmn_case_opt_double(c, "initial.u", 0.0, -INFINITY, INFINITY, &ini->u));
  }
  if (cmn_case_has(c, "initial.table")) {
    if (has_rho || has_p || cmn_case_has(c, "initial.u"))
      return cmn_case_fail(c, "initial.table",
                           "a table replaces initial.rho, initial.p and "
                           "initial.u: give one or the other");
    const char *file;
    TRY(cmn_case_get_string(c, "initial.table", &file));
    char path[1024], err[1536];
    resolve_path(base_dir, file, path, sizeof path);
    static const char *const names[] = {"x", "rho", "u"};
    double *cols[3];
    long rows = read_table(path, 3, names, cols, err, sizeof err);
    if (rows < 0) return cmn_case_fail(c, "initial.table", "%s", err);
    ini->ntable = (size_t)rows;
    ini->table_x = cols[0], ini->table_rho = cols[1], ini->table_u = cols[2];
  }
  int nreg = cmn_case_seq_length(c, "initial.regions");
  if (nreg < 0) return -1;
  ini->nregions = (size_t)nreg;
  ini->regions = nreg > 0 ? cmn_calloc((size_t)nreg, sizeof *ini->regions) : NULL;
  for (int r = 0; r < nreg; ++r) {
    struct fv1d_region *reg = &ini->regions[r];
    char key[128], key_rho[128], key_p[128];
    snprintf(key, sizeof key, "initial.regions[%d].from", r);
    TRY(cmn_case_opt_double(c, key, -INFINITY, -INFINITY, INFINITY, &reg->from));
    snprintf(key, sizeof key, "initial.regions[%d].to", r);
    TRY(cmn_case_opt_double(c, key, INFINITY, -INFINITY, INFINITY, &reg->to));
    if (!(reg->to > reg->from)) return cmn_case_fail(c, key, "must exceed 'from'");
    snprintf(key_rho, sizeof key_rho, "initial.regions[%d].rho", r);
    snprintf(key_p, sizeof key_p, "initial.regions[%d].p", r);
    if (cmn_case_has(c, key_p)) {
      if (cmn_case_has(c, key_rho)) return cmn_case_fail(c, key_p, "give rho or p, not both");
      double pressure;
      TRY(cmn_case_get_double(c, key_p, -INFINITY, INFINITY, &pressure));
      if (!(pressure > rmn_eos_min_pressure(eos)))
        return cmn_case_fail(c, key_p, "pressure %g Pa is below the vacuum pressure %g Pa",
                             pressure, rmn_eos_min_pressure(eos));
      reg->rho = rmn_eos_density(eos, pressure);
    } else {
      TRY(cmn_case_get_positive(c, key_rho, &reg->rho));
    }
    snprintf(key, sizeof key, "initial.regions[%d].u", r);
    TRY(cmn_case_opt_double(c, key, 0.0, -INFINITY, INFINITY, &reg->u));
  }
  /* the background must be a wet, finite state at every quadrature point of the mesh */
  const double dx = (p->x_max - p->x_min) / (double)p->cells;
  for (long i = 0; i < 3 * p->cells; ++i) {
    double x = p->x_min + ((double)i + 0.5) * dx / 3.0, rho, u;
    fv1d_initial_point(p, x, &rho, &u);
    if (!(rho > 0.0) || !isfinite(rho) || !isfinite(u)) {
      const char *key = ini->ntable   ? "initial.table"
                        : ini->p_expr ? "initial.p"
                                      : (!isfinite(u) ? "initial.u" : "initial.rho");
      return cmn_case_fail(c, key,
                           "non-physical initial state at x = %g m: rho = %g kg/m^3, "
                           "u = %g m/s",
                           x, rho, u);
    }
  }
  return 0;
}

static int read_signal(struct cmn_case *c, const char *base_dir, const char *side,
                       struct fv1d_bc *bc, const struct rmn_eos *eos) {
  struct fv1d_signal *sig = &bc->signal;
  char key[128];
  int kind;
  snprintf(key, sizeof key, "boundaries.%s.signal", side);
  TRY(cmn_case_opt_choice(c, key, fv1d_signal_names, FV1D_SIGNAL_CONSTANT, &kind));
  sig->kind = (enum fv1d_signal_kind)kind;
  double lo = -INFINITY, hi = INFINITY;
  switch (sig->kind) {
    case FV1D_SIGNAL_CONSTANT:
      snprintf(key, sizeof key, "boundaries.%s.value", side);
      TRY(cmn_case_get_double(c, key, lo, hi, &sig->value));
      lo = hi = sig->value;
      break;
    case FV1D_SIGNAL_SINUSOID:
      snprintf(key, sizeof key, "boundaries.%s.value", side);
      TRY(cmn_case_opt_double(c, key, 0.0, -INFINITY, INFINITY, &sig->value));
      snprintf(key, sizeof key, "boundaries.%s.amplitude", side);
      TRY(cmn_case_get_double(c, key, -INFINITY, INFINITY, &sig->amplitude));
      snprintf(key, sizeof key, "boundaries.%s.frequency", side);
      TRY(cmn_case_get_double(c, key, 0.0, INFINITY, &sig->frequency));
      snprintf(key, sizeof key, "boundaries.%s.phase", side);
      TRY(cmn_case_opt_double(c, key, 0.0, -INFINITY, INFINITY, &sig->phase));
      lo = sig->value - fabs(sig->amplitude), hi = sig->value + fabs(sig->amplitude);
      break;
    case FV1D_SIGNAL_RAMP:
      snprintf(key, sizeof key, "boundaries.%s.start", side);
      TRY(cmn_case_opt_double(c, key, 0.0, -INFINITY, INFINITY, &sig->start));
      snprintf(key, sizeof key, "boundaries.%s.value", side);
      TRY(cmn_case_get_double(c, key, -INFINITY, INFINITY, &sig->value));
      snprintf(key, sizeof key, "boundaries.%s.t_start", side);
      TRY(cmn_case_opt_double(c, key, 0.0, 0.0, INFINITY, &sig->t_start));
      snprintf(key, sizeof key, "boundaries.%s.duration", side);
      TRY(cmn_case_get_double(c, key, 0.0, INFINITY, &sig->duration));
      lo = fmin(sig->start, sig->value), hi = fmax(sig->start, sig->value);
      break;
    case FV1D_SIGNAL_TABLE: {
      const char *file;
      snprintf(key, sizeof key, "boundaries.%s.table", side);
      TRY(cmn_case_get_string(c, key, &file));
      char path[1024], err[1536];
      resolve_path(base_dir, file, path, sizeof path);
      static const char *const names[] = {"t", "value"};
      double *cols[2];
      long rows = read_table(path, 2, names, cols, err, sizeof err);
      if (rows < 0) return cmn_case_fail(c, key, "%s", err);
      sig->ntable = (size_t)rows;
      sig->table_t = cols[0], sig->table_v = cols[1];
      lo = hi = sig->table_v[0];
      for (size_t k = 0; k < sig->ntable; ++k)
        lo = fmin(lo, sig->table_v[k]), hi = fmax(hi, sig->table_v[k]);
      break;
    }
  }
  if (bc->imposed == RMN_IMPOSE_PRESSURE && !(lo > rmn_eos_min_pressure(eos))) {
    snprintf(key, sizeof key, "boundaries.%s", side);
    return cmn_case_fail(c, key,
                         "imposed pressure reaches %g Pa, at or below the vacuum "
                         "pressure p(0) = %g Pa",
                         lo, rmn_eos_min_pressure(eos));
  }
  if (bc->imposed == RMN_IMPOSE_VELOCITY && !(fmax(fabs(lo), fabs(hi)) < eos->c0)) {
    snprintf(key, sizeof key, "boundaries.%s", side);
    return cmn_case_fail(c, key,
                         "imposed velocity reaches %g m/s: the boundary problem needs "
                         "subsonic flow (|u| < c0 = %g m/s)",
                         fmax(fabs(lo), fabs(hi)), eos->c0);
  }
  return 0;
}

static int read_boundaries(struct cmn_case *c, const char *base_dir, struct fv1d_params *p) {
  static const char *const sides[2] = {"left", "right"};
  static const char *const impose_names[] = {"pressure", "velocity", NULL};
  for (int s = 0; s < 2; ++s) {
    char key[128];
    int type, imposed;
    snprintf(key, sizeof key, "boundaries.%s.type", sides[s]);
    TRY(cmn_case_get_choice(c, key, fv1d_bc_names, &type));
    p->bc[s].type = (enum fv1d_bc_type)type;
    if (p->bc[s].type == FV1D_BC_OPEN) {
      snprintf(key, sizeof key, "boundaries.%s.impose", sides[s]);
      TRY(cmn_case_get_choice(c, key, impose_names, &imposed));
      p->bc[s].imposed = imposed == 0 ? RMN_IMPOSE_PRESSURE : RMN_IMPOSE_VELOCITY;
      TRY(read_signal(c, base_dir, sides[s], &p->bc[s], &p->eos));
    }
  }
  if ((p->bc[0].type == FV1D_BC_PERIODIC) != (p->bc[1].type == FV1D_BC_PERIODIC))
    return cmn_case_fail(
        c, p->bc[0].type == FV1D_BC_PERIODIC ? "boundaries.right.type" : "boundaries.left.type",
        "periodic must be set on both ends");
  return 0;
}

static int read_numerics(struct cmn_case *c, struct fv1d_params *p) {
  int flux, recon;
  TRY(cmn_case_opt_choice(c, "numerics.flux", fv1d_flux_names, FV1D_FLUX_GODUNOV, &flux));
  TRY(cmn_case_opt_choice(c, "numerics.reconstruction", fv1d_recon_names, FV1D_RECON_MINMOD,
                          &recon));
  p->flux = (enum fv1d_flux)flux;
  p->recon = (enum fv1d_recon)recon;
  return 0;
}

static int read_time(struct cmn_case *c, struct fv1d_params *p) {
  const char *method;
  TRY(cmn_case_get_positive(c, "time.end", &p->t_end));
  TRY(cmn_case_opt_string(c, "time.method", "ssprk3", &method));
  TRY(cmn_case_opt_double(c, "time.cfl", 0.5, 1e-6, 2.0, &p->cfl));
  if (!(p->cfl > 0.0)) return cmn_case_fail(c, "time.cfl", "must be positive");
  TRY(cmn_case_opt_bool(c, "time.adaptive", 0, &p->adaptive));
  TRY(cmn_case_opt_double(c, "time.rtol", 1e-6, 1e-14, 1.0, &p->rtol));
  TRY(cmn_case_opt_double(c, "time.atol", 1e-9, 1e-300, 1.0, &p->atol));
  TRY(cmn_case_opt_long(c, "time.max_steps", 100000000L, 1, 1000000000000L, &p->max_steps));
  if (!p->adaptive && p->cfl > 1.0)
    cmn_warning(
        "%s:%d: time.cfl = %g with the fixed step: beyond 1 the explicit step is unstable "
        "for every flux (docs/fv1d.md section 3); expect a blow-up, or use time.cfl <= 1",
        cmn_case_name(c), cmn_case_line(c, "time.cfl"), p->cfl);
  char err[256];
  if (strlen(method) >= sizeof p->method) return cmn_case_fail(c, "time.method", "name too long");
  if (fv1d_method_check(method, p->adaptive, err, sizeof err) != 0)
    return cmn_case_fail(c, "time.method", "%s", err);
  snprintf(p->method, sizeof p->method, "%s", method);
  return 0;
}

static int read_output(struct cmn_case *c, struct fv1d_params *p) {
  if (cmn_case_has(c, "output.times")) {
    if (cmn_case_has(c, "output.count"))
      return cmn_case_fail(c, "output.count", "give output.times or output.count, not both");
    int n = cmn_case_seq_length(c, "output.times");
    if (n < 0) return -1;
    if (n == 0) return cmn_case_fail(c, "output.times", "expected a non-empty list of times");
    p->output_times = cmn_calloc((size_t)n + 1, sizeof(double));
    int count = 0;
    TRY(cmn_case_get_doubles(c, "output.times", 0, n, p->output_times, &count));
    p->noutput = (size_t)count;
    for (int k = 0; k < count; ++k) {
      double t = p->output_times[k];
      if (!(t > 0.0 && t <= p->t_end) || (k > 0 && !(t > p->output_times[k - 1])))
        return cmn_case_fail(c, "output.times",
                             "times must increase strictly within (0, time.end = %g]", p->t_end);
    }
    if (p->output_times[count - 1] < p->t_end) p->output_times[p->noutput++] = p->t_end;
  } else {
    long count;
    TRY(cmn_case_opt_long(c, "output.count", 1, 1, 1000000, &count));
    p->noutput = (size_t)count;
    p->output_times = cmn_calloc((size_t)count, sizeof(double));
    for (long k = 0; k < count; ++k)
      p->output_times[k] = k + 1 == count ? p->t_end : p->t_end * (double)(k + 1) / (double)count;
  }
  TRY(cmn_case_opt_long(c, "output.series_every", 1, 1, 1000000000L, &p->series_every));
  TRY(cmn_case_opt_bool(c, "output.progress", 1, &p->progress));
  return 0;
}

int fv1d_case_read(struct cmn_case *c, const char *base_dir, struct fv1d_params *p) {
  fv1d_params_default(p);
  TRY(read_domain(c, p));
  TRY(read_fluid(c, p));
  TRY(read_riemann(c, p));
  TRY(read_initial(c, base_dir, p));
  TRY(read_boundaries(c, base_dir, p));
  TRY(read_numerics(c, p));
  TRY(read_time(c, p));
  TRY(read_output(c, p));
  TRY(cmn_case_check_unused(c));
  return 0;
}
