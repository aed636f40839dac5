/* Wall meshes: STL round trips (ASCII and binary), closedness and orientation checks with their
 * messages, refinement (conforming, sizes, area kept), generators, polyline files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sabre/sph.h"
#include "testutil.h"
/* testutil.h first */
#include "sph_testfiles.h"

static double total_measure(const struct sph_mesh *m) {
  double sum = 0;
  for (size_t e = 0; e < m->nelem; e++) {
    const double *a = m->vert[m->elem[e][0]], *b = m->vert[m->elem[e][1]];
    if (m->dim == 2) {
      sum += hypot(b[0] - a[0], b[1] - a[1]);
    } else {
      const double *c = m->vert[m->elem[e][2]];
      double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      double w[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                     u[0] * v[1] - u[1] * v[0]};
      sum += 0.5 * sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    }
  }
  return sum;
}

/* A cube of side 1.5 meshed at 0.5, coordinates exact in single precision. */
static void cube(struct sph_mesh *m) {
  sph_mesh_init(m, 3);
  int src = sph_mesh_add_source(m, "cube");
  sph_mesh_box(m, (double[]){0.25, -0.5, 1.125}, (double[]){1.75, 1.0, 2.625}, 0.5, 0, 0, src);
}

static void test_box_closed(void **state) {
  (void)state;
  struct sph_mesh m;
  cube(&m);
  char msg[512];
  assert_int_equal(m.nelem, 6 * 9 * 2);
  assert_int_equal(m.nvert, 6 * 16 - 12 * 4 + 8); /* faces' nodes minus shared edge nodes */
  assert_int_equal(sph_mesh_check(&m, NULL, msg, sizeof msg), 0);
  assert_rel(sph_mesh_signed_volume(&m, 0), 1.5 * 1.5 * 1.5, 1e-14);
  assert_rel(total_measure(&m), 6 * 1.5 * 1.5, 1e-14);
  /* Normals into the box: at the face x = 0.25 it is +x. */
  for (size_t e = 0; e < m.nelem; e++) {
    const double *a = m.vert[m.elem[e][0]], *b = m.vert[m.elem[e][1]], *c = m.vert[m.elem[e][2]];
    double cx = (a[0] + b[0] + c[0]) / 3 - 1.0, cy = (a[1] + b[1] + c[1]) / 3 - 0.25,
           cz = (a[2] + b[2] + c[2]) / 3 - 1.875;
    assert_true(cx * m.normal[e][0] + cy * m.normal[e][1] + cz * m.normal[e][2] < 0);
  }
  sph_mesh_free(&m);
}

static void roundtrip(int binary) {
  struct sph_mesh m, r;
  cube(&m);
  const char *path = test_path(binary ? "cube_bin.stl" : "cube_ascii.stl");
  assert_int_equal(sph_mesh_write_stl(&m, path, binary), 0);
  FILE *f = fopen(path, "rb");
  char head[6] = {0};
  assert_int_equal(fread(head, 1, 5, f), 5);
  fclose(f);
  assert_int_equal(strcmp(head, "solid") == 0, !binary);
  sph_mesh_init(&r, 3);
  char msg[512];
  assert_int_equal(sph_mesh_read_stl(&r, path, 1.0, 1, msg, sizeof msg), 0);
  assert_int_equal(r.nelem, m.nelem);
  assert_int_equal(r.nvert, m.nvert);
  for (size_t e = 0; e < m.nelem; e++)
    for (int k = 0; k < 3; k++) {
      for (int a = 0; a < 3; a++) assert_true(r.vert[r.elem[e][k]][a] == m.vert[m.elem[e][k]][a]);
      assert_abs(r.normal[e][k], m.normal[e][k], 1e-15);
    }
  assert_int_equal(sph_mesh_check(&r, NULL, msg, sizeof msg), 0);
  assert_rel(sph_mesh_signed_volume(&r, 0), 1.5 * 1.5 * 1.5, 1e-14);
  sph_mesh_free(&r);
  /* Read as an obstacle: normals reversed, volume negative. */
  sph_mesh_init(&r, 3);
  assert_int_equal(sph_mesh_read_stl(&r, path, 2.0, 0, msg, sizeof msg), 0);
  assert_rel(sph_mesh_signed_volume(&r, 0), -8 * 1.5 * 1.5 * 1.5, 1e-14);
  assert_abs(r.normal[0][0], -m.normal[0][0], 1e-15);
  sph_mesh_free(&r);
  sph_mesh_free(&m);
}

static void test_stl_roundtrip_ascii(void **state) {
  (void)state;
  roundtrip(0);
}

static void test_stl_roundtrip_binary(void **state) {
  (void)state;
  roundtrip(1);
}

/* Check that `path` read as STL then checked fails with a message containing `want`. */
static void expect_stl_error(const char *path, const char *want) {
  struct sph_mesh m;
  sph_mesh_init(&m, 3);
  char msg[1024] = "";
  int rc = sph_mesh_read_stl(&m, path, 1.0, 1, msg, sizeof msg);
  if (rc == 0) rc = sph_mesh_check(&m, NULL, msg, sizeof msg);
  if (rc == 0 || !strstr(msg, want)) print_error("message: '%s', wanted '%s'\n", msg, want);
  assert_int_equal(rc, -1);
  assert_non_null(strstr(msg, want));
  sph_mesh_free(&m);
}

static const char tetra_facets[] =
    "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\n"
    "endfacet\n"
    "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\n"
    "endfacet\n"
    "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\n"
    "endfacet\n";

static void test_stl_errors(void **state) {
  (void)state;
  char text[4096];
  /* A closed tetrahedron is accepted. */
  snprintf(text, sizeof text,
           "solid t\n%sfacet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\n"
           "endloop\nendfacet\nendsolid t\n",
           tetra_facets);
  struct sph_mesh m;
  sph_mesh_init(&m, 3);
  char msg[1024];
  const char *ok = test_write("tetra.stl", text);
  assert_int_equal(sph_mesh_read_stl(&m, ok, 1.0, 1, msg, sizeof msg), 0);
  assert_int_equal(sph_mesh_check(&m, NULL, msg, sizeof msg), 0);
  assert_rel(sph_mesh_signed_volume(&m, 0), 1.0 / 6.0, 1e-15);
  sph_mesh_free(&m);
  /* Missing fourth face: open. */
  snprintf(text, sizeof text, "solid t\n%sendsolid t\n", tetra_facets);
  expect_stl_error(test_write("open.stl", text), "the surface is open");
  /* Fourth face with its vertices in the wrong order (normal 0: no facet-normal check). */
  snprintf(text, sizeof text,
           "solid t\n%sfacet normal 0 0 0\nouter loop\nvertex 1 0 0\nvertex 0 0 1\nvertex 0 1 0\n"
           "endloop\nendfacet\nendsolid t\n",
           tetra_facets);
  expect_stl_error(test_write("flipped.stl", text), "inconsistent orientation");
  expect_stl_error(test_path("flipped.stl"), "flipped.stl: triangle 4 runs through");
  /* Facet normal against the vertex order. */
  snprintf(text, sizeof text,
           "solid t\n%sfacet normal -1 -1 -1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\n"
           "vertex 0 0 1\nendloop\nendfacet\nendsolid t\n",
           tetra_facets);
  expect_stl_error(test_write("normal.stl", text), ":23: triangle 4: its facet normal");
  /* Syntax errors name the line. */
  expect_stl_error(test_write("syntax.stl",
                              "solid x\nfacet normal 0 0 1\nouter loop\n"
                              "vertex 0 0\nendloop\n"),
                   "syntax.stl:5: expected three numbers after 'vertex', got 'endloop'");
  expect_stl_error(test_write("trunc.stl", "solid x\nfacet normal 0 0 1\n"),
                   "trunc.stl:3: expected 'outer', got 'end of file'");
  expect_stl_error(test_write("junk.stl", "hello"), "not an STL file");
  /* Degenerate triangle. */
  expect_stl_error(test_write("degen.stl",
                              "solid d\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\n"
                              "vertex 1 1 1\nvertex 2 2 2\nendloop\nendfacet\n"
                              "endsolid d\n"),
                   "degen.stl: triangle 1: degenerate");
  /* Binary: truncated file is not taken for binary. */
  struct sph_mesh c;
  cube(&c);
  const char *bin = test_path("cut.stl");
  assert_int_equal(sph_mesh_write_stl(&c, bin, 1), 0);
  assert_int_equal(truncate(bin, 84 + 50 * 10), 0);
  expect_stl_error(bin, "says n = 108");
  sph_mesh_free(&c);
}

/* Reading `path` with the one open solid name[0] fails with a message containing `want`. */
static void expect_open_error(const char *path, const char **name, const char *want) {
  const struct sph_stl_open open = {0, 1, name};
  struct sph_mesh m;
  sph_mesh_init(&m, 3);
  char msg[1024] = "";
  assert_int_equal(sph_mesh_read_stl_open(&m, path, 1.0, 1, &open, msg, sizeof msg), -1);
  if (!strstr(msg, want)) print_error("message: '%s', wanted '%s'\n", msg, want);
  assert_non_null(strstr(msg, want));
  sph_mesh_free(&m);
}

/* Open solids of an ASCII STL: the tetrahedron written as two solids, 'base' (three facets) and
 * 'lid' (one); open_solids flags the named ones, the parts record their element ranges (kept by
 * refinement), and unknown names or names with a binary file are errors. */
static void test_stl_open_solids(void **state) {
  (void)state;
  char text[4096], msg[1024];
  snprintf(text, sizeof text,
           "solid base\n%sendsolid base\nsolid  lid \nfacet normal 1 1 1\nouter loop\n"
           "vertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid lid\n",
           tetra_facets);
  const char *path = test_write("two.stl", text);
  const char *lid[] = {"lid"}, *none[] = {"top"};
  struct sph_stl_open open = {0, 1, lid};
  struct sph_mesh m;
  sph_mesh_init(&m, 3);
  assert_int_equal(sph_mesh_read_stl_open(&m, path, 1.0, 1, &open, msg, sizeof msg), 0);
  assert_int_equal(sph_mesh_check(&m, NULL, msg, sizeof msg), 0);
  assert_int_equal(m.nelem, 4);
  for (size_t e = 0; e < m.nelem; e++)
    assert_int_equal(m.flags[e] & SPH_FLAG_OPEN, m.source_index[e] == 4 ? SPH_FLAG_OPEN : 0);
  assert_int_equal(m.nparts, 2);
  assert_string_equal(m.parts[0].name, "base");
  assert_true(m.parts[0].first == 1 && m.parts[0].last == 3);
  assert_string_equal(m.parts[1].name, "lid");
  assert_true(m.parts[1].first == 4 && m.parts[1].last == 4 && m.parts[1].source == 0);
  /* refinement keeps the flags (per element) and the parts */
  sph_mesh_refine(&m, 0.3);
  size_t nopen = 0;
  for (size_t e = 0; e < m.nelem; e++) {
    assert_int_equal(m.flags[e] & SPH_FLAG_OPEN, m.source_index[e] == 4 ? SPH_FLAG_OPEN : 0);
    nopen += m.source_index[e] == 4;
  }
  assert_true(m.nelem > 4 && nopen > 1 && m.nparts == 2 && m.parts[1].first == 4);
  sph_mesh_free(&m);
  /* the whole file */
  open = (struct sph_stl_open){1, 0, NULL};
  sph_mesh_init(&m, 3);
  assert_int_equal(sph_mesh_read_stl_open(&m, path, 1.0, 1, &open, msg, sizeof msg), 0);
  for (size_t e = 0; e < m.nelem; e++) assert_int_equal(m.flags[e], SPH_FLAG_OPEN);
  sph_mesh_free(&m);
  /* a name the file does not have; names with a binary file */
  expect_open_error(path, none, "two.stl: no solid named 'top'");
  struct sph_mesh c;
  cube(&c);
  const char *bin = test_path("cube_open.stl");
  assert_int_equal(sph_mesh_write_stl(&c, bin, 1), 0);
  sph_mesh_free(&c);
  expect_open_error(bin, lid, "a binary STL file has no solid names");
}

static void test_refine_3d(void **state) {
  (void)state;
  /* A coarse tetrahedron refined at dr: closed, conforming, small, same area and volume. */
  struct sph_mesh m;
  sph_mesh_init(&m, 3);
  int src = sph_mesh_add_source(&m, "tetra");
  const double p[4][3] = {{0.1, 0.2, 0.3}, {1.4, 0.25, 0.35}, {0.3, 1.15, 0.1}, {0.4, 0.5, 1.6}};
  for (int i = 0; i < 4; i++) sph_mesh_add_vertex(&m, p[i]);
  sph_mesh_add_element(&m, (size_t[]){0, 1, 2}, 0, 0, src, 1);
  sph_mesh_add_element(&m, (size_t[]){0, 3, 1}, 0, 0, src, 2);
  sph_mesh_add_element(&m, (size_t[]){0, 2, 3}, 0, 0, src, 3);
  sph_mesh_add_element(&m, (size_t[]){1, 3, 2}, 0, 0, src, 4);
  char msg[512];
  assert_int_equal(sph_mesh_check(&m, NULL, msg, sizeof msg), 0);
  double area = total_measure(&m), vol = sph_mesh_signed_volume(&m, src);
  double dr = 0.0731;
  sph_mesh_refine(&m, dr);
  assert_true(m.nelem > 400);
  if (sph_mesh_check(&m, NULL, msg, sizeof msg)) print_error("%s\n", msg);
  assert_int_equal(sph_mesh_check(&m, NULL, msg, sizeof msg), 0);
  assert_rel(total_measure(&m), area, 1e-12);
  assert_rel(sph_mesh_signed_volume(&m, src), vol, 1e-12);
  double lmax = 0;
  for (size_t e = 0; e < m.nelem; e++)
    for (int k = 0; k < 3; k++) {
      const double *a = m.vert[m.elem[e][k]], *b = m.vert[m.elem[e][(k + 1) % 3]];
      lmax = fmax(lmax, sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                             (a[2] - b[2]) * (a[2] - b[2])));
    }
  assert_true(lmax <= 1.5 * dr);
  assert_true(lmax > 0.5 * dr);
  sph_mesh_free(&m);
}

static void test_polygon_2d(void **state) {
  (void)state;
  /* Clockwise input with fluid inside is turned counter-clockwise; refinement to ≈ dr. */
  const double pts[4][2] = {{0, 0}, {0, 1.1}, {2.3, 1.1}, {2.3, 0}};
  struct sph_mesh m;
  sph_mesh_init(&m, 2);
  int src = sph_mesh_add_source(&m, "poly");
  sph_mesh_polygon(&m, 4, pts, 1, 1, NULL, src);
  assert_rel(sph_mesh_signed_volume(&m, src), 2.3 * 1.1, 1e-14);
  sph_mesh_refine(&m, 0.1);
  assert_int_equal(m.nelem, 2 * (11 + 23));
  char msg[512];
  assert_int_equal(sph_mesh_check(&m, NULL, msg, sizeof msg), 0);
  assert_rel(total_measure(&m), 2 * (1.1 + 2.3), 1e-14);
  /* Normal of the bottom wall points up (into the fluid). */
  for (size_t e = 0; e < m.nelem; e++)
    if (m.vert[m.elem[e][0]][1] == 0 && m.vert[m.elem[e][1]][1] == 0)
      assert_abs(m.normal[e][1], 1.0, 1e-15);
  /* An open polyline is rejected, and so is a second wall run the other way. */
  struct sph_mesh o;
  sph_mesh_init(&o, 2);
  src = sph_mesh_add_source(&o, "floor");
  sph_mesh_polygon(&o, 4, pts, 0, 1, NULL, src);
  assert_int_equal(sph_mesh_check(&o, NULL, msg, sizeof msg), -1);
  assert_non_null(strstr(msg, "floor: segment 1: the wall is open at (0, 0)"));
  sph_mesh_free(&o);
  sph_mesh_init(&o, 2);
  src = sph_mesh_add_source(&o, "tank");
  sph_mesh_polygon(&o, 4, pts, 1, 1, NULL, src);
  src = sph_mesh_add_source(&o, "lid");
  sph_mesh_polygon(&o, 2, (const double[][2]){{2.3, 1.1}, {0, 1.1}}, 0, 1, NULL, src);
  sph_mesh_merge_vertices(&o, 0);
  assert_int_equal(sph_mesh_check(&o, NULL, msg, sizeof msg), -1);
  assert_non_null(strstr(msg, "inconsistent orientation"));
  assert_non_null(strstr(msg, "lid: segment 1"));
  sph_mesh_free(&o);
  /* A channel (box without its x ends) closes through the periodic boundary. */
  sph_mesh_init(&o, 2);
  src = sph_mesh_add_source(&o, "channel");
  sph_mesh_box(&o, (double[]){0, 0}, (double[]){1, 0.4}, 0.1, 0, 3u, src);
  sph_mesh_refine(&o, 0.1);
  assert_int_equal(sph_mesh_check(&o, NULL, msg, sizeof msg), -1);
  assert_non_null(strstr(msg, "open"));
  sph_mesh_free(&o);
  sph_mesh_free(&m);
}

static void test_polyline_file(void **state) {
  (void)state;
  struct sph_mesh m;
  char msg[512];
  sph_mesh_init(&m, 2);
  const char *ok = test_write("tank.poly",
                              "# tank with an outlet on the right\npolygon\n0 0\n2 0 open\n2 1\n"
                              "0 1   # top left\n\npolygon\n0.5 0.25\n0.5 0.5\n0.75 0.5\n");
  assert_int_equal(sph_mesh_read_polyline(&m, ok, 1, msg, sizeof msg), 0);
  assert_int_equal(m.nelem, 7);
  assert_int_equal(sph_mesh_check(&m, NULL, msg, sizeof msg), 0);
  int nopen = 0;
  for (size_t e = 0; e < m.nelem; e++) nopen += m.flags[e] & SPH_FLAG_OPEN;
  assert_int_equal(nopen, 1);
  /* Segments numbered through the file; each knows the line of its first point. */
  for (size_t e = 0; e < m.nelem; e++) assert_int_equal(m.source_index[e], (long)e + 1);
  assert_int_equal(m.source_line[1], 4);
  assert_int_equal(m.source_line[4], 9);
  sph_mesh_free(&m);
  static const struct {
    const char *text, *want;
  } bad[] = {
      {"polygon\n0 0\n1 x\n", "bad.poly:3: expected 'polygon', 'polyline', or a point"},
      {"0 0\n", "bad.poly:1: point before any 'polygon'"},
      {"polygon\n0 0\n1 1\npolyline\n0 0\n1 0\n", "bad.poly:1: polygon with 2 points"},
      {"# nothing\n", "no 'polygon' or 'polyline'"},
      {"polyline\n0 0\n1 0 open\n", "'open' not allowed"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    sph_mesh_init(&m, 2);
    assert_int_equal(
        sph_mesh_read_polyline(&m, test_write("bad.poly", bad[i].text), 1, msg, sizeof msg), -1);
    if (!strstr(msg, bad[i].want)) print_error("message: '%s'\n", msg);
    assert_non_null(strstr(msg, bad[i].want));
    sph_mesh_free(&m);
  }
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_box_closed),           cmocka_unit_test(test_stl_roundtrip_ascii),
      cmocka_unit_test(test_stl_roundtrip_binary), cmocka_unit_test(test_stl_errors),
      cmocka_unit_test(test_stl_open_solids),      cmocka_unit_test(test_refine_3d),
      cmocka_unit_test(test_polygon_2d),           cmocka_unit_test(test_polyline_file)};
  return cmocka_run_group_tests(tests, test_dir_setup, test_dir_teardown);
}
