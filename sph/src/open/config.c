/* The `open_boundaries` section of a case file (sabre/sph_open.h; keys, units and defaults:
 * docs/sph-case-file.md) and its check against the wall mesh. */
#include <gsl/gsl_math.h> /* M_PI */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "open/open_internal.h"
#include "sabre/common.h"
#include "sabre/sph_open.h"

#define TRY(x)               \
  do {                       \
    if ((x) != 0) return -1; \
  } while (0)

static const char *const vars[] = {"t", "x", "y", "z"};

/* The keys that give the imposed value: exactly one per group. */
static const char *const value_keys[] = {"pressure", "velocity",   "normal_velocity",
                                         "table",    "poiseuille", "stokes5",
                                         "solitary", "hydrostatic"};
#define NVALUE_KEYS 8

static char *key(char *buf, size_t len, const char *base, const char *name) {
  if (snprintf(buf, len, "%s.%s", base, name) >= (int)len) cmn_error("key too long: %s", base);
  return buf;
}

/* A number or an expression of t, x, y (, z), kept as text; *number receives the number (NaN for
 * an expression). */
static int read_expr(struct cmn_case *c, const char *path, int dim, char *out, double *number) {
  const char *text;
  TRY(cmn_case_get_string(c, path, &text));
  if (strlen(text) >= SPH_OPEN_EXPR_LEN)
    return cmn_case_fail(c, path, "expression longer than %d characters", SPH_OPEN_EXPR_LEN - 1);
  snprintf(out, SPH_OPEN_EXPR_LEN, "%s", text);
  if (cmn_parse_double(text, number) == 0) return 0;
  *number = NAN;
  char err[512];
  struct cmn_expr *e = cmn_expr_compile(text, 1 + dim, vars, err, sizeof err);
  if (!e)
    return cmn_case_fail(c, path, "expected a number or an expression of t, x, y%s: %s",
                         dim == 3 ? ", z" : "", err);
  cmn_expr_free(e);
  return 0;
}

static int check_pressure(struct cmn_case *c, const char *path, double p,
                          const struct rmn_eos *eos) {
  if (!(p > rmn_eos_min_pressure(eos)))
    return cmn_case_fail(c, path,
                         "imposed pressure %g Pa is at or below the vacuum pressure p(0) = %g Pa "
                         "of the EOS",
                         p, rmn_eos_min_pressure(eos));
  return 0;
}

static int check_speed(struct cmn_case *c, const char *path, double u, const struct rmn_eos *eos) {
  if (!(fabs(u) < eos->c0))
    return cmn_case_fail(c, path,
                         "imposed speed %g m/s is not below c0 = %g m/s: the boundary problem "
                         "needs subsonic flow",
                         u, eos->c0);
  return 0;
}

/* File names are relative to the case file's directory. */
static int resolve(struct cmn_case *c, const char *path, const char *file, char *out, size_t len) {
  const char *name = cmn_case_name(c), *slash = strrchr(name, '/');
  int dir = file[0] == '/' || !slash ? 0 : (int)(slash - name) + 1;
  if ((size_t)snprintf(out, len, "%.*s%s", dir, name, file) >= len)
    return cmn_case_fail(c, path, "file name longer than %zu characters", len - 1);
  return 0;
}

static int read_table(struct cmn_case *c, const char *path, int dim, const struct rmn_eos *eos,
                      struct sph_open_group *g) {
  const char *file;
  TRY(cmn_case_get_string(c, path, &file));
  TRY(resolve(c, path, file, g->table, sizeof g->table));
  struct cmn_table t;
  char err[1536];
  if (cmn_table_read(g->table, &t, err, sizeof err) != 0) return cmn_case_fail(c, path, "%s", err);
  static const char *const p_names[] = {"t", "p"}, *const un_names[] = {"t", "un"},
                           *const u_names[] = {"t", "u", "v", "w"};
  int rc = 0;
  if (g->imposed == RMN_IMPOSE_PRESSURE) {
    rc = cmn_table_expect_columns(&t, 2, p_names, err, sizeof err);
  } else if (t.ncols == 2) {
    g->normal = 1;
    rc = cmn_table_expect_columns(&t, 2, un_names, err, sizeof err);
  } else {
    rc = cmn_table_expect_columns(&t, 1 + dim, u_names, err, sizeof err);
    if (rc != 0) {
      const size_t len = strlen(err);
      snprintf(err + len, sizeof err - len, " (or 't,un' for a normal velocity)");
    }
  }
  if (rc == 0) rc = cmn_table_check_increasing(&t, 0, err, sizeof err);
  if (rc != 0) {
    cmn_table_free(&t);
    return cmn_case_fail(c, path, "%s", err);
  }
  for (size_t r = 0; r < t.nrows && rc == 0; r++) {
    const double *row = t.data + r * (size_t)t.ncols;
    if (g->imposed == RMN_IMPOSE_PRESSURE && !(row[1] > rmn_eos_min_pressure(eos)))
      rc = cmn_case_fail(c, path, "%s:%ld: pressure %g Pa at or below the vacuum pressure %g Pa",
                         g->table, t.lines[r], row[1], rmn_eos_min_pressure(eos));
    double u2 = 0.0;
    for (int k = 1; k < t.ncols; k++) u2 += row[k] * row[k];
    if (rc == 0 && g->imposed == RMN_IMPOSE_VELOCITY && !(sqrt(u2) < eos->c0))
      rc = cmn_case_fail(c, path, "%s:%ld: speed %g m/s is not below c0 = %g m/s", g->table,
                         t.lines[r], sqrt(u2), eos->c0);
  }
  cmn_table_free(&t);
  return rc;
}

/* A unit vector of dim numbers at path (default def); error if zero. */
static int read_unit(struct cmn_case *c, const char *path, int dim, const double *def,
                     double *out) {
  out[0] = out[1] = out[2] = 0.0;
  TRY(cmn_case_opt_doubles(c, path, dim, def, out));
  double n = sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  if (!(n > 0.0)) return cmn_case_fail(c, path, "expected a non-zero vector");
  for (int k = 0; k < 3; k++) out[k] /= n;
  return 0;
}

static int read_poiseuille(struct cmn_case *c, const char *base, int dim, const struct rmn_eos *eos,
                           struct sph_open_group *g) {
  char p[192];
  struct sph_open_poiseuille *d = &g->poiseuille;
  if (dim < 2) return cmn_case_fail(c, base, "needs dimension 2 or 3");
  static const char *const shapes[] = {"plates", "circle", "rectangle", NULL};
  TRY(cmn_case_opt_choice(c, key(p, sizeof p, base, "shape"), shapes,
                          dim == 2 ? SPH_DUCT_PLATES : SPH_DUCT_CIRCLE, &d->shape));
  if ((dim == 2) != (d->shape == SPH_DUCT_PLATES))
    return cmn_case_fail(c, p, "expected %s in %dD", dim == 2 ? "plates" : "circle or rectangle",
                         dim);
  TRY(cmn_case_get_doubles(c, key(p, sizeof p, base, "center"), dim, dim, d->center, NULL));
  if (d->shape == SPH_DUCT_RECTANGLE) {
    TRY(cmn_case_get_doubles(c, key(p, sizeof p, base, "half_widths"), 2, 2, d->half, NULL));
    if (!(d->half[0] > 0.0 && d->half[1] > 0.0))
      return cmn_case_fail(c, p, "expected two positive half-widths [a, b] in m");
    const double ex[3] = {1.0, 0.0, 0.0};
    TRY(read_unit(c, key(p, sizeof p, base, "axis"), dim, ex, d->axis));
  } else {
    TRY(cmn_case_get_positive(c, key(p, sizeof p, base, "radius"), &d->radius));
  }
  const int has_u = cmn_case_has(c, key(p, sizeof p, base, "u_max")),
            has_q = cmn_case_has(c, key(p, sizeof p, base, "flux"));
  if (has_u == has_q)
    return cmn_case_fail(c, base,
                         "give exactly one of 'u_max' (centre-line speed, m/s) and 'flux' "
                         "(volume flux, m^%d/s)",
                         dim);
  if (has_u) {
    TRY(cmn_case_get_double(c, key(p, sizeof p, base, "u_max"), -INFINITY, INFINITY, &d->u_max));
    d->flux = NAN; /* computed by the source (the rectangle needs its series) */
  } else {
    TRY(cmn_case_get_double(c, key(p, sizeof p, base, "flux"), -INFINITY, INFINITY, &d->flux));
    d->u_max = NAN;
  }
  /* U_max from the flux for the closed forms; the rectangle's comes from its series
   * (sph_open_source_init); the speed is checked there. */
  if (d->shape == SPH_DUCT_PLATES && has_q) d->u_max = 3.0 * d->flux / (4.0 * d->radius);
  if (d->shape == SPH_DUCT_CIRCLE && has_q)
    d->u_max = 2.0 * d->flux / (M_PI * d->radius * d->radius);
  if (d->shape == SPH_DUCT_PLATES && has_u) d->flux = 4.0 * d->u_max * d->radius / 3.0;
  if (d->shape == SPH_DUCT_CIRCLE && has_u) d->flux = 0.5 * M_PI * d->radius * d->radius * d->u_max;
  TRY(check_speed(c, key(p, sizeof p, base, has_u ? "u_max" : "flux"), sph_open_duct_umax(d), eos));
  TRY(cmn_case_opt_double(c, key(p, sizeof p, base, "ramp"), 0.0, 0.0, INFINITY, &d->ramp));
  return 0;
}

/* Horizontal unit direction of travel (the part of `direction` normal to g). */
static int read_direction(struct cmn_case *c, const char *base, int dim, const double up[3],
                          struct sph_open_group *g) {
  char p[192];
  const double ex[3] = {1.0, 0.0, 0.0};
  g->direction[0] = g->direction[1] = g->direction[2] = 0.0;
  TRY(cmn_case_opt_doubles(c, key(p, sizeof p, base, "direction"), dim, ex, g->direction));
  double dn = g->direction[0] * up[0] + g->direction[1] * up[1] + g->direction[2] * up[2];
  for (int k = 0; k < 3; k++) g->direction[k] -= dn * up[k];
  double n = sqrt(g->direction[0] * g->direction[0] + g->direction[1] * g->direction[1] +
                  g->direction[2] * g->direction[2]);
  if (!(n > 1e-12)) return cmn_case_fail(c, p, "expected a direction that is not vertical");
  for (int k = 0; k < 3; k++) g->direction[k] /= n;
  return 0;
}

/* Map a wave library message "<field>: why" to the case key base.<field>. */
static int wave_fail(struct cmn_case *c, const char *base, const char *msg, int amplitude_given) {
  char field[32] = "", p[192];
  size_t n = strcspn(msg, ":");
  if (n < sizeof field && msg[n] == ':') {
    memcpy(field, msg, n);
    field[n] = '\0';
  }
  if (amplitude_given && strcmp(field, "height") == 0) {
    snprintf(p, sizeof p, "%s.amplitude", base);
    return cmn_case_fail(c, p, "(height H = 2A)%s", msg + n + 1);
  }
  if (field[0]) {
    snprintf(p, sizeof p, "%s.%s", base, field);
    return cmn_case_fail(c, p, "%s", msg + n + 2);
  }
  return cmn_case_fail(c, base, "%s", msg);
}

static int read_stokes5(struct cmn_case *c, const char *base, int dim, double gnorm,
                        const double up[3], const struct rmn_eos *eos, struct sph_open_group *g) {
  char p[192];
  struct sph_stokes5_params *w = &g->stokes5;
  sph_stokes5_params_init(w);
  w->g = gnorm;
  w->rho0 = eos->rho0;
  TRY(cmn_case_get_positive(c, key(p, sizeof p, base, "depth"), &w->depth));
  const int has_h = cmn_case_has(c, key(p, sizeof p, base, "height")),
            has_a = cmn_case_has(c, key(p, sizeof p, base, "amplitude"));
  if (has_h == has_a)
    return cmn_case_fail(c, base, "give exactly one of 'height' (H, m) and 'amplitude' (H/2, m)");
  if (has_h) {
    TRY(cmn_case_get_positive(c, key(p, sizeof p, base, "height"), &w->height));
  } else {
    double a;
    TRY(cmn_case_get_positive(c, key(p, sizeof p, base, "amplitude"), &a));
    w->height = 2.0 * a;
  }
  const int has_l = cmn_case_has(c, key(p, sizeof p, base, "length")),
            has_t = cmn_case_has(c, key(p, sizeof p, base, "period"));
  if (has_l == has_t)
    return cmn_case_fail(c, base, "give exactly one of 'length' (L, m) and 'period' (T, s)");
  if (has_l)
    TRY(cmn_case_get_positive(c, key(p, sizeof p, base, "length"), &w->length));
  else
    TRY(cmn_case_get_positive(c, key(p, sizeof p, base, "period"), &w->period));
  TRY(cmn_case_opt_double(c, key(p, sizeof p, base, "current"), 0.0, -INFINITY, INFINITY,
                          &w->current));
  TRY(cmn_case_opt_double(c, key(p, sizeof p, base, "bed"), 0.0, -INFINITY, INFINITY, &g->bed));
  TRY(cmn_case_opt_double(c, key(p, sizeof p, base, "x0"), 0.0, -INFINITY, INFINITY, &g->x0));
  TRY(read_direction(c, base, dim, up, g));
  struct sph_stokes5 wave;
  char msg[512];
  if (sph_stokes5_init(&wave, w, msg, sizeof msg) != SPH_WAVE_SUCCESS)
    return wave_fail(c, base, msg, has_a);
  return 0;
}

static int read_solitary(struct cmn_case *c, const char *base, int dim, double gnorm,
                         const double up[3], const struct rmn_eos *eos, struct sph_open_group *g) {
  char p[192];
  struct sph_solitary_params *w = &g->solitary;
  sph_solitary_params_init(w);
  w->g = gnorm;
  w->rho0 = eos->rho0;
  TRY(cmn_case_get_positive(c, key(p, sizeof p, base, "depth"), &w->depth));
  TRY(cmn_case_get_positive(c, key(p, sizeof p, base, "amplitude"), &w->amplitude));
  double deg;
  TRY(cmn_case_opt_double(c, key(p, sizeof p, base, "angle"), 0.0, -360.0, 360.0, &deg));
  if (dim == 2 && deg != 0.0) return cmn_case_fail(c, p, "expected 0 in 2D (no y of the wave)");
  w->angle = deg * (M_PI / 180.0);
  TRY(cmn_case_opt_double(c, key(p, sizeof p, base, "x0"), 0.0, -INFINITY, INFINITY, &w->x0));
  TRY(cmn_case_opt_double(c, key(p, sizeof p, base, "bed"), 0.0, -INFINITY, INFINITY, &g->bed));
  TRY(read_direction(c, base, dim, up, g));
  struct sph_solitary wave;
  char msg[512];
  if (sph_solitary_init(&wave, w, msg, sizeof msg) != SPH_WAVE_SUCCESS)
    return wave_fail(c, base, msg, 0);
  return 0;
}

static int read_hydrostatic(struct cmn_case *c, const char *base, double gnorm,
                            struct sph_open_group *g) {
  char p[192];
  const char *text;
  TRY(cmn_case_get_string(c, key(p, sizeof p, base, "depth"), &text));
  g->depth_measured = strcmp(text, "measured") == 0;
  if (!g->depth_measured && (cmn_parse_double(text, &g->depth) != 0 || !(g->depth >= 0.0)))
    return cmn_case_fail(
        c, p, "expected a depth >= 0 (m) or 'measured' (at the boundary), got '%s'", text);
  if (g->depth_measured) g->depth = NAN;
  TRY(cmn_case_opt_double(c, key(p, sizeof p, base, "bed"), 0.0, -INFINITY, INFINITY, &g->bed));
  TRY(cmn_case_opt_bool(c, key(p, sizeof p, base, "absorbing"), 0, &g->absorbing));
  if (g->absorbing && g->depth_measured)
    return cmn_case_fail(c, p,
                         "needs the still depth as a number (the level the outgoing long waves "
                         "leave behind), not 'measured'");
  const char *ck = key(p, sizeof p, base, "current");
  if (cmn_case_has(c, ck) && !g->absorbing)
    return cmn_case_fail(c, ck,
                         "applies to an absorbing outlet only (hydrostatic.absorbing: true)");
  TRY(cmn_case_opt_double(c, ck, 0.0, -INFINITY, INFINITY, &g->current));
  if (g->absorbing && !(fabs(g->current) < sqrt(gnorm * g->depth)))
    return cmn_case_fail(c, ck,
                         "expected a subcritical current, |U| < sqrt(g D) = %g m/s, got %g m/s",
                         sqrt(gnorm * g->depth), g->current);
  return 0;
}

int sph_open_wave_read(struct cmn_case *c, const char *base, int dim, const double gravity[3],
                       const struct rmn_eos *eos, struct sph_open_group *g) {
  memset(g, 0, sizeof *g);
  snprintf(g->name, sizeof g->name, "%s", base);
  g->wall = -1;
  g->imposed = RMN_IMPOSE_VELOCITY;
  if (cmn_case_is_map(c, base) != 1)
    return cmn_case_fail(c, base, "expected a mapping with one of 'stokes5' and 'solitary'");
  char p[192];
  const int has_s = cmn_case_has(c, key(p, sizeof p, base, "stokes5")),
            has_l = cmn_case_has(c, key(p, sizeof p, base, "solitary"));
  if (has_s == has_l) return cmn_case_fail(c, base, "give exactly one of 'stokes5' and 'solitary'");
  const double gnorm =
      sqrt(gravity[0] * gravity[0] + gravity[1] * gravity[1] + gravity[2] * gravity[2]);
  if (!(gnorm > 0.0))
    return cmn_case_fail(c, base, "a wave needs a non-zero gravity (it sets the vertical)");
  if (dim < 2) return cmn_case_fail(c, base, "a wave needs dimension 2 or 3");
  double up[3];
  for (int k = 0; k < 3; k++) up[k] = -gravity[k] / gnorm;
  key(p, sizeof p, base, has_s ? "stokes5" : "solitary");
  if (cmn_case_is_map(c, p) != 1)
    return cmn_case_fail(c, p, "expected a mapping of the generator's keys");
  g->source = has_s ? SPH_OPEN_STOKES5 : SPH_OPEN_SOLITARY;
  if (has_s) return read_stokes5(c, p, dim, gnorm, up, eos, g);
  return read_solitary(c, p, dim, gnorm, up, eos, g);
}

/* The value of a group: exactly one of the value keys, of a kind that matches `impose`. */
static int read_value(struct cmn_case *c, const char *base, int dim, const double gravity[3],
                      const struct rmn_eos *eos, struct sph_open_group *g) {
  char p[192];
  int which = -1;
  for (int k = 0; k < NVALUE_KEYS; k++) {
    if (!cmn_case_has(c, key(p, sizeof p, base, value_keys[k]))) continue;
    if (which >= 0)
      return cmn_case_fail(c, p,
                           "give one value only: '%s' is given too (impose %s and the boundary "
                           "problem gives the other quantity)",
                           value_keys[which],
                           g->imposed == RMN_IMPOSE_PRESSURE ? "the pressure" : "the velocity");
    which = k;
  }
  if (which < 0)
    return cmn_case_fail(c, base,
                         "no value: give one of pressure, velocity, normal_velocity, table, "
                         "poiseuille, stokes5, solitary, hydrostatic");
  const char *name = value_keys[which];
  key(p, sizeof p, base, name);
  static const int fits_pressure[NVALUE_KEYS] = {1, 0, 0, 1, 0, 1, 1, 1};
  static const int fits_velocity[NVALUE_KEYS] = {0, 1, 1, 1, 1, 1, 1, 0};
  const int fits = g->imposed == RMN_IMPOSE_PRESSURE ? fits_pressure[which] : fits_velocity[which];
  if (!fits)
    return cmn_case_fail(c, p, "'%s' does not go with impose: %s (%s)", name,
                         g->imposed == RMN_IMPOSE_PRESSURE ? "pressure" : "velocity",
                         g->imposed == RMN_IMPOSE_PRESSURE
                             ? "give pressure, table, stokes5, solitary or hydrostatic"
                             : "give velocity, normal_velocity, table, poiseuille, stokes5 or "
                               "solitary");
  const double gnorm =
      sqrt(gravity[0] * gravity[0] + gravity[1] * gravity[1] + gravity[2] * gravity[2]);
  double up[3] = {0.0, 0.0, 0.0};
  if (gnorm > 0.0)
    for (int k = 0; k < 3; k++) up[k] = -gravity[k] / gnorm;
  if (which >= 5 && !(gnorm > 0.0))
    return cmn_case_fail(c, p, "'%s' needs a non-zero gravity (it sets the vertical)", name);
  if (which >= 4 && cmn_case_is_map(c, p) != 1)
    return cmn_case_fail(c, p, "expected a mapping of the generator's keys");
  switch (which) {
    case 0: { /* pressure */
      g->source = SPH_OPEN_VALUE;
      g->ncomp = 1;
      double v;
      TRY(read_expr(c, p, dim, g->expr[0], &v));
      if (!isnan(v)) TRY(check_pressure(c, p, v, eos));
      break;
    }
    case 1: { /* velocity: dim numbers or expressions */
      g->source = SPH_OPEN_VALUE;
      g->ncomp = dim;
      int n = cmn_case_seq_length(c, p);
      if (n < 0) return -1;
      if (n != dim)
        return cmn_case_fail(
            c, p, "expected %d numbers or expressions (the velocity vector), got %d", dim, n);
      double u2 = 0.0;
      int numbers = 1;
      for (int k = 0; k < dim; k++) {
        char q[224];
        snprintf(q, sizeof q, "%s[%d]", p, k);
        double v;
        TRY(read_expr(c, q, dim, g->expr[k], &v));
        if (isnan(v))
          numbers = 0;
        else
          u2 += v * v;
      }
      if (numbers) TRY(check_speed(c, p, sqrt(u2), eos));
      break;
    }
    case 2: { /* normal_velocity */
      g->source = SPH_OPEN_VALUE;
      g->ncomp = 1;
      g->normal = 1;
      double v;
      TRY(read_expr(c, p, dim, g->expr[0], &v));
      if (!isnan(v)) TRY(check_speed(c, p, v, eos));
      break;
    }
    case 3:
      g->source = SPH_OPEN_TABLE;
      TRY(read_table(c, p, dim, eos, g));
      break;
    case 4:
      g->source = SPH_OPEN_POISEUILLE;
      g->normal = 1;
      TRY(read_poiseuille(c, p, dim, eos, g));
      break;
    case 5:
      g->source = SPH_OPEN_STOKES5;
      if (dim < 2) return cmn_case_fail(c, p, "needs dimension 2 or 3");
      TRY(read_stokes5(c, p, dim, gnorm, up, eos, g));
      break;
    case 6:
      g->source = SPH_OPEN_SOLITARY;
      if (dim < 2) return cmn_case_fail(c, p, "needs dimension 2 or 3");
      TRY(read_solitary(c, p, dim, gnorm, up, eos, g));
      break;
    case 7:
      g->source = SPH_OPEN_HYDROSTATIC;
      TRY(read_hydrostatic(c, p, gnorm, g));
      break;
  }
  /* The inflow's tangential velocity: from the user when the value gives none. */
  const int own_tangential = g->source == SPH_OPEN_STOKES5 || g->source == SPH_OPEN_SOLITARY ||
                             (g->imposed == RMN_IMPOSE_VELOCITY && !g->normal);
  key(p, sizeof p, base, "tangential_velocity");
  if (own_tangential && cmn_case_has(c, p))
    return cmn_case_fail(c, p,
                         "'%s' gives the whole velocity: the inflow's tangential velocity is its "
                         "own",
                         name);
  if (!own_tangential) {
    const double zero[3] = {0.0, 0.0, 0.0};
    TRY(cmn_case_opt_doubles(c, p, dim, zero, g->tangential));
    double u2 = 0.0;
    for (int k = 0; k < dim; k++) u2 += g->tangential[k] * g->tangential[k];
    TRY(check_speed(c, p, sqrt(u2), eos));
  }
  return 0;
}

/* The `type` of the wall a group names (geometry.walls[wall].type). */
static int wall_type(struct cmn_case *c, const struct sph_open_group *g, const char **type) {
  char t[96];
  snprintf(t, sizeof t, "geometry.walls[%d].type", g->wall);
  return cmn_case_get_string(c, t, type);
}

/* `faces: [x-, ...]` of a box or channel wall, instead of `edges`. */
static int read_faces(struct cmn_case *c, const char *base, int dim, struct sph_open_group *g) {
  static const char *const names[] = {"x-", "x+", "y-", "y+", "z-", "z+", NULL};
  char p[192], q[224];
  key(p, sizeof p, base, "faces");
  int n = cmn_case_seq_length(c, p);
  if (n <= 0) return n;
  if (g->nedges > 0) return cmn_case_fail(c, p, "give 'edges' or 'faces', not both");
  const char *type;
  TRY(wall_type(c, g, &type));
  if (strcmp(type, "box") != 0 && strcmp(type, "channel") != 0)
    return cmn_case_fail(c, p,
                         "faces select parts of a box or channel wall; geometry.walls[%d] is "
                         "a %s (select its elements with 'edges')",
                         g->wall, type);
  for (int i = 0; i < n; i++) {
    int f;
    snprintf(q, sizeof q, "%s[%d]", p, i);
    TRY(cmn_case_get_choice(c, q, names, &f));
    if (f >= 2 * dim) return cmn_case_fail(c, q, "no such face in %dD", dim);
    g->faces |= 1u << f;
  }
  return 0;
}

/* `solids: [name, ...]` of an STL wall (ASCII solids), instead of `edges`; their element ranges
 * come from the mesh (sph_open_check_mesh). */
static int read_solids(struct cmn_case *c, const char *base, struct sph_open_group *g) {
  char p[192], q[224];
  key(p, sizeof p, base, "solids");
  int n = cmn_case_seq_length(c, p);
  if (n <= 0) return n;
  if (g->nedges > 0 || g->faces)
    return cmn_case_fail(c, p, "give one of 'edges', 'faces' and 'solids', not two");
  const int max = (int)(sizeof g->solids / sizeof g->solids[0]);
  if (n > max) return cmn_case_fail(c, p, "at most %d solids", max);
  const char *type;
  TRY(wall_type(c, g, &type));
  if (strcmp(type, "stl") != 0)
    return cmn_case_fail(c, p, "solids select parts of an STL wall; geometry.walls[%d] is a %s",
                         g->wall, type);
  for (int i = 0; i < n; i++) {
    const char *name;
    snprintf(q, sizeof q, "%s[%d]", p, i);
    TRY(cmn_case_get_string(c, q, &name));
    if (strlen(name) == 0 || strlen(name) >= sizeof g->solids[i])
      return cmn_case_fail(c, q, "expected a solid name of 1 to %zu characters",
                           sizeof g->solids[i] - 1);
    snprintf(g->solids[i], sizeof g->solids[i], "%s", name);
  }
  g->nsolids = n;
  return 0;
}

int sph_open_config_read(struct sph_open_config *oc, struct cmn_case *c, int dim,
                         const double gravity[3], const struct rmn_eos *eos) {
  memset(oc, 0, sizeof *oc);
  int n = cmn_case_seq_length(c, "open_boundaries");
  if (n < 0) return -1;
  if (n > SPH_MAX_OPEN_GROUPS)
    return cmn_case_fail(c, "open_boundaries", "at most %d open-boundary groups are supported",
                         SPH_MAX_OPEN_GROUPS);
  int nwalls = cmn_case_seq_length(c, "geometry.walls");
  if (nwalls < 0) return -1;
  for (int i = 0; i < n; i++) {
    struct sph_open_group *g = &oc->group[i];
    char base[64], p[192];
    snprintf(base, sizeof base, "open_boundaries[%d]", i);
    if (cmn_case_is_map(c, base) != 1)
      return cmn_case_fail(c, base, "expected a mapping (name, wall, impose and a value)");
    const char *name;
    TRY(cmn_case_get_string(c, key(p, sizeof p, base, "name"), &name));
    if (strlen(name) == 0 || strlen(name) >= sizeof g->name || strpbrk(name, ", \"\n/"))
      return cmn_case_fail(c, p,
                           "expected a name of 1 to %zu characters without spaces, commas, "
                           "quotes or slashes",
                           sizeof g->name - 1);
    for (int j = 0; j < i; j++)
      if (strcmp(oc->group[j].name, name) == 0)
        return cmn_case_fail(c, p, "duplicate open-boundary name '%s'", name);
    snprintf(g->name, sizeof g->name, "%s", name);
    long wall;
    TRY(cmn_case_get_long(c, key(p, sizeof p, base, "wall"), 0, nwalls > 0 ? nwalls - 1 : 0,
                          &wall));
    if (nwalls <= 0) return cmn_case_fail(c, p, "there are no geometry.walls");
    g->wall = (int)wall;
    key(p, sizeof p, base, "edges");
    int ne = cmn_case_seq_length(c, p);
    if (ne < 0) return -1;
    const int max_edges = (int)(sizeof g->edges / sizeof g->edges[0]);
    if (ne > max_edges) return cmn_case_fail(c, p, "at most %d edges", max_edges);
    for (int e = 0; e < ne; e++) {
      char q[224];
      snprintf(q, sizeof q, "%s[%d]", p, e);
      TRY(cmn_case_get_long(c, q, 1, 1000000000L, &g->edges[e]));
    }
    g->nedges = ne;
    TRY(read_faces(c, base, dim, g));
    TRY(read_solids(c, base, g));
    static const char *const imposes[] = {"pressure", "velocity", NULL};
    int imposed;
    TRY(cmn_case_get_choice(c, key(p, sizeof p, base, "impose"), imposes, &imposed));
    g->imposed = imposed == 0 ? RMN_IMPOSE_PRESSURE : RMN_IMPOSE_VELOCITY;
    static const char *const shocks[] = {"exact", "linearised", NULL};
    int shock;
    TRY(cmn_case_opt_choice(c, key(p, sizeof p, base, "shock"), shocks, 0, &shock));
    g->shock = shock == 0 ? RMN_SHOCK_EXACT : RMN_SHOCK_LINEARISED;
    TRY(cmn_case_opt_double(c, key(p, sizeof p, base, "outflow_deficit"), 1.0, 0.0, 1e6,
                            &g->outflow_deficit));
    g->bed = 0.0;
    g->depth = NAN;
    TRY(read_value(c, base, dim, gravity, eos, g));
  }
  oc->ngroups = n;
  return 0;
}

/* The inward normal of face f of a box (bit numbering of `faces`) is ±e_a. */
static int on_face(unsigned faces, const double n[3]) {
  for (int f = 0; f < 6; f++) {
    if (!(faces >> f & 1u)) continue;
    const double want = f % 2 ? -1.0 : 1.0; /* the low face's normal points up the axis */
    if (fabs(n[f / 2] - want) < 1e-9) return 1;
  }
  return 0;
}

int sph_open_group_selects(const struct sph_open_group *g, int wall, long edge, const double n[3],
                           unsigned flags) {
  if (wall != g->wall) return 0;
  if (g->faces) return on_face(g->faces, n);
  if (g->nsolids) {
    for (int k = 0; k < g->nsolids; k++)
      if (edge >= g->solid_first[k] && edge <= g->solid_last[k]) return 1;
    return 0;
  }
  if (g->nedges == 0) return (flags & SPH_FLAG_OPEN) != 0;
  for (int k = 0; k < g->nedges; k++)
    if (g->edges[k] == edge) return 1;
  return 0;
}

/* Does group g select mesh element e (wall source[e], element number source_index[e])? */
static int selects(const struct sph_open_group *g, const struct sph_mesh *m, size_t e) {
  return sph_open_group_selects(g, m->source[e], m->source_index[e], m->normal[e], m->flags[e]);
}

int sph_open_check_mesh(struct sph_open_config *oc, struct cmn_case *c,
                        const struct sph_mesh *walls) {
  const struct sph_mesh *m = walls;
  char p[192];
  for (int i = 0; i < oc->ngroups; i++) {
    struct sph_open_group *g = &oc->group[i];
    /* solids by name: their element ranges in the STL file */
    for (int k = 0; k < g->nsolids; k++) {
      int found = -1, times = 0;
      for (int q = 0; q < m->nparts; q++)
        if (m->parts[q].source == g->wall && strcmp(m->parts[q].name, g->solids[k]) == 0) {
          if (found < 0) found = q;
          times++;
        }
      if (times > 1) {
        snprintf(p, sizeof p, "open_boundaries[%d].solids[%d]", i, k);
        return cmn_case_fail(c, p,
                             "%d solids of geometry.walls[%d] are called '%s': selecting by name "
                             "needs unique names",
                             times, g->wall, g->solids[k]);
      }
      if (found < 0) {
        char list[512] = "";
        for (int q = 0; q < m->nparts; q++)
          if (m->parts[q].source == g->wall &&
              strlen(list) + strlen(m->parts[q].name) + 8 < sizeof list)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s'%s'", list[0] ? ", " : "",
                     m->parts[q].name);
        snprintf(p, sizeof p, "open_boundaries[%d].solids[%d]", i, k);
        return cmn_case_fail(c, p, "geometry.walls[%d] has no solid named '%s' (its solids: %s)",
                             g->wall, g->solids[k], list[0] ? list : "none");
      }
      g->solid_first[k] = m->parts[found].first;
      g->solid_last[k] = m->parts[found].last;
    }
    size_t count = 0;
    for (size_t e = 0; e < m->nelem; e++) count += (size_t)selects(g, m, e);
    if (g->faces || g->nsolids) { /* faces of a box, or named solids of an STL file */
      const char *what = g->faces ? "face" : "solid", *list = g->faces ? "open" : "open_solids";
      snprintf(p, sizeof p, "open_boundaries[%d].%ss", i, what);
      for (size_t e = 0; e < m->nelem; e++)
        if (selects(g, m, e) && !(m->flags[e] & SPH_FLAG_OPEN))
          return cmn_case_fail(c, p,
                               "a selected %s of geometry.walls[%d] is a wall, not open (list it "
                               "in the wall's '%s')",
                               what, g->wall, list);
      if (count == 0)
        return cmn_case_fail(c, p, "selects no element of geometry.walls[%d]", g->wall);
    }
    if (g->nedges == 0 && !g->faces && !g->nsolids && count == 0) {
      snprintf(p, sizeof p, "open_boundaries[%d].wall", i);
      return cmn_case_fail(c, p,
                           "geometry.walls[%d] has no open element (flag faces or edges with "
                           "'open' / 'open_edges' in the geometry)",
                           g->wall);
    }
    for (int k = 0; k < g->nedges; k++) {
      snprintf(p, sizeof p, "open_boundaries[%d].edges[%d]", i, k);
      size_t found = 0, open = 0;
      for (size_t e = 0; e < m->nelem; e++)
        if (m->source[e] == g->wall && m->source_index[e] == g->edges[k]) {
          found++;
          open += (m->flags[e] & SPH_FLAG_OPEN) != 0;
        }
      if (found == 0)
        return cmn_case_fail(c, p, "geometry.walls[%d] has no element %ld", g->wall, g->edges[k]);
      if (open != found)
        return cmn_case_fail(c, p,
                             "element %ld of geometry.walls[%d] is a wall, not open (flag it "
                             "with 'open' / 'open_edges' in the geometry)",
                             g->edges[k], g->wall);
    }
  }
  for (size_t e = 0; e < m->nelem; e++) {
    if (!(m->flags[e] & SPH_FLAG_OPEN)) continue;
    int first = -1;
    for (int i = 0; i < oc->ngroups; i++) {
      if (!selects(&oc->group[i], m, e)) continue;
      if (first >= 0) {
        snprintf(p, sizeof p, "open_boundaries[%d]", i);
        return cmn_case_fail(c, p,
                             "element %ld of geometry.walls[%d] is already in the group '%s': "
                             "each open element belongs to exactly one group",
                             m->source_index[e], m->source[e], oc->group[first].name);
      }
      first = i;
    }
    if (first < 0) {
      snprintf(p, sizeof p, "geometry.walls[%d]", m->source[e]);
      return cmn_case_fail(c, p,
                           "its element %ld is open but no open_boundaries group selects it "
                           "(every open element needs an imposed pressure or velocity)",
                           m->source_index[e]);
    }
  }
  return 0;
}
