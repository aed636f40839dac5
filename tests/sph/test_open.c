/*
 * Open boundaries (sabre/sph_open.h, docs/sph-solver.md §10, docs/sph-case-file.md):
 *   - the case-file section: a full example, and every error naming its key;
 *   - each kind of imposed value at given (t, x) against its formula;
 *   - the per-point solve: the Shepard interior state against a naive sum over all fluid particles,
 *     and the stored values against a direct rmn_boundary_solve of the same state (bitwise);
 *   - the exact shock branch against the acoustic relation (second order in a small jump) and the
 *     linearised option, and a strong compression;
 *   - the vertex rule (own Shepard state, normal of its open segments, imposed value at the vertex;
 *     corners included);
 *   - a failed solve's message;
 *   - still water in a 2D box with one open face at the hydrostatic pressure: it behaves like the
 *     wall it still is.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sabre/common.h"
#include "sabre/sph_open.h"
#include "sabre/sph_solver.h"
#include "solver_fixture.h"
#include "testutil.h"

/* ------------------------------------------------------------------------------------------- */
/* Case-file helpers                                                                            */

static const char base2d[] =
    "geometry:\n"
    "  dimension: 2\n"
    "  dr: 0.025\n"
    "  walls: [{type: box, lo: [0, 0], hi: [1, 0.5], open: [x-, x+]}]\n"
    "fluid: {rho0: 1000, c0: 20}\n"
    "gravity: [0, -9.81]\n"
    "time: {end: 1}\n";

static const char base3d[] =
    "geometry:\n"
    "  dimension: 3\n"
    "  dr: 0.05\n"
    "  walls: [{type: box, lo: [0, 0, 0], hi: [1, 0.5, 0.5], open: [x-]}]\n"
    "fluid: {rho0: 1000, c0: 20}\n"
    "gravity: [0, 0, -9.81]\n"
    "time: {end: 1}\n";

/* Read base + extra as case.yaml (non-fatal): sph_config_read and the unused-key check. */
static int read_case(const char *base, int dim, const char *extra, struct sph_config *cfg,
                     char *msg, size_t len) {
  char text[8192];
  snprintf(text, sizeof text, "%s%s", base, extra);
  char err[512];
  struct cmn_case *c = cmn_case_parse(text, "case.yaml", err, sizeof err);
  if (!c) fail_msg("%s", err);
  cmn_case_set_fatal(c, 0);
  int rc = sph_config_read(cfg, c, dim);
  if (rc == 0) {
    cmn_case_mark_used(c, "geometry");
    rc = cmn_case_check_unused(c);
  }
  snprintf(msg, len, "%s", cmn_case_error(c));
  cmn_case_free(c);
  return rc;
}

static void expect_error(const char *extra, const char *key, const char *what) {
  struct sph_config *cfg = calloc(1, sizeof *cfg);
  char msg[2048];
  assert_int_equal(read_case(base2d, 2, extra, cfg, msg, sizeof msg), -1);
  print_message("%s\n", msg);
  if (!strstr(msg, "case.yaml") || !strstr(msg, key) || !strstr(msg, what))
    fail_msg("'%s' lacks 'case.yaml', '%s' or '%s'", msg, key, what);
  free(cfg);
}

static char tmpdir[64];

static const char *write_file(const char *name, const char *text) {
  static char path[8][256];
  static int k = 0;
  k = (k + 1) % 8;
  snprintf(path[k], sizeof path[k], "%s/%s", tmpdir, name);
  FILE *f = fopen(path[k], "w");
  assert_non_null(f);
  fputs(text, f);
  fclose(f);
  return path[k];
}

static int setup(void **state) {
  (void)state;
  snprintf(tmpdir, sizeof tmpdir, "/tmp/sabre-test-open-XXXXXX");
  assert_non_null(mkdtemp(tmpdir));
  gsl_set_error_handler_off();
  return 0;
}

static int teardown(void **state) {
  (void)state;
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  return system(cmd) == 0 ? 0 : -1;
}

/* ------------------------------------------------------------------------------------------- */

static void test_parse(void **state) {
  (void)state;
  struct sph_config *cfg = calloc(1, sizeof *cfg);
  char msg[2048], extra[4096];
  const char *tab = write_file("inlet.csv", "# inflow\nt,un\n0,0\n0.5,0.2\n");
  snprintf(extra, sizeof extra,
           "open_boundaries:\n"
           "  - {name: in, wall: 0, edges: [4], impose: velocity, table: %s}\n"
           "  - name: out\n"
           "    wall: 0\n"
           "    edges: [2]\n"
           "    impose: pressure\n"
           "    shock: linearised\n"
           "    hydrostatic: {depth: measured, bed: 0.01}\n",
           tab);
  assert_int_equal(read_case(base2d, 2, extra, cfg, msg, sizeof msg), 0);
  const struct sph_open_config *oc = &cfg->open;
  assert_int_equal(oc->ngroups, 2);
  assert_string_equal(oc->group[0].name, "in");
  assert_int_equal(oc->group[0].imposed, RMN_IMPOSE_VELOCITY);
  assert_int_equal(oc->group[0].source, SPH_OPEN_TABLE);
  assert_int_equal(oc->group[0].normal, 1);
  assert_int_equal(oc->group[0].shock, RMN_SHOCK_EXACT);
  assert_true(oc->group[0].nedges == 1 && oc->group[0].edges[0] == 4);
  assert_int_equal(oc->group[1].imposed, RMN_IMPOSE_PRESSURE);
  assert_int_equal(oc->group[1].source, SPH_OPEN_HYDROSTATIC);
  assert_int_equal(oc->group[1].shock, RMN_SHOCK_LINEARISED);
  assert_true(oc->group[1].depth_measured && oc->group[1].bed == 0.01);
  /* generators */
  assert_int_equal(read_case(base2d, 2,
                             "open_boundaries:\n"
                             "  - {name: w, wall: 0, edges: [4], impose: velocity,\n"
                             "     stokes5: {depth: 0.5, amplitude: 0.05, length: 2.5, x0: 0.1}}\n"
                             "  - {name: p, wall: 0, edges: [2], impose: velocity,\n"
                             "     poiseuille: {center: [1, 0.25], radius: 0.25, flux: 0.01}}\n",
                             cfg, msg, sizeof msg),
                   0);
  assert_rel(cfg->open.group[0].stokes5.height, 0.1, 1e-15);
  assert_rel(cfg->open.group[0].stokes5.g, 9.81, 1e-15);
  assert_rel(cfg->open.group[1].poiseuille.u_max, 3.0 * 0.01 / (4.0 * 0.25), 1e-15);
  assert_int_equal(read_case(base3d, 3,
                             "open_boundaries:\n"
                             "  - {name: s, wall: 0, impose: pressure,\n"
                             "     solitary: {depth: 0.3, amplitude: 0.1, angle: 30, x0: -2}}\n",
                             cfg, msg, sizeof msg),
                   0);
  assert_rel(cfg->open.group[0].solitary.angle, M_PI / 6.0, 1e-15);
  free(cfg);
}

static void test_parse_errors(void **state) {
  (void)state;
  const char *g = "open_boundaries:\n  - {name: o, wall: 0, edges: [2], ";
  char e[1024];
#define EXPECT(rest, key, what)                \
  do {                                         \
    snprintf(e, sizeof e, "%s%s}\n", g, rest); \
    expect_error(e, key, what);                \
  } while (0)
  EXPECT("impose: pressure, pressure: 0, colour: red", "open_boundaries[0].colour", "unknown");
  EXPECT("pressure: 0", "open_boundaries[0].impose", "");
  EXPECT("impose: mass, pressure: 0", "open_boundaries[0].impose", "pressure, velocity");
  EXPECT("impose: pressure", "open_boundaries[0]", "no value");
  EXPECT("impose: pressure, pressure: 0, velocity: [1, 0]", "open_boundaries[0].velocity",
         "one value only");
  EXPECT("impose: pressure, normal_velocity: 0.1", "open_boundaries[0].normal_velocity",
         "does not go with impose: pressure");
  EXPECT("impose: velocity, hydrostatic: {depth: 0.2}", "open_boundaries[0].hydrostatic",
         "does not go with impose: velocity");
  EXPECT("impose: pressure, pressure: -1e6", "open_boundaries[0].pressure", "vacuum");
  EXPECT("impose: pressure, pressure: '2*sin(w*t)'", "open_boundaries[0].pressure",
         "unknown name 'w'");
  EXPECT("impose: pressure, pressure: [1, 2]", "open_boundaries[0].pressure", "");
  EXPECT("impose: velocity, velocity: [1]", "open_boundaries[0].velocity", "expected 2");
  EXPECT("impose: velocity, velocity: [30, 0]", "open_boundaries[0].velocity", "subsonic");
  EXPECT("impose: velocity, normal_velocity: 'x +'", "open_boundaries[0].normal_velocity",
         "expected a number or an expression");
  EXPECT("impose: pressure, shock: exactly, pressure: 0", "open_boundaries[0].shock",
         "exact, linearised");
  EXPECT("impose: velocity, velocity: [1, 0], tangential_velocity: [0, 1]",
         "open_boundaries[0].tangential_velocity", "whole velocity");
  EXPECT("impose: pressure, hydrostatic: {depth: deep}", "open_boundaries[0].hydrostatic.depth",
         "measured");
  EXPECT("impose: pressure, hydrostatic: {depth: measured, absorbing: true}",
         "open_boundaries[0].hydrostatic.absorbing", "still depth as a number");
  EXPECT("impose: pressure, hydrostatic: {depth: 0.2, absorbing: maybe}",
         "open_boundaries[0].hydrostatic.absorbing", "");
  EXPECT("impose: pressure, hydrostatic: {depth: 0.2, current: 0.3}",
         "open_boundaries[0].hydrostatic.current", "absorbing outlet only");
  EXPECT("impose: pressure, hydrostatic: {depth: 0.2, absorbing: true, current: -1.5}",
         "open_boundaries[0].hydrostatic.current", "subcritical");
  EXPECT("impose: pressure, hydrostatic: {depth: 0.2, absorbing: true, current: fast}",
         "open_boundaries[0].hydrostatic.current", "");
  EXPECT("impose: pressure, pressure: 0, outflow_deficit: -0.5",
         "open_boundaries[0].outflow_deficit", "");
  EXPECT("impose: pressure, pressure: 0, outflow_deficit: lots",
         "open_boundaries[0].outflow_deficit", "");
  EXPECT("impose: velocity, poiseuille: {center: [1, 0.25], radius: 0.25, u_max: 1, flux: 2}",
         "open_boundaries[0].poiseuille", "exactly one of 'u_max'");
  EXPECT("impose: velocity, poiseuille: {center: [1, 0.25], radius: 0.25, u_max: 25}",
         "open_boundaries[0].poiseuille.u_max", "subsonic");
  EXPECT("impose: velocity, poiseuille: {center: [1, 0.25], radius: 0.25, u_max: 1, ramp: -2}",
         "open_boundaries[0].poiseuille.ramp", ">= 0");
  EXPECT("solids: [inlet], impose: pressure, pressure: 0", "open_boundaries[0].solids",
         "give one of 'edges', 'faces' and 'solids', not two");
  expect_error(
      "open_boundaries:\n  - {name: o, wall: 0, solids: [inlet], impose: pressure, "
      "pressure: 0}\n",
      "open_boundaries[0].solids",
      "solids select parts of an STL wall; geometry.walls[0] is a box");
  EXPECT("impose: velocity, poiseuille: {shape: circle, center: [1, 0.25], radius: 1, u_max: 1}",
         "open_boundaries[0].poiseuille.shape", "plates in 2D");
  EXPECT("impose: velocity, stokes5: {depth: 0.5, height: 0.5, length: 2.5}",
         "open_boundaries[0].stokes5.height", "breaking");
  EXPECT("impose: velocity, stokes5: {depth: 0.5, amplitude: 0.25, length: 2.5}",
         "open_boundaries[0].stokes5.amplitude", "breaking");
  EXPECT("impose: velocity, stokes5: {depth: 0.5, height: 0.1, length: 2.5, period: 2}",
         "open_boundaries[0].stokes5", "exactly one of 'length'");
  EXPECT("impose: velocity, stokes5: {depth: 0.5, height: 0.1, length: 2.5, depht: 1}",
         "open_boundaries[0].stokes5.depht", "unknown");
  EXPECT("impose: pressure, solitary: {depth: 0.3, amplitude: 0.3}",
         "open_boundaries[0].solitary.amplitude", "");
  EXPECT("impose: pressure, stokes5: 3", "open_boundaries[0].stokes5", "mapping");
  EXPECT("impose: pressure, table: /nonexistent/p.csv", "open_boundaries[0].table",
         "/nonexistent/p.csv");
  char t[512];
  snprintf(t, sizeof t, "impose: pressure, table: %s",
           write_file("back.csv", "t,p\n0,0\n0.5,1\n0.5,2\n"));
  EXPECT(t, "open_boundaries[0].table", "increase strictly");
  snprintf(t, sizeof t, "impose: pressure, table: %s", write_file("hdr.csv", "time,p\n0,0\n"));
  EXPECT(t, "open_boundaries[0].table", "the header must be 't,p'");
  snprintf(t, sizeof t, "impose: velocity, table: %s", write_file("uv.csv", "t,u\n0,0\n"));
  EXPECT(t, "open_boundaries[0].table", "'t,un'");
  snprintf(t, sizeof t, "impose: pressure, table: %s", write_file("bad.csv", "t,p\n0,abc\n"));
  EXPECT(t, "open_boundaries[0].table", "expected a number, got 'abc'");
  snprintf(t, sizeof t, "impose: pressure, table: %s", write_file("vac.csv", "t,p\n0,-1e6\n"));
  EXPECT(t, "open_boundaries[0].table", "vacuum");
#undef EXPECT
  expect_error(
      "open_boundaries: [{name: a, wall: 0, impose: pressure, pressure: 0},\n"
      "  {name: a, wall: 0, impose: pressure, pressure: 0}]\n",
      "open_boundaries[1].name", "duplicate");
  expect_error("open_boundaries: [{name: a, wall: 3, impose: pressure, pressure: 0}]\n",
               "open_boundaries[0].wall", "");
  expect_error("open_boundaries: [{name: 'a b', wall: 0, impose: pressure, pressure: 0}]\n",
               "open_boundaries[0].name", "without spaces");
  {
    struct sph_config *cfg = calloc(1, sizeof *cfg);
    char nog[1024], msg[1024];
    snprintf(nog, sizeof nog, "%.*sgravity: [0, 0]\ntime: {end: 1}\n",
             (int)(strstr(base2d, "gravity") - base2d), base2d);
    assert_int_equal(read_case(nog, 2,
                               "open_boundaries: [{name: a, wall: 0, impose: pressure, "
                               "hydrostatic: {depth: 0.1}}]\n",
                               cfg, msg, sizeof msg),
                     -1);
    print_message("%s\n", msg);
    assert_non_null(strstr(msg, "open_boundaries[0].hydrostatic"));
    assert_non_null(strstr(msg, "gravity"));
    free(cfg);
  }
  expect_error("open_boundaries: {name: a}\n", "open_boundaries", "sequence");
  expect_error(
      "open_boundaries: [{name: a, wall: 0, faces: [x-], edges: [4], impose: pressure, "
      "pressure: 0}]\n",
      "open_boundaries[0].faces", "not both");
  expect_error(
      "open_boundaries: [{name: a, wall: 0, faces: [z-], impose: pressure, "
      "pressure: 0}]\n",
      "open_boundaries[0].faces[0]", "no such face in 2D");
}

/* sph_open_check_mesh on the meshed box of base2d (edges 1 bottom, 2 right, 3 top, 4 left). */
static int check_mesh(const char *walls, const char *extra, char *msg, size_t len) {
  char text[4096];
  snprintf(text, sizeof text,
           "geometry: {dimension: 2, dr: 0.1, walls: [%s]}\n"
           "fluid: {rho0: 1000, c0: 20}\ngravity: [0, -9.81]\ntime: {end: 1}\n%s",
           walls, extra);
  char err[512];
  struct cmn_case *c = cmn_case_parse(text, "case.yaml", err, sizeof err);
  assert_non_null(c);
  struct sph_geometry g;
  sph_geometry_read(&g, c); /* fatal mode: the geometry itself is good */
  cmn_case_set_fatal(c, 0);
  struct sph_config *cfg = calloc(1, sizeof *cfg);
  int rc = sph_config_read(cfg, c, 2);
  assert_int_equal(rc, 0);
  rc = sph_open_check_mesh(&cfg->open, c, &g.walls);
  snprintf(msg, len, "%s", cmn_case_error(c));
  if (rc) print_message("%s\n", msg);
  free(cfg);
  sph_geometry_free(&g);
  cmn_case_free(c);
  return rc;
}

static void test_check_mesh(void **state) {
  (void)state;
  char msg[2048];
  const char *box = "{type: box, lo: [0, 0], hi: [1, 0.5], open: [x+]}";
  assert_int_equal(
      check_mesh(box, "open_boundaries: [{name: o, wall: 0, impose: pressure, pressure: 0}]\n", msg,
                 sizeof msg),
      0);
  assert_int_equal(check_mesh(box,
                              "open_boundaries: [{name: o, wall: 0, edges: [2], impose: pressure, "
                              "pressure: 0}]\n",
                              msg, sizeof msg),
                   0);
  /* a selected element that is a wall */
  assert_int_equal(check_mesh(box,
                              "open_boundaries: [{name: o, wall: 0, edges: [2, 3], impose: "
                              "pressure, pressure: 0}]\n",
                              msg, sizeof msg),
                   -1);
  assert_non_null(strstr(msg, "open_boundaries[0].edges[1]"));
  assert_non_null(strstr(msg, "element 3 of geometry.walls[0] is a wall"));
  /* an element that does not exist */
  assert_int_equal(check_mesh(box,
                              "open_boundaries: [{name: o, wall: 0, edges: [7], impose: "
                              "pressure, pressure: 0}]\n",
                              msg, sizeof msg),
                   -1);
  assert_non_null(strstr(msg, "has no element 7"));
  /* an open element without a group */
  assert_int_equal(check_mesh(box, "", msg, sizeof msg), -1);
  assert_non_null(strstr(msg, "geometry.walls[0]"));
  assert_non_null(strstr(msg, "element 2 is open but no open_boundaries group"));
  /* in two groups */
  assert_int_equal(check_mesh(box,
                              "open_boundaries: [{name: a, wall: 0, impose: pressure, pressure: "
                              "0},\n  {name: b, wall: 0, edges: [2], impose: pressure, pressure: "
                              "0}]\n",
                              msg, sizeof msg),
                   -1);
  assert_non_null(strstr(msg, "open_boundaries[1]"));
  assert_non_null(strstr(msg, "exactly one group"));
  /* faces of a box instead of element numbers */
  const char *box2 = "{type: box, lo: [0, 0], hi: [1, 0.5], open: [x-, x+]}";
  assert_int_equal(check_mesh(box2,
                              "open_boundaries: [{name: a, wall: 0, faces: [x-], impose: pressure, "
                              "pressure: 0},\n  {name: b, wall: 0, faces: [x+], impose: pressure, "
                              "pressure: 0}]\n",
                              msg, sizeof msg),
                   0);
  assert_int_equal(check_mesh(box2,
                              "open_boundaries: [{name: a, wall: 0, faces: [x-, y-], impose: "
                              "pressure, pressure: 0}, {name: b, wall: 0, faces: [x+], impose: "
                              "pressure, pressure: 0}]\n",
                              msg, sizeof msg),
                   -1);
  assert_non_null(strstr(msg, "open_boundaries[0].faces"));
  assert_non_null(strstr(msg, "is a wall, not open"));
  /* a whole wall without open elements */
  assert_int_equal(check_mesh("{type: box, lo: [0, 0], hi: [1, 0.5]}",
                              "open_boundaries: [{name: o, wall: 0, impose: pressure, pressure: "
                              "0}]\n",
                              msg, sizeof msg),
                   -1);
  assert_non_null(strstr(msg, "open_boundaries[0].wall"));
  assert_non_null(strstr(msg, "no open element"));
}

/* ------------------------------------------------------------------------------------------- */
/* Values                                                                                       */

struct src_fixture {
  struct sph_config *cfg;
  struct sph_open_source src;
  struct rmn_eos eos;
};

static void src_make(struct src_fixture *fx, const char *base, int dim, const char *group) {
  fx->cfg = calloc(1, sizeof *fx->cfg);
  char msg[2048], extra[4096];
  snprintf(extra, sizeof extra, "open_boundaries:\n  - {name: o, wall: 0, %s}\n", group);
  if (read_case(base, dim, extra, fx->cfg, msg, sizeof msg) != 0) fail_msg("%s", msg);
  assert_int_equal(rmn_eos_init(&fx->eos, 1000.0, 20.0, 7.0), RMN_SUCCESS);
  if (sph_open_source_init(&fx->src, &fx->cfg->open.group[0], dim, fx->cfg->gravity, &fx->eos, msg,
                           sizeof msg) != 0)
    fail_msg("%s", msg);
}

static void src_free(struct src_fixture *fx) {
  sph_open_source_free(&fx->src);
  free(fx->cfg);
}

static struct sph_open_value src_eval(struct src_fixture *fx, double t, double x, double y,
                                      double z, double nx, double ny, double nz, double level) {
  const double pos[3] = {x, y, z}, n[3] = {nx, ny, nz};
  struct sph_open_value v;
  sph_open_source_eval(&fx->src, t, pos, n, level, &v);
  return v;
}

static void test_values_2d(void **state) {
  (void)state;
  struct src_fixture fx;
  struct sph_open_value v;
  /* constant pressure, tangential velocity without its normal part */
  src_make(&fx, base2d, 2, "impose: pressure, pressure: 1234.5, tangential_velocity: [0.3, 0.4]");
  v = src_eval(&fx, 0.7, 1.0, 0.2, 0.0, -1.0, 0.0, 0.0, NAN);
  assert_true(v.p == 1234.5 && isnan(v.un));
  assert_true(v.u[0] == 0.0 && v.u[1] == 0.4 && v.u[2] == 0.0);
  src_free(&fx);
  /* expression of t, x, y */
  src_make(&fx, base2d, 2, "impose: pressure, pressure: '100*t + 10*x - 5*y'");
  v = src_eval(&fx, 0.3, 0.2, 0.7, 0.0, 1.0, 0.0, 0.0, NAN);
  assert_rel(v.p, 30.0 + 2.0 - 3.5, 1e-15);
  src_free(&fx);
  /* velocity vector: u_n = u·n, the vector kept for the tangential part */
  src_make(&fx, base2d, 2, "impose: velocity, velocity: ['0.5*t', '-0.25 + y']");
  v = src_eval(&fx, 0.4, 0.0, 0.1, 0.0, 0.6, 0.8, 0.0, NAN);
  assert_rel(v.u[0], 0.2, 1e-15);
  assert_rel(v.u[1], -0.15, 1e-14);
  assert_rel(v.un, 0.6 * 0.2 - 0.8 * 0.15, 1e-14);
  assert_true(isnan(v.p));
  src_free(&fx);
  /* normal velocity + tangential */
  src_make(&fx, base2d, 2,
           "impose: velocity, normal_velocity: '0.1*sin(2*pi*t)', tangential_velocity: [0.3, "
           "0.4]");
  v = src_eval(&fx, 0.125, 0.5, 0.0, 0.0, 0.0, 1.0, 0.0, NAN);
  assert_rel(v.un, 0.1 * sin(0.25 * M_PI), 1e-15);
  assert_rel(v.u[0], 0.3, 1e-15);
  assert_rel(v.u[1], v.un, 1e-15);
  src_free(&fx);
  /* tables: at nodes, between them, constant beyond the ends */
  char g[512];
  snprintf(g, sizeof g, "impose: pressure, table: %s",
           write_file("p.csv", "t,p\n0,0\n0.5,100\n1.0,50\n"));
  src_make(&fx, base2d, 2, g);
  const double tq[5] = {-1.0, 0.25, 0.5, 0.75, 2.0}, pq[5] = {0.0, 50.0, 100.0, 75.0, 50.0};
  for (int i = 0; i < 5; i++)
    assert_rel(src_eval(&fx, tq[i], 0.3, 0.2, 0.0, 1.0, 0.0, 0.0, NAN).p, pq[i], 1e-15);
  src_free(&fx);
  snprintf(g, sizeof g, "impose: velocity, table: %s",
           write_file("u.csv", "t,u,v\n0,0,0\n1,0.2,-0.1\n"));
  src_make(&fx, base2d, 2, g);
  v = src_eval(&fx, 0.25, 0.3, 0.2, 0.0, -1.0, 0.0, 0.0, NAN);
  assert_rel(v.u[0], 0.05, 1e-15);
  assert_rel(v.u[1], -0.025, 1e-15);
  assert_rel(v.un, -0.05, 1e-15);
  src_free(&fx);
  /* Poiseuille between plates, by U_max and by flux */
  src_make(&fx, base2d, 2,
           "impose: velocity, poiseuille: {center: [0, 0.3], radius: 0.1, u_max: 0.2}");
  v = src_eval(&fx, 0.0, 0.0, 0.35, 0.0, 1.0, 0.0, 0.0, NAN);
  assert_rel(v.un, 0.15, 1e-14);
  assert_rel(v.u[0], 0.15, 1e-14);
  assert_true(v.u[1] == 0.0);
  assert_true(src_eval(&fx, 0.0, 0.0, 0.45, 0.0, 1.0, 0.0, 0.0, NAN).un == 0.0);
  src_free(&fx);
  src_make(&fx, base2d, 2,
           "impose: velocity, poiseuille: {center: [0, 0.3], radius: 0.1, flux: 0.004}");
  assert_rel(src_eval(&fx, 0.0, 0.0, 0.3, 0.0, 1.0, 0.0, 0.0, NAN).un, 3.0 * 0.004 / 0.4, 1e-14);
  src_free(&fx);
  /* the start-up ramp s²(3 − 2s), s = min(t/T, 1): 0 before the start, 1/2 at T/2, 1 from T */
  src_make(&fx, base2d, 2,
           "impose: velocity, poiseuille: {center: [0, 0.3], radius: 0.1, u_max: 0.2, ramp: 4}");
  const double tr[6] = {-1.0, 0.0, 1.0, 2.0, 4.0, 9.0}, fr[6] = {0.0, 0.0, 0.15625, 0.5, 1.0, 1.0};
  for (int i = 0; i < 6; i++)
    assert_rel(src_eval(&fx, tr[i], 0.0, 0.35, 0.0, 1.0, 0.0, 0.0, NAN).un, 0.15 * fr[i], 1e-14);
  src_free(&fx);
  /* hydrostatic: the Tait profile below bed + depth, zero above; measured: the level given */
  src_make(&fx, base2d, 2, "impose: pressure, hydrostatic: {depth: 0.3, bed: 0.05}");
  const double d = 0.25, pe = sph_hydrostatic_pressure(&fx.eos, 9.81, d);
  assert_rel(src_eval(&fx, 0.0, 1.0, 0.1, 0.0, -1.0, 0.0, 0.0, NAN).p, pe, 1e-15);
  /* ρ0 g d (1 + g d/(2 c0²)) to second order in g d/c0² */
  assert_rel(pe, 1000.0 * 9.81 * d * (1.0 + 9.81 * d / (2.0 * 400.0)), 1e-4);
  assert_true(src_eval(&fx, 0.0, 1.0, 0.4, 0.0, -1.0, 0.0, 0.0, NAN).p == 0.0);
  src_free(&fx);
  src_make(&fx, base2d, 2, "impose: pressure, hydrostatic: {depth: measured}");
  assert_rel(src_eval(&fx, 0.0, 1.0, 0.1, 0.0, -1.0, 0.0, 0.0, 0.35).p,
             sph_hydrostatic_pressure(&fx.eos, 9.81, 0.25), 1e-15);
  assert_true(src_eval(&fx, 0.0, 1.0, 0.1, 0.0, -1.0, 0.0, 0.0, NAN).p == 0.0);
  src_free(&fx);
  /* Stokes wave: the generator at the mapped point (bed, x0), clamped to the surface above it */
  src_make(&fx, base2d, 2,
           "impose: velocity, stokes5: {depth: 0.5, height: 0.1, length: 2.5, bed: 0.1, x0: "
           "0.3}");
  struct sph_stokes5 w;
  struct sph_stokes5_params wp;
  sph_stokes5_params_init(&wp);
  wp.depth = 0.5;
  wp.height = 0.1;
  wp.length = 2.5;
  assert_int_equal(sph_stokes5_init(&w, &wp, NULL, 0), SPH_WAVE_SUCCESS);
  struct sph_wave_point pt;
  assert_int_equal(sph_stokes5_eval(&w, 1.2 - 0.3, 0.4 - 0.1, 0.7, &pt), SPH_WAVE_SUCCESS);
  v = src_eval(&fx, 0.7, 1.2, 0.4, 0.0, -1.0, 0.0, 0.0, NAN);
  assert_rel(v.u[0], pt.u, 1e-15);
  assert_rel(v.u[1], pt.w, 1e-15);
  assert_rel(v.un, -pt.u, 1e-15);
  v = src_eval(&fx, 0.7, 1.2, 5.0, 0.0, -1.0, 0.0, 0.0, NAN); /* far above the surface */
  sph_stokes5_eval(&w, 0.9, pt.eta, 0.7, &pt);
  assert_rel(v.u[0], pt.u, 1e-15);
  assert_rel(v.u[1], pt.w, 1e-15);
  src_free(&fx);
  src_make(&fx, base2d, 2,
           "impose: pressure, stokes5: {depth: 0.5, height: 0.1, length: 2.5, bed: 0.1, x0: "
           "0.3}");
  sph_stokes5_eval(&w, 0.9, 0.3, 0.7, &pt);
  assert_rel(src_eval(&fx, 0.7, 1.2, 0.4, 0.0, -1.0, 0.0, 0.0, NAN).p, pt.p, 1e-15);
  assert_true(src_eval(&fx, 0.7, 1.2, 5.0, 0.0, -1.0, 0.0, 0.0, NAN).p == 0.0);
  src_free(&fx);
}

/* ∫∫ over the rectangle [−a, a] × [−b, b] of the source's normal speed, by Gauss–Legendre. */
static double rect_flux(struct src_fixture *fx, double a, double b) {
  gsl_integration_glfixed_table *tab = gsl_integration_glfixed_table_alloc(64);
  double sum = 0.0;
  for (size_t i = 0; i < 64; i++)
    for (size_t j = 0; j < 64; j++) {
      double y, z, wy, wz;
      gsl_integration_glfixed_point(-a, a, i, &y, &wy, tab);
      gsl_integration_glfixed_point(-b, b, j, &z, &wz, tab);
      sum += wy * wz * src_eval(fx, 0.0, 0.0, 0.25 + y, 0.25 + z, 1.0, 0.0, 0.0, NAN).un;
    }
  gsl_integration_glfixed_table_free(tab);
  return sum;
}

static void test_values_3d(void **state) {
  (void)state;
  struct src_fixture fx;
  struct sph_open_value v;
  /* circular pipe by flux */
  src_make(&fx, base3d, 3,
           "impose: velocity, poiseuille: {center: [0, 0.25, 0.25], radius: 0.1, flux: 0.002}");
  const double U = 2.0 * 0.002 / (M_PI * 0.01);
  v = src_eval(&fx, 0.0, 0.0, 0.25 + 0.06, 0.25 - 0.03, 1.0, 0.0, 0.0, NAN);
  assert_rel(v.un, U * (1.0 - 0.0045 / 0.01), 1e-14);
  assert_rel(v.u[0], v.un, 1e-15);
  src_free(&fx);
  /* rectangular duct 2a × 2b, a along y: U_max at the centre, zero on the walls, the flux given,
   * and the Poisson equation Δu = const (finite differences) */
  src_make(&fx, base3d, 3,
           "impose: velocity, poiseuille: {shape: rectangle, center: [0, 0.25, 0.25], "
           "half_widths: [0.1, 0.05], axis: [0, 1, 0], flux: 0.001}");
  const double uc = src_eval(&fx, 0.0, 0.0, 0.25, 0.25, 1.0, 0.0, 0.0, NAN).un;
  assert_rel(rect_flux(&fx, 0.1, 0.05), 0.001, 1e-8);
  assert_abs(src_eval(&fx, 0.0, 0.0, 0.35, 0.27, 1.0, 0.0, 0.0, NAN).un, 0.0, 1e-12 * uc);
  assert_abs(src_eval(&fx, 0.0, 0.0, 0.22, 0.30, 1.0, 0.0, 0.0, NAN).un, 0.0, 1e-12 * uc);
  const double hh = 1e-3, y0 = 0.25 + 0.03, z0 = 0.25 - 0.02;
  double lap[2];
  for (int k = 0; k < 2; k++) {
    const double yc = k ? y0 : 0.25, zc = k ? z0 : 0.25;
    const double c0 = src_eval(&fx, 0.0, 0.0, yc, zc, 1.0, 0.0, 0.0, NAN).un;
    lap[k] = (src_eval(&fx, 0.0, 0.0, yc + hh, zc, 1.0, 0.0, 0.0, NAN).un +
              src_eval(&fx, 0.0, 0.0, yc - hh, zc, 1.0, 0.0, 0.0, NAN).un +
              src_eval(&fx, 0.0, 0.0, yc, zc + hh, 1.0, 0.0, 0.0, NAN).un +
              src_eval(&fx, 0.0, 0.0, yc, zc - hh, 1.0, 0.0, 0.0, NAN).un - 4.0 * c0) /
             (hh * hh);
  }
  assert_rel(lap[1], lap[0], 1e-5);
  /* the same duct with the sides swapped describes the same flow turned by 90° */
  struct src_fixture fy;
  src_make(&fy, base3d, 3,
           "impose: velocity, poiseuille: {shape: rectangle, center: [0, 0.25, 0.25], "
           "half_widths: [0.05, 0.1], axis: [0, 0, 1], flux: 0.001}");
  assert_rel(src_eval(&fy, 0.0, 0.0, y0, z0, 1.0, 0.0, 0.0, NAN).un,
             src_eval(&fx, 0.0, 0.0, y0, z0, 1.0, 0.0, 0.0, NAN).un, 1e-13);
  src_free(&fy);
  src_free(&fx);
  /* by U_max */
  src_make(&fx, base3d, 3,
           "impose: velocity, poiseuille: {shape: rectangle, center: [0, 0.25, 0.25], "
           "half_widths: [0.1, 0.05], axis: [0, 1, 0], u_max: 0.3}");
  assert_rel(src_eval(&fx, 0.0, 0.0, 0.25, 0.25, 1.0, 0.0, 0.0, NAN).un, 0.3, 1e-14);
  src_free(&fx);
  /* solitary wave at an angle: the generator at (x·direction, x·(up × direction), z − bed) */
  src_make(&fx, base3d, 3,
           "impose: velocity, solitary: {depth: 0.3, amplitude: 0.1, angle: 30, x0: -0.5, bed: "
           "0.02}");
  struct sph_solitary sw;
  struct sph_solitary_params sp;
  sph_solitary_params_init(&sp);
  sp.depth = 0.3;
  sp.amplitude = 0.1;
  sp.angle = M_PI / 6.0;
  sp.x0 = -0.5;
  assert_int_equal(sph_solitary_init(&sw, &sp, NULL, 0), SPH_WAVE_SUCCESS);
  struct sph_wave_point pt;
  assert_int_equal(sph_solitary_eval(&sw, 0.1, 0.2, 0.15, 0.4, &pt), SPH_WAVE_SUCCESS);
  v = src_eval(&fx, 0.4, 0.1, 0.2, 0.17, 1.0, 0.0, 0.0, NAN);
  assert_rel(v.u[0], pt.u, 1e-15);
  assert_rel(v.u[1], pt.v, 1e-15);
  assert_rel(v.u[2], pt.w, 1e-15);
  assert_rel(v.un, pt.u, 1e-15);
  src_free(&fx);
}

/* ------------------------------------------------------------------------------------------- */
/* Solver-level fixtures                                                                        */

/* A 2D box 0.5 × 0.4 m with its right face open, water to 0.2 m (first row Δr from the walls). */
static const char box_case[] =
    "geometry:\n"
    "  dimension: 2\n"
    "  dr: 0.025\n"
    "  first_row: 1\n"
    "  walls: [{type: box, lo: [0, 0], hi: [0.5, 0.4], open: [x+]}]\n"
    "  fluid: [{type: box, lo: [0, 0], hi: [0.5, 0.2]}]\n"
    "fluid: {rho0: 1000, c0: 20}\n"
    "gravity: [0, -9.81]\n"
    "initial: {pressure: hydrostatic}\n"
    "time: {end: 1}\n";

static struct sph_solver *box_solver(const char *open) {
  char text[4096];
  snprintf(text, sizeof text, "%sopen_boundaries:\n  - {name: right, wall: 0, %s}\n", box_case,
           open);
  return fixture_solver_from_case(text);
}

/* Perturb the fluid (seeded): velocities and densities, so that the interior states differ. */
static void stir(struct sph_solver *sv, double du, double drho) {
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 2385);
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < f->n; a++) {
    for (int c = 0; c < 2; c++) f->v[c][a] += sabre_rng_uniform(&rng, -du, du);
    f->rho[a] *= 1.0 + sabre_rng_uniform(&rng, -drho, drho);
  }
  sph_solver_sync(sv);
}

/* Naive Shepard interior state at x over every fluid particle, J(33–35) with the full
 * hydrostatic correction: with gravity each particle's corrected pressure clipped at 0, without
 * the floor of the wall vertices. */
static void naive_interior(const struct sph_solver *sv, const double *x, double *p, double u[3],
                           double *alpha, double *ytop) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  double al = 0.0, sp = 0.0, sr = 0.0, spos = 0.0, su[3] = {0.0, 0.0, 0.0};
  *ytop = -INFINITY;
  for (size_t b = 0; b < f->n; b++) {
    double r[3] = {x[0] - f->x[0][b], x[1] - f->x[1][b], x[2] - f->x[2][b]};
    const double d = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    const double w = sph_kernel_w(&sv->kernel, d);
    if (w <= 0.0) continue;
    const double vw = f->mass[b] / f->rho[b] * w;
    const double pb = rmn_eos_pressure(&sv->eos, f->rho[b]);
    *ytop = fmax(*ytop, f->x[1][b]);
    al += vw;
    const double ph = pb + f->rho[b] * (sv->cfg.gravity[0] * r[0] + sv->cfg.gravity[1] * r[1]);
    sp += vw * ph;
    spos += vw * fmax(ph, 0.0);
    sr += vw * pb;
    for (int c = 0; c < 3; c++) su[c] += vw * f->v[c][b];
  }
  *alpha = al;
  const int gravity = sv->cfg.gravity[0] != 0.0 || sv->cfg.gravity[1] != 0.0;
  *p = !(al > 0.0) ? NAN : gravity ? spos / al : fmax(sp / al, fmin(sr / al, 0.0));
  for (int c = 0; c < 3; c++) u[c] = al > 0.0 ? su[c] / al : NAN;
}

/* Every wet point of group 0: interior state = naive sums (1e-12); stored values = a direct
 * rmn_boundary_solve of the recorded input (bitwise) and of the naive state (1e-12). */
static void check_points(struct sph_solver *sv, size_t *nseg_wet, size_t *nvert_wet) {
  const struct sph_open *op = sv->open;
  const struct sph_open_points *pt = &op->pts[0];
  struct rmn_params prm;
  rmn_params_default(&prm);
  prm.shock = (enum rmn_shock_model)sv->cfg.open.group[0].shock;
  struct rmn_workspace *ws = rmn_workspace_alloc();
  *nseg_wet = *nvert_wet = 0;
  for (size_t k = 0; k < pt->npoints; k++) {
    const int is_seg = k < pt->nseg;
    const struct sph_parts *pk = &sv->sys.part[is_seg ? SPH_KIND_SEGMENT : SPH_KIND_VERTEX];
    const size_t i = pt->index[k];
    const double x[3] = {pk->x[0][i], pk->x[1][i], pk->x[2][i]};
    double p, u[3], alpha, ytop;
    naive_interior(sv, x, &p, u, &alpha, &ytop);
    /* the wet fraction: everything without gravity; with gravity (along −y here) the part below
     * the local free surface, Δr/2 above the highest fluid particle within 2h */
    double wet = alpha > 0.0;
    if (alpha > 0.0 && sv->cfg.gravity[1] != 0.0) {
      const double level = ytop + 0.5 * sv->sys.dr;
      const struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
      if (is_seg) {
        const double y0 = v->x[1][pk->vertex[0][i]], y1 = v->x[1][pk->vertex[1][i]];
        const double lo = fmin(y0, y1), hi = fmax(y0, y1);
        wet = hi - lo < 1e-12 ? level >= lo : fmin(fmax((level - lo) / (hi - lo), 0.0), 1.0);
      } else {
        wet = x[1] <= level;
      }
    }
    assert_abs(pt->wet[k], wet, 1e-12);
    if (pt->slot[k] == (size_t)-1) {
      assert_true(wet == 0.0);
      continue;
    }
    *(is_seg ? nseg_wet : nvert_wet) += 1;
    assert_rel(pt->alpha[k], alpha, 1e-12);
    assert_rel(pt->p_int[k], p, 1e-12);
    for (int c = 0; c < 2; c++) assert_abs(pt->u_int[k][c], u[c], 1e-12);
    const struct rmn_boundary_input *in = &pt->in[pt->slot[k]];
    struct rmn_boundary_result r;
    assert_int_equal(rmn_boundary_solve(&sv->eos, &prm, ws, 2, in, &r), RMN_SUCCESS);
    assert_true(r.p == pk->p[i] && r.rho == pk->rho[i]);
    assert_true(r.u[0] == pk->v[0][i] && r.u[1] == pk->v[1][i]);
    /* the same from the naive state and the imposed value at the point */
    struct rmn_boundary_input in2 = *in;
    in2.rho = rmn_eos_density(&sv->eos, p);
    for (int c = 0; c < 3; c++) in2.u[c] = u[c];
    struct rmn_boundary_result r2;
    assert_int_equal(rmn_boundary_solve(&sv->eos, &prm, ws, 2, &in2, &r2), RMN_SUCCESS);
    assert_rel(pk->p[i], r2.p, 1e-12);
    assert_rel(pk->rho[i], r2.rho, 1e-13);
    for (int c = 0; c < 2; c++) assert_abs(pk->v[c][i], r2.u[c], 1e-12);
    assert_true(r.wave == r2.wave || fabs(r.rho - in->rho) < 1e-9 * in->rho);
  }
  rmn_workspace_free(ws);
}

static void test_solve_direct(void **state) {
  (void)state;
  sabre_fp_traps_on();
  /* imposed velocity: an inflow (shocks) then an outflow (expansions) */
  const char *cases[] = {"impose: velocity, normal_velocity: 0.05, tangential_velocity: [0, 0.02]",
                         "impose: velocity, velocity: ['0.04', '-0.1*y']",
                         "impose: pressure, pressure: '1000 + 200*t - 500*y'",
                         "impose: pressure, hydrostatic: {depth: measured}"};
  for (int i = 0; i < 4; i++) {
    struct sph_solver *sv = box_solver(cases[i]);
    stir(sv, 0.05, 2e-4);
    sv->time = 0.3;
    sph_solver_evaluate(sv);
    assert_int_equal(sv->open->fail, 0);
    size_t ns, nv;
    check_points(sv, &ns, &nv);
    print_message(
        "%s: %zu wet segments, %zu wet vertices; waves %ld contact %ld expansion %ld "
        "shock, %ld dry\n",
        cases[i], ns, nv, sv->open->stats[0].nwave[0], sv->open->stats[0].nwave[1],
        sv->open->stats[0].nwave[2], sv->open->stats[0].ndry);
    assert_true(ns >= 9 && nv >= 9);
    /* the stats are the measure-weighted means */
    const struct sph_open_points *pt = &sv->open->pts[0];
    double m = 0.0, sp = 0.0;
    for (size_t k = 0; k < pt->nseg; k++)
      if (pt->slot[k] != (size_t)-1) { /* over the wet part of each segment */
        m += pt->measure[k] * pt->wet[k];
        sp += pt->measure[k] * pt->wet[k] * sv->sys.part[SPH_KIND_SEGMENT].p[pt->index[k]];
      }
    assert_rel(sv->open->stats[0].p, sp / m, 1e-14);
    assert_true(sv->open->stats[0].time == 0.3);
    /* the predictor evaluates the open boundaries at t + dt/2 */
    char msg[1024];
    assert_int_equal(sph_solver_step(sv, INFINITY, msg, sizeof msg), 0);
    assert_true(sv->open->stats[0].time == 0.3 + 0.5 * sv->dt);
    fixture_solver_destroy(sv);
  }
}

/* An absorbing hydrostatic outlet: its level is the boundary state of the shallow-water Riemann
 * invariants, √(g d_b) = (u_out − U + 2√(g d_int) + 2√(g D))/4, with d_int the highest fluid
 * particle within 2h of its segments + Δr/2, u_out the measure-weighted mean Shepard outflow
 * velocity of the segments that see fluid (naive sums, 1e-12) and U the group's current; the
 * imposed pressure is the hydrostatic one below it. Still water at the lattice's level D keeps the
 * level D, and so does a uniform outflow at U under the level D with `current: U`. */
static void test_absorbing_level(void **state) {
  (void)state;
  sabre_fp_traps_on();
  const double g = 9.81, depth = 0.19, current = 0.12;
  struct sph_solver *sv =
      box_solver("impose: pressure, hydrostatic: {depth: 0.19, absorbing: true, current: 0.12}");
  stir(sv, 0.05, 2e-4);
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < f->n; a++) f->v[0][a] += 0.3; /* towards the outlet */
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
  assert_int_equal(sv->open->fail, 0);
  const struct sph_open_points *pt = &sv->open->pts[0];
  const struct sph_parts *sg = &sv->sys.part[SPH_KIND_SEGMENT];
  double top = -INFINITY, su = 0.0, sm = 0.0;
  for (size_t k = 0; k < pt->nseg; k++) {
    const size_t i = pt->index[k];
    const double x[3] = {sg->x[0][i], sg->x[1][i], sg->x[2][i]};
    double p, u[3], alpha, ytop;
    naive_interior(sv, x, &p, u, &alpha, &ytop);
    if (!(alpha > 0.0)) continue;
    top = fmax(top, ytop);
    su -= pt->measure[k] * (u[0] * pt->normal[k][0] + u[1] * pt->normal[k][1]);
    sm += pt->measure[k];
  }
  const double d_int = top + 0.5 * sv->sys.dr, u_out = su / sm;
  const double c = 0.25 * (u_out - current + 2.0 * sqrt(g * d_int) + 2.0 * sqrt(g * depth));
  const double level = c * c / g;
  print_message(
      "absorbing outlet: d_int %.6g m, u_out %.4g m/s, D %.3g m, U %.3g m/s: level %.6g m\n", d_int,
      u_out, depth, current, level);
  assert_true(u_out > 0.25 && level > depth);
  assert_rel(sv->open->stats[0].level, level, 1e-12);
  size_t checked = 0;
  for (size_t k = 0; k < pt->nseg; k++) {
    const size_t i = pt->index[k];
    const double dz = level - sg->x[1][i];
    if (pt->slot[k] == (size_t)-1 || !(dz > 0.0)) continue;
    assert_rel(pt->value[k].p, sph_hydrostatic_pressure(&sv->eos, g, dz), 1e-12);
    checked++;
  }
  assert_true(checked >= 5);
  fixture_solver_destroy(sv);
  /* still water whose lattice holds the level D = 0.2125 m (rows to 0.2 m, + Δr/2) */
  sv = box_solver("impose: pressure, hydrostatic: {depth: 0.2125, absorbing: true}");
  sph_solver_evaluate(sv);
  assert_rel(sv->open->stats[0].level, 0.2125, 1e-14);
  fixture_solver_destroy(sv);
  /* a uniform outflow at U = 0.3 m/s under that level, with current: 0.3 */
  sv = box_solver("impose: pressure, hydrostatic: {depth: 0.2125, absorbing: true, current: 0.3}");
  f = &sv->sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < f->n; a++) f->v[0][a] = 0.3;
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
  assert_rel(sv->open->stats[0].level, 0.2125, 1e-14);
  fixture_solver_destroy(sv);
}

/* 3D: a box with its x+ face open at the hydrostatic pressure and the x- face at an imposed
 * velocity vector; every point's values are the direct solve of its input, and the open vertices
 * carry the imposed pressure at their own position with the face's normal. */
static void test_solve_3d(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_solver *sv = fixture_solver_from_case(
      "geometry:\n"
      "  dimension: 3\n"
      "  dr: 0.1\n"
      "  h_over_dr: 1.3\n"
      "  first_row: 1\n"
      "  walls: [{type: box, lo: [0, 0, 0], hi: [0.6, 0.4, 0.5], open: [x-, x+]}]\n"
      "  fluid: [{type: box, lo: [0, 0, 0], hi: [0.6, 0.4, 0.3]}]\n"
      "fluid: {rho0: 1000, c0: 15}\n"
      "gravity: [0, 0, -9.81]\n"
      "initial: {pressure: hydrostatic}\n"
      "time: {end: 1}\n"
      "open_boundaries:\n"
      "  - {name: out, wall: 0, faces: [x+], impose: pressure, hydrostatic: {depth: 0.35}}\n"
      "  - {name: in, wall: 0, faces: [x-], impose: velocity, velocity: [0.05, 0.01, '0.1*z']}\n");
  stir(sv, 0.03, 1e-4);
  sph_solver_evaluate(sv);
  assert_int_equal(sv->open->fail, 0);
  struct rmn_params prm;
  rmn_params_default(&prm);
  struct rmn_workspace *ws = rmn_workspace_alloc();
  size_t wet[2] = {0, 0};
  for (int g = 0; g < 2; g++) {
    const struct sph_open_points *pt = &sv->open->pts[g];
    for (size_t k = 0; k < pt->npoints; k++) {
      if (pt->slot[k] == (size_t)-1) continue;
      const int is_seg = k < pt->nseg;
      const struct sph_parts *pk = &sv->sys.part[is_seg ? SPH_KIND_SEGMENT : SPH_KIND_VERTEX];
      const size_t i = pt->index[k];
      struct rmn_boundary_result r;
      assert_int_equal(rmn_boundary_solve(&sv->eos, &prm, ws, 3, &pt->in[pt->slot[k]], &r), 0);
      assert_true(r.p == pk->p[i] && r.rho == pk->rho[i]);
      for (int c = 0; c < 3; c++) assert_true(r.u[c] == pk->v[c][i]);
      assert_abs(pt->normal[k][0], g == 0 ? -1.0 : 1.0, 1e-15);
      if (g == 0 && !is_seg) { /* zero above the level */
        const double d = 0.35 - pk->x[2][i];
        assert_rel(pk->p[i], d > 0.0 ? sph_hydrostatic_pressure(&sv->eos, 9.81, d) : 0.0, 1e-14);
      }
      if (g == 1 && r.flow == RMN_FLOW_INFLOW) { /* the imposed vector's tangential part */
        assert_rel(r.u[1], 0.01, 1e-13);
        assert_rel(r.u[2], 0.1 * pk->x[2][i], 1e-13);
      }
      wet[g]++;
    }
  }
  print_message("3D: %zu and %zu wet points\n", wet[0], wet[1]);
  assert_true(wet[0] >= 20 && wet[1] >= 20);
  rmn_workspace_free(ws);
  fixture_solver_destroy(sv);
}

/* The exact shock branch and the acoustic relation p2 − p_int = ρ c (u2 − u_int) agree to second
 * order in the jump; the linearised option (p2 − p_int = ρ u_int (u_int − u2), a shock at rest)
 * does not: it differs at first order. A strong compression is a shock that satisfies the
 * moving-shock Rankine–Hugoniot relations and the Lax condition. */
static void test_linearised_exact(void **state) {
  (void)state;
  struct rmn_eos eos;
  assert_int_equal(rmn_eos_init(&eos, 1000.0, 20.0, 7.0), RMN_SUCCESS);
  struct rmn_params ex, li;
  rmn_params_default(&ex);
  rmn_params_default(&li);
  li.shock = RMN_SHOCK_LINEARISED;
  struct rmn_workspace *ws = rmn_workspace_alloc();
  const double rho = 1000.7, un = -0.31, c = rmn_eos_sound_speed(&eos, rho);
  double e_ac[4], e_li[4];
  for (int i = 0; i < 4; i++) {
    const double du = 0.02 / (double)(1 << i); /* a compression: u2 > u_int */
    struct rmn_normal_state se, sl;
    assert_int_equal(
        rmn_boundary_solve_normal(&eos, &ex, ws, rho, un, RMN_IMPOSE_VELOCITY, un + du, &se), 0);
    assert_int_equal(
        rmn_boundary_solve_normal(&eos, &li, ws, rho, un, RMN_IMPOSE_VELOCITY, un + du, &sl), 0);
    assert_int_equal(se.wave, RMN_WAVE_SHOCK);
    assert_int_equal(sl.wave, RMN_WAVE_SHOCK);
    const double dp = se.p - rmn_eos_pressure(&eos, rho);
    e_ac[i] = fabs(dp - rho * c * du) / (rho * c * du);
    e_li[i] = fabs(sl.p - se.p) / fabs(dp);
  }
  for (int i = 1; i < 4; i++) {
    print_message("du = %g: exact vs acoustic %.3e (ratio %.3f), linearised vs exact %.3e\n",
                  0.02 / (1 << i), e_ac[i], e_ac[i - 1] / e_ac[i], e_li[i]);
    assert_rel(e_ac[i - 1] / e_ac[i], 2.0, 0.02); /* relative error O(du): absolute O(du²) */
    assert_true(e_li[i] > 0.5);                   /* O(1) relative: first order in du */
  }
  /* strong compression: imposed pressure 40 % of ρ0 c0² above */
  const double p2 = 0.4 * 1000.0 * 400.0;
  struct rmn_normal_state s;
  assert_int_equal(rmn_boundary_solve_normal(&eos, &ex, ws, rho, un, RMN_IMPOSE_PRESSURE, p2, &s),
                   0);
  assert_int_equal(s.wave, RMN_WAVE_SHOCK);
  double res[2];
  rmn_shock_residuals(&eos, rho, un, s.rho, s.un, s.shock_speed, res);
  assert_abs(res[0], 0.0, 1e-9 * rho * c);
  assert_abs(res[1], 0.0, 1e-9 * p2);
  assert_true(un + c < s.shock_speed && s.shock_speed < s.un + rmn_eos_sound_speed(&eos, s.rho));
  assert_rel(s.un, rmn_shock_velocity_closed_form(&eos, rho, un, s.rho), 1e-12);
  rmn_workspace_free(ws);
  /* and through the solver: `shock: linearised` reaches the library's linearised branch */
  struct sph_solver *sv = box_solver("impose: velocity, shock: linearised, normal_velocity: 0.05");
  stir(sv, 0.05, 2e-4);
  sph_solver_evaluate(sv);
  assert_int_equal(sv->open->fail, 0);
  size_t ns, nv;
  check_points(sv, &ns, &nv);
  assert_true(sv->open->stats[0].nwave[RMN_WAVE_SHOCK] > 0);
  fixture_solver_destroy(sv);
}

/* The vertex rule: every open vertex, corners included, is solved as a point of the open boundary
 * (its own Shepard state, the normal of its open segments, the imposed value at the vertex); a
 * wall vertex keeps its wall value. */
static void test_vertex_rule(void **state) {
  (void)state;
  struct sph_solver *sv = box_solver("impose: pressure, pressure: '2000 - 9810*y + 300*t'");
  stir(sv, 0.05, 2e-4);
  sv->time = 0.1;
  sph_solver_evaluate(sv);
  const struct sph_open_points *pt = &sv->open->pts[0];
  const struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  size_t corner = (size_t)-1, wet = 0;
  for (size_t k = pt->nseg; k < pt->npoints; k++) {
    const size_t iv = pt->index[k];
    /* the normal of the open face, also at the corner (whose own normal is the wall's mean) */
    assert_abs(pt->normal[k][0], -1.0, 1e-15);
    assert_abs(pt->normal[k][1], 0.0, 1e-15);
    if (v->flags[iv] & SPH_FLAG_CORNER) corner = iv;
    if (pt->slot[k] == (size_t)-1) continue;
    wet++;
    assert_rel(v->p[iv], 2000.0 - 9810.0 * v->x[1][iv] + 300.0 * 0.1, 1e-14);
    assert_rel(v->rho[iv], rmn_eos_density(&sv->eos, v->p[iv]), 1e-15);
  }
  assert_true(wet >= 9);
  /* the bottom corner (0.5, 0): open, solved, with the imposed value at the corner itself */
  assert_true(corner != (size_t)-1);
  size_t bottom = (size_t)-1;
  for (size_t iv = 0; iv < v->n; iv++)
    if (v->x[0][iv] == 0.5 && v->x[1][iv] == 0.0) bottom = iv;
  assert_true(bottom != (size_t)-1 && (v->flags[bottom] & SPH_FLAG_CORNER));
  assert_int_equal(sv->open->vert_group[bottom], 0);
  assert_rel(v->p[bottom], 2030.0, 1e-14);
  size_t ns, nv;
  check_points(sv, &ns, &nv); /* each vertex value is the direct solve of its own state */
  /* the floor vertex next to the corner is a wall vertex: its Shepard wall value */
  for (size_t iv = 0; iv < v->n; iv++)
    if (fabs(v->x[0][iv] - 0.475) < 1e-12 && v->x[1][iv] == 0.0) {
      assert_int_equal(sv->open->vert_group[iv], -1);
      assert_true(v->v[0][iv] == 0.0 && v->v[1][iv] == 0.0);
    }
  fixture_solver_destroy(sv);
}

/* A failed solve stops the step with a message naming the group, the segment (element,
 * position), the time and both states. */
static void test_failed_solve(void **state) {
  (void)state;
  struct sph_solver *sv = box_solver("impose: pressure, pressure: '-1e6 + t'");
  char msg[2048];
  assert_int_equal(sph_solver_step(sv, INFINITY, msg, sizeof msg), -1);
  print_message("%s\n", msg);
  const char *want[] = {"step 1, t = 0 s",
                        "open boundary 'right'",
                        "segment id",
                        "element 2 of geometry.walls[0]",
                        "at (0.5, ",
                        "normal (-1, 0, 0)",
                        "RMN_ECAVITATION",
                        "interior state rho = ",
                        "imposed pressure -1000000 Pa"};
  for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
    if (!strstr(msg, want[i])) fail_msg("'%s' lacks '%s'", msg, want[i]);
  fixture_solver_destroy(sv);
  /* an imposed speed that the boundary problem cannot take (supersonic) */
  sv = box_solver("impose: velocity, normal_velocity: '-12*t'");
  sv->time = 0.5;
  assert_int_equal(sph_solver_step(sv, INFINITY, msg, sizeof msg), -1);
  print_message("%s\n", msg);
  assert_non_null(strstr(msg, "step 1, t = 0.5 s"));
  assert_non_null(strstr(msg, "RMN_ESUPERSONIC"));
  assert_non_null(strstr(msg, "imposed normal velocity -6 m/s"));
  fixture_solver_destroy(sv);
}

/* Still water with one open face at the hydrostatic pressure behaves like the wall it still is.
 * At t = 0 the imposed pressure equals the interior (Shepard) pressure on every wet point of the
 * face (the generator's profile is the initial state's). Then the run with the open face and the
 * same run with the face a wall move alike: the same largest speed (the slow side-wall motion of
 * docs/sph-solver.md §7.1 at this resolution), positions within a fraction of Δr (the open face
 * keeps the imposed pressure while the bulk pressure drifts by about 2 % of ρ0 g H, which the wall
 * vertices follow). */
static void test_still_water(void **state) {
  (void)state;
  sabre_fp_traps_on();
  static const char still[] =
      "geometry:\n"
      "  dimension: 2\n"
      "  dr: 0.025\n"
      "  first_row: 1\n"
      "  walls: [{type: box, lo: [0, 0], hi: [0.4, 0.4]%s}]\n"
      "  fluid: [{type: box, lo: [0, 0], hi: [0.4, 0.2]}]\n"
      "fluid: {rho0: 1000, c0: 20}\n"
      "gravity: [0, -9.81]\n"
      "initial: {pressure: hydrostatic}\n"
      "numerics: {vertex_volume: geometric}\n"
      "repack: {steps: 300}\n"
      "time: {end: 1}\n%s";
  char text[2][4096];
  snprintf(text[0], sizeof text[0], still, ", open: [x+]",
           "open_boundaries: [{name: right, wall: 0, impose: pressure,\n"
           "                   hydrostatic: {depth: 0.2125}}]\n");
  snprintf(text[1], sizeof text[1], still, "", "");
  struct sph_solver *sv[2] = {fixture_solver_from_case(text[0]), fixture_solver_from_case(text[1])};
  const double rho_g_h = 1000.0 * 9.81 * 0.2125, sqrt_gh = sqrt(9.81 * 0.2125);
  /* t = 0: imposed = interior on the wet points */
  sph_solver_evaluate(sv[0]);
  const struct sph_open_points *pt = &sv[0]->open->pts[0];
  double dp0 = 0.0, du0 = 0.0;
  size_t wet = 0;
  for (size_t k = 0; k < pt->npoints; k++) {
    if (pt->slot[k] == (size_t)-1) continue;
    wet++;
    dp0 = fmax(dp0, fabs(pt->value[k].p - pt->p_int[k]));
    du0 = fmax(du0, fabs(pt->out[pt->slot[k]].un));
  }
  /* wet: the points below the free surface (0.2125 m after the repacking), the segment that
   * straddles it, none Δr above it */
  const struct sph_parts *vx = &sv[0]->sys.part[SPH_KIND_VERTEX];
  for (size_t k = 0; k < pt->npoints; k++) {
    const size_t i = pt->index[k];
    const double y = k < pt->nseg ? fmin(vx->x[1][sv[0]->sys.part[SPH_KIND_SEGMENT].vertex[0][i]],
                                         vx->x[1][sv[0]->sys.part[SPH_KIND_SEGMENT].vertex[1][i]])
                                  : vx->x[1][i];
    if (y < 0.2125 - 0.1 * 0.025) assert_true(pt->slot[k] != (size_t)-1);
    if (y > 0.2125 + 0.025) assert_true(pt->slot[k] == (size_t)-1);
  }
  print_message("%zu wet points at t = 0\n", wet);
  assert_true(wet >= 17);
  char msg[1024];
  const double t_end = 0.1;
  double umax[2] = {0.0, 0.0};
  for (int k = 0; k < 2; k++) {
    while (sv[k]->time < t_end - 1e-12) {
      if (sph_solver_step(sv[k], t_end - sv[k]->time, msg, sizeof msg) != 0) fail_msg("%s", msg);
      const struct sph_parts *f = &sv[k]->sys.part[SPH_KIND_FLUID];
      for (size_t a = 0; a < f->n; a++) umax[k] = fmax(umax[k], hypot(f->v[0][a], f->v[1][a]));
    }
  }
  const struct sph_parts *f0 = &sv[0]->sys.part[SPH_KIND_FLUID],
                         *f1 = &sv[1]->sys.part[SPH_KIND_FLUID];
  assert_int_equal(f0->n, f1->n);
  double dx = 0.0;
  for (size_t a = 0; a < f0->n; a++)
    dx = fmax(dx, hypot(f0->x[0][a] - f1->x[0][a], f0->x[1][a] - f1->x[1][a]));
  const struct sph_open_stats *st = &sv[0]->open->stats[0];
  print_message(
      "t = 0: %zu wet points, max |imposed - interior p| %.3g Pa (%.2g rho0 g H), max |u_n| "
      "%.3g m/s; to t = %g s: max|u| open %.4g m/s (%.3g %% sqrt(gH)), wall %.4g m/s; largest "
      "position difference %.3g dr; open face at the end: mean p %.6g Pa (interior %.6g Pa), "
      "mean u_n %.3g m/s (interior %.3g m/s), waves %ld/%ld/%ld, dry %ld\n",
      wet, dp0, dp0 / rho_g_h, du0, t_end, umax[0], 100.0 * umax[0] / sqrt_gh, umax[1], dx / 0.025,
      st->p, st->p_int, st->un, st->un_int, st->nwave[0], st->nwave[1], st->nwave[2], st->ndry);
  assert_true(dp0 <= 1e-4 * rho_g_h);
  assert_true(du0 <= 1e-5 * sqrt_gh);
  assert_true(umax[0] <= 1.05 * umax[1]);
  assert_true(dx <= 0.12 * 0.025); /* measured 0.089 dr */
  fixture_solver_destroy(sv[0]);
  fixture_solver_destroy(sv[1]);
}

/* Open solids of an STL wall: a 3D box tank written as an ASCII STL with the solids 'inlet'
 * (x = 0), 'outlet' (x = L) and 'walls', `open_solids: [inlet, outlet]` in the geometry and groups
 * selecting them by `solids`, runs the through-flow as the same box given as a `box` wall with
 * `open: [x-, x+]` and `faces`; errors name the key. */
static void stl_quad(char *out, size_t len, const double q[4][3]) {
  const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (int t = 0; t < 2; t++) {
    size_t n = strlen(out);
    snprintf(out + n, len - n, "facet normal 0 0 0\nouter loop\n");
    for (int k = 0; k < 3; k++) {
      n = strlen(out);
      const double *x = q[tri[t][k]];
      snprintf(out + n, len - n, "vertex %.17g %.17g %.17g\n", x[0], x[1], x[2]);
    }
    n = strlen(out);
    snprintf(out + n, len - n, "endloop\nendfacet\n");
  }
}

static double mean_u(const struct sph_solver *sv) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  double u = 0.0;
  for (size_t a = 0; a < f->n; a++) u += f->v[0][a];
  return u / (double)f->n;
}

static void test_stl_solids(void **state) {
  (void)state;
  sabre_fp_traps_on();
  const double L = 0.2, W = 0.125, H = 0.125;
  /* faces with their corners counter-clockwise seen from outside the tank (outward normals) */
  const double xm[4][3] = {{0, 0, 0}, {0, 0, H}, {0, W, H}, {0, W, 0}};
  const double xp[4][3] = {{L, 0, 0}, {L, W, 0}, {L, W, H}, {L, 0, H}};
  const double walls[4][4][3] = {{{0, 0, 0}, {L, 0, 0}, {L, 0, H}, {0, 0, H}},
                                 {{0, W, 0}, {0, W, H}, {L, W, H}, {L, W, 0}},
                                 {{0, 0, 0}, {0, W, 0}, {L, W, 0}, {L, 0, 0}},
                                 {{0, 0, H}, {L, 0, H}, {L, W, H}, {0, W, H}}};
  static char stl[16384];
  snprintf(stl, sizeof stl, "solid walls\n");
  for (int k = 0; k < 4; k++) stl_quad(stl, sizeof stl, walls[k]);
  snprintf(stl + strlen(stl), sizeof stl - strlen(stl), "endsolid walls\nsolid inlet\n");
  stl_quad(stl, sizeof stl, xm);
  snprintf(stl + strlen(stl), sizeof stl - strlen(stl), "endsolid inlet\nsolid outlet\n");
  stl_quad(stl, sizeof stl, xp);
  snprintf(stl + strlen(stl), sizeof stl - strlen(stl), "endsolid outlet\n");
  const char *path = write_file("tank.stl", stl);
  static const char tmpl[] =
      "geometry:\n"
      "  dimension: 3\n"
      "  dr: 0.025\n"
      "  first_row: 1\n"
      "  walls: [%s]\n"
      "  fluid: [{type: box, lo: [0, 0, 0], hi: [0.2, 0.125, 0.125]}]\n"
      "fluid: {rho0: 1000, c0: 20}\n"
      "initial: {velocity: [0.2, 0, 0]}\n"
      "time: {end: 1}\n"
      "open_boundaries:\n"
      "  - {name: in, wall: 0, %s, impose: velocity, normal_velocity: 0.2}\n"
      "  - {name: out, wall: 0, %s, impose: pressure, pressure: 0}\n";
  char wall_stl[600], text[2][4096];
  snprintf(wall_stl, sizeof wall_stl, "{type: stl, file: '%s', open_solids: [inlet, outlet]}",
           path);
  snprintf(text[0], sizeof text[0], tmpl, wall_stl, "solids: [inlet]", "solids: [outlet]");
  snprintf(text[1], sizeof text[1], tmpl,
           "{type: box, lo: [0, 0, 0], hi: [0.2, 0.125, 0.125], open: [x-, x+]}", "faces: [x-]",
           "faces: [x+]");
  struct sph_solver *sv[2] = {fixture_solver_from_case(text[0]), fixture_solver_from_case(text[1])};
  size_t nopen[2][2] = {{0, 0}, {0, 0}};
  for (int k = 0; k < 2; k++) {
    const struct sph_parts *sg = &sv[k]->sys.part[SPH_KIND_SEGMENT];
    for (size_t j = 0; j < sg->n; j++)
      if (sv[k]->open->seg_group[j] >= 0) {
        nopen[k][sv[k]->open->seg_group[j]]++;
        assert_true(sg->flags[j] & SPH_FLAG_OPEN);
        /* the inlet's normal is +x, the outlet's −x */
        assert_true(fabs(sg->normal[0][j] - (sv[k]->open->seg_group[j] == 0 ? 1.0 : -1.0)) < 1e-12);
      }
  }
  assert_true(nopen[0][0] > 0 && nopen[0][1] > 0 && nopen[1][0] > 0 && nopen[1][1] > 0);
  char msg[1024];
  const double t_end = 0.25;
  for (int k = 0; k < 2; k++)
    while (sv[k]->time < t_end - 1e-12)
      if (sph_solver_step(sv[k], t_end - sv[k]->time, msg, sizeof msg) != 0) fail_msg("%s", msg);
  const double u[2] = {mean_u(sv[0]), mean_u(sv[1])};
  print_message(
      "STL tank: %zu inlet and %zu outlet segments (box: %zu, %zu); at t = %g s mean u %.5f m/s "
      "(box %.5f), created %ld/%ld, deleted %ld/%ld\n",
      nopen[0][0], nopen[0][1], nopen[1][0], nopen[1][1], t_end, u[0], u[1],
      sv[0]->open->created[0], sv[1]->open->created[0], sv[0]->open->deleted[1],
      sv[1]->open->deleted[1]);
  assert_true(sv[0]->open->created[0] > 0 && sv[0]->open->deleted[1] > 0);
  assert_true(fabs(u[0] - 0.2) <= 0.02 * 0.2 && fabs(u[0] - u[1]) <= 0.02 * 0.2);
  fixture_solver_destroy(sv[0]);
  fixture_solver_destroy(sv[1]);
  /* a group naming a solid the file does not have (the key, the wall and the file's solids), and
   * one selecting a solid that is not open */
  /* the same tank with its walls written as two solids that share the name 'walls' */
  static char stl2[16384];
  snprintf(stl2, sizeof stl2, "solid walls\n");
  for (int k = 0; k < 4; k++) {
    if (k == 2)
      snprintf(stl2 + strlen(stl2), sizeof stl2 - strlen(stl2), "endsolid\nsolid walls\n");
    stl_quad(stl2, sizeof stl2, walls[k]);
  }
  snprintf(stl2 + strlen(stl2), sizeof stl2 - strlen(stl2), "endsolid\n%s",
           strstr(stl, "solid inlet"));
  char wall_stl2[600];
  snprintf(wall_stl2, sizeof wall_stl2, "{type: stl, file: '%s', open_solids: [inlet, outlet]}",
           write_file("tank2.stl", stl2));
  const char *bad[3][4] = {{wall_stl, "solids: [nozzle]", "open_boundaries[1].solids[0]",
                            "geometry.walls[0] has no solid named 'nozzle' (its solids: 'walls', "
                            "'inlet', 'outlet')"},
                           {wall_stl, "solids: [walls]", "open_boundaries[1].solids",
                            "a selected solid of geometry.walls[0] is a wall, not open (list it "
                            "in the wall's 'open_solids')"},
                           {wall_stl2, "solids: [walls]", "open_boundaries[1].solids[0]",
                            "2 solids of geometry.walls[0] are called 'walls': selecting by name "
                            "needs unique names"}};
  for (int k = 0; k < 3; k++) {
    snprintf(text[0], sizeof text[0], tmpl, bad[k][0], "solids: [inlet]", bad[k][1]);
    char err[512];
    struct cmn_case *c = cmn_case_parse(text[0], "case.yaml", err, sizeof err);
    assert_non_null(c);
    struct sph_geometry g;
    sph_geometry_read(&g, c);
    cmn_case_set_fatal(c, 0);
    struct sph_config *cfg = calloc(1, sizeof *cfg);
    assert_int_equal(sph_config_read(cfg, c, 3), 0);
    assert_int_equal(sph_open_check_mesh(&cfg->open, c, &g.walls), -1);
    const char *e = cmn_case_error(c);
    print_message("%s\n", e);
    assert_non_null(strstr(e, bad[k][2]));
    assert_non_null(strstr(e, bad[k][3]));
    free(cfg);
    sph_geometry_free(&g);
    cmn_case_free(c);
  }
}

/* `sabre-sph run` with a bad open_boundaries section: exit status 2, the key in the message, and
 * no run directory written. */
static char run_case[512], run_out[512];
static void run_body(void) {
  char *argv[] = {"run", run_case, "--output", run_out, NULL};
  exit(sph_cmd_run(4, argv));
}

static void test_run_errors(void **state) {
  (void)state;
  const char *bad[][2] = {
      {"open_boundaries: [{name: o, wall: 0, edges: [2, 3], impose: pressure, pressure: 0}]\n",
       "open_boundaries[0].edges[1]: element 3 of geometry.walls[0] is a wall"},
      {"", "geometry.walls[0]: its element 2 is open but no open_boundaries group"},
      {"open_boundaries: [{name: o, wall: 0, impose: pressure, table: back.csv}]\n",
       "open_boundaries[0].table: "}};
  write_file("back.csv", "t,p\n0,0\n1,5\n0.5,2\n");
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    char text[4096];
    snprintf(text, sizeof text, "%s%s", box_case, bad[i][0]);
    snprintf(run_case, sizeof run_case, "%s", write_file("bad.yaml", text));
    snprintf(run_out, sizeof run_out, "%s/out%zu", tmpdir, i);
    char err[4096];
    assert_int_equal(sabre_run_child(run_body, err, sizeof err), CMN_EXIT_INPUT);
    print_message("%s", err);
    if (!strstr(err, "bad.yaml:") || !strstr(err, bad[i][1]))
      fail_msg("'%s' lacks '%s'", err, bad[i][1]);
    assert_int_equal(access(run_out, F_OK), -1); /* nothing written */
  }
}

int main(void) {
  cmn_set_program_name("test_open");
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_parse),
      cmocka_unit_test(test_parse_errors),
      cmocka_unit_test(test_check_mesh),
      cmocka_unit_test(test_values_2d),
      cmocka_unit_test(test_values_3d),
      cmocka_unit_test(test_solve_direct),
      cmocka_unit_test(test_absorbing_level),
      cmocka_unit_test(test_solve_3d),
      cmocka_unit_test(test_linearised_exact),
      cmocka_unit_test(test_vertex_rule),
      cmocka_unit_test(test_failed_solve),
      cmocka_unit_test(test_still_water),
      cmocka_unit_test(test_run_errors),
      cmocka_unit_test(test_stl_solids),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
