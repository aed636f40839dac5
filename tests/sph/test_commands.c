/* The sabre-sph commands `gamma` and `mesh`, run in a child process with stdout and stderr
 * captured: the public output format of `gamma`, its values on known configurations (far field,
 * wall, corner; a box given as --box and as an STL file; an STL obstacle), `mesh` output files,
 * and bad options (exit code 2 with a message). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph.h"
#include "testutil.h"
/* testutil.h first */
#include "sph_testfiles.h"

static char out[1 << 16];

struct invocation {
  int (*cmd)(int, char **);
  const char *const *argv;
};

static int invoke(void *arg) {
  const struct invocation *inv = arg;
  int argc = 0;
  while (inv->argv[argc]) argc++;
  return inv->cmd(argc, (char **)inv->argv);
}

/* Run a command (NULL-terminated argv, argv[0] its name); stdout+stderr into `out`. */
static int run(int (*cmd)(int, char **), const char *const *argv) {
  struct invocation inv = {cmd, argv};
  return test_capture(invoke, &inv, out, sizeof out);
}

/* Parse line `k` (0-based) of `out` as {"at": [...], "gamma": g, "grad_gamma": [...]}. */
static void parse_line(int k, int dim, double *gamma, double *grad) {
  const char *line = out;
  for (int i = 0; i < k; i++) {
    line = strchr(line, '\n');
    assert_non_null(line);
    line++;
  }
  const char *g = strstr(line, "\"gamma\": ");
  const char *gg = strstr(line, "\"grad_gamma\": [");
  assert_non_null(g);
  assert_non_null(gg);
  assert_true(strncmp(line, "{\"at\": [", 8) == 0);
  *gamma = strtod(g + 9, NULL);
  const char *p = gg + 15;
  for (int a = 0; a < dim; a++) {
    char *end;
    grad[a] = strtod(p, &end);
    assert_true(end != p);
    p = end + (a + 1 < dim ? 2 : 0);
  }
  assert_true(strncmp(p, "]}", 2) == 0);
}

static int count_lines(void) {
  int n = 0;
  for (const char *p = out; *p; p++) n += *p == '\n';
  return n;
}

static void test_gamma_2d(void **state) {
  (void)state;
  const char *argv[] = {"gamma",     "--dim",     "2",
                        "--dr",      "0.05",      "--h-over-dr",
                        "2",         "--box",     "-0.5,0.25:1.5,1.75",
                        "--at",      "0.5,1",     "--at",
                        "0.73,0.25", "--at",      "-0.5,1.75",
                        "--at",      "0.41,0.33", NULL};
  assert_int_equal(run(sph_cmd_gamma, argv), 0);
  assert_int_equal(count_lines(), 4);
  double g, grad[2];
  parse_line(0, 2, &g, grad); /* far from the walls */
  assert_rel(g, 1.0, 1e-14);
  assert_abs(grad[0], 0, 1e-14);
  parse_line(1, 2, &g, grad); /* on the floor: 1/2, gradient along +y */
  assert_rel(g, 0.5, 1e-12);
  assert_abs(grad[0], 0, 1e-10);
  assert_true(grad[1] > 0);
  parse_line(2, 2, &g, grad); /* top-left corner: 1/4, gradient along (+x, -y) */
  assert_rel(g, 0.25, 1e-12);
  assert_rel(grad[0], -grad[1], 1e-12);
  assert_true(grad[0] > 0);
  parse_line(3, 2, &g, grad); /* 0.08 above the floor: between 1/2 and 1 */
  assert_true(g > 0.5 && g < 1.0);
}

/* The same cube given as --box and as an STL file (coarse triangles, refined by the command). */
static void test_gamma_box_vs_stl(void **state) {
  (void)state;
  struct sph_mesh m;
  sph_mesh_init(&m, 3);
  sph_mesh_box(&m, (double[]){0, 0, 0}, (double[]){1, 1, 1}, 1.0, 0, 0,
               sph_mesh_add_source(&m, "cube"));
  char stl[256];
  snprintf(stl, sizeof stl, "%s", test_path("cube.stl"));
  assert_int_equal(sph_mesh_write_stl(&m, stl, 1), 0);
  sph_mesh_free(&m);
  const char *pts[] = {"0.5,0.5,0.5", "0.31,0.47,0.06", "0.03,0.04,0.05", "1,0.5,0.5", NULL};
  double gb[4], gs[4], gradb[4][3], grads[4][3];
  for (int which = 0; which < 2; which++) {
    const char *argv[32] = {"gamma", "--dim", "3", "--dr", "0.1", "--h-over-dr", "1.3"};
    int n = 7;
    argv[n++] = which ? "--stl" : "--box";
    argv[n++] = which ? stl : "0,0,0:1,1,1";
    for (int p = 0; pts[p]; p++) {
      argv[n++] = "--at";
      argv[n++] = pts[p];
    }
    argv[n] = NULL;
    assert_int_equal(run(sph_cmd_gamma, argv), 0);
    assert_int_equal(count_lines(), 4);
    for (int p = 0; p < 4; p++)
      parse_line(p, 3, which ? &gs[p] : &gb[p], which ? grads[p] : gradb[p]);
  }
  for (int p = 0; p < 4; p++) {
    assert_abs(gs[p], gb[p], 1e-12);
    for (int a = 0; a < 3; a++) assert_abs(grads[p][a], gradb[p][a], 1e-9);
  }
  assert_rel(gb[0], 1.0, 1e-14);
  assert_rel(gb[3], 0.5, 1e-12);
}

/* A box tank with an STL cube obstacle: next to the middle of an obstacle face γ equals γ at the
 * same distance from the middle of the floor (both a plane within the support). */
static void test_gamma_obstacle(void **state) {
  (void)state;
  struct sph_mesh m;
  sph_mesh_init(&m, 3);
  sph_mesh_box(&m, (double[]){0.3, 0.3, 0.3}, (double[]){0.7, 0.7, 0.7}, 0.2, 0, 0,
               sph_mesh_add_source(&m, "obstacle"));
  char stl[256];
  snprintf(stl, sizeof stl, "%s", test_path("obstacle.stl"));
  assert_int_equal(sph_mesh_write_stl(&m, stl, 0), 0);
  sph_mesh_free(&m);
  const char *argv[] = {"gamma",
                        "--dim",
                        "3",
                        "--dr",
                        "0.05",
                        "--h-over-dr",
                        "1.3",
                        "--box",
                        "0,0,0:1,1,1",
                        "--stl",
                        stl,
                        "--at",
                        "0.5,0.5,0.037",
                        "--at",
                        "0.5,0.5,0.737",
                        "--at",
                        "0.5,0.263,0.5",
                        NULL};
  assert_int_equal(run(sph_cmd_gamma, argv), 0);
  double g0, g1, g2, grad0[3], grad1[3], grad2[3];
  parse_line(0, 3, &g0, grad0);
  parse_line(1, 3, &g1, grad1);
  parse_line(2, 3, &g2, grad2);
  assert_true(g0 < 0.99);
  assert_rel(g1, g0, 1e-12);
  assert_rel(g2, g0, 1e-12);
  assert_rel(grad1[2], grad0[2], 1e-10);  /* +z away from the obstacle's top and the floor */
  assert_rel(grad2[1], -grad0[2], 1e-10); /* -y away from the obstacle's y- face */
}

/* A point outside the walls is reported on stderr (the output line is still printed). */
static void test_gamma_outside(void **state) {
  (void)state;
  const char *argv[] = {"gamma",   "--dim", "2",       "--dr", "0.1",     "--h-over-dr",
                        "2",       "--box", "0,0:1,1", "--at", "1.5,0.5", "--at",
                        "0.5,0.5", "--at",  "1,0.3",   NULL};
  assert_int_equal(run(sph_cmd_gamma, argv), 0);
  assert_non_null(strstr(out, "warning: --at 1.5,0.5,0 lies outside the fluid, 0.5 m behind"));
  assert_null(strstr(out, "--at 0.5,0.5,0 lies"));
  assert_null(strstr(out, "--at 1,0.3,0 lies")); /* on the wall */
  assert_non_null(strstr(out, "{\"at\": [1.5, 0.5]"));
}

static void test_gamma_errors(void **state) {
  (void)state;
  static const struct {
    const char *argv[12];
    const char *want;
  } bad[] = {
      {{"gamma", "--dim", "2", "--dr", "0.1", "--h-over-dr", "2", "--box", "0,0:1,1"},
       "at least one --at"},
      {{"gamma", "--dim", "4", "--dr", "0.1"}, "--dim '4': expected 1, 2 or 3"},
      {{"gamma", "--dim", "2", "--dr", "-1"}, "--dr '-1': expected a positive number"},
      {{"gamma", "--dim", "2", "--dr", "0.1", "--h-over-dr", "2", "--box", "0,0:1", "--at",
        "0.5,0.5"},
       "--box (HI) '1': expected 2 comma-separated numbers"},
      {{"gamma", "--dim", "2", "--dr", "0.1", "--h-over-dr", "2", "--box", "1,0:0,1", "--at",
        "0.5,0.5"},
       "HI must exceed LO"},
      {{"gamma", "--dim", "2", "--dr", "0.1", "--h-over-dr", "2", "--at", "0.5,0.5"},
       "gamma needs walls"},
      {{"gamma", "--dim", "2", "--stl", "x.stl", "--dr", "0.1", "--h-over-dr", "2", "--at", "0,0"},
       "STL walls exist in 3D only"},
      {{"gamma", "--dim", "2", "--frobnicate", "1"}, "unknown option '--frobnicate'"},
      {{"gamma", "--dim"}, "--dim needs a value"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    int rc = run(sph_cmd_gamma, bad[i].argv);
    if (rc != CMN_EXIT_INPUT || !strstr(out, bad[i].want))
      print_error("case %zu: exit %d, output '%s'\n", i, rc, out);
    assert_int_equal(rc, CMN_EXIT_INPUT);
    assert_non_null(strstr(out, bad[i].want));
  }
}

static void test_mesh_command(void **state) {
  (void)state;
  const char *geometry =
      "geometry:\n  dimension: 2\n  dr: 0.1\n  walls:\n"
      "    - {type: box, lo: [0, 0], hi: [1, 0.8]}\n"
      "  fluid:\n    - {type: box, lo: [0, 0], hi: [1, 0.5]}\n";
  char case_path[256];
  snprintf(case_path, sizeof case_path, "%s", test_write("tank.yaml", geometry));
  char dir[256];
  snprintf(dir, sizeof dir, "%s", test_path("out/mesh"));
  const char *argv[] = {"mesh", case_path, "--output", dir, "--set", "geometry.dr=0.05", NULL};
  assert_int_equal(run(sph_cmd_mesh, argv), 0);
  assert_non_null(strstr(out, "200 fluid, 72 vertex, 72 segment particles"));
  char text[4096];
  test_read("out/mesh/mesh.pvd", text, sizeof text);
  assert_non_null(strstr(text, "part=\"0\" file=\"fluid_000000.vtu\""));
  assert_non_null(strstr(text, "part=\"1\" file=\"boundary_000000.vtu\""));
  test_read("out/mesh/fluid_000000.vtu", text, sizeof text);
  assert_non_null(strstr(text, "NumberOfPoints=\"200\" NumberOfCells=\"200\""));
  assert_non_null(strstr(text, "Name=\"gamma\""));
  assert_non_null(strstr(text, "Name=\"grad_gamma\" NumberOfComponents=\"3\""));
  test_read("out/mesh/boundary_000000.vtu", text, sizeof text);
  assert_non_null(strstr(text, "NumberOfPoints=\"72\" NumberOfCells=\"72\""));
  assert_non_null(strstr(text, "<CellData>"));
  test_read("out/mesh/used_case.yaml", text, sizeof text);
  assert_non_null(strstr(text, "dr: 0.05"));
  assert_non_null(strstr(text, "h_over_dr:"));
  /* A run case (solver sections next to geometry) is accepted, and its sections are checked. */
  snprintf(text, sizeof text, "%sfluid: {rho0: 1000, c0: 20}\ntime: {end: 0.5}\n", geometry);
  test_write("tank.yaml", text);
  const char *full[] = {"mesh", case_path, "--output", dir, NULL};
  assert_int_equal(run(sph_cmd_mesh, full), 0);
  const char *bad_solver[] = {"mesh", case_path, "--output", dir, "--set", "fluid.rh0=1", NULL};
  assert_int_equal(run(sph_cmd_mesh, bad_solver), CMN_EXIT_INPUT);
  assert_non_null(strstr(out, "unknown key 'fluid.rh0'"));
  /* A typo in the case is reported. */
  const char *typo[] = {"mesh", case_path, "--output", dir, "--set", "geometry.dx=1", NULL};
  assert_int_equal(run(sph_cmd_mesh, typo), CMN_EXIT_INPUT);
  assert_non_null(strstr(out, "unknown key 'geometry.dx'"));
  /* Command-line errors come from common/'s cli layer, as for `run`: exit 2 naming the option. */
  const char *bad_set[] = {"mesh", case_path, "--output", dir, "--set", "bad", NULL};
  assert_int_equal(run(sph_cmd_mesh, bad_set), CMN_EXIT_INPUT);
  assert_non_null(strstr(out, "--set 'bad': expected key=value"));
  const char *no_value[] = {"mesh", case_path, "--output", dir, "--set", NULL};
  assert_int_equal(run(sph_cmd_mesh, no_value), CMN_EXIT_INPUT);
  assert_non_null(strstr(out, "mesh: --set: missing value"));
  const char *no_output[] = {"mesh", case_path, "--set", "geometry.dr=0.05", NULL};
  assert_int_equal(run(sph_cmd_mesh, no_output), CMN_EXIT_INPUT);
  assert_non_null(strstr(out, "mesh: --output DIR is required"));
  const char *unknown[] = {"mesh", case_path, "--output", dir, "--frobnicate", NULL};
  assert_int_equal(run(sph_cmd_mesh, unknown), CMN_EXIT_INPUT);
  assert_non_null(strstr(out, "mesh: unknown option '--frobnicate'"));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_gamma_2d),       cmocka_unit_test(test_gamma_box_vs_stl),
      cmocka_unit_test(test_gamma_obstacle), cmocka_unit_test(test_gamma_outside),
      cmocka_unit_test(test_gamma_errors),   cmocka_unit_test(test_mesh_command)};
  return cmocka_run_group_tests(tests, test_dir_setup, test_dir_teardown);
}
