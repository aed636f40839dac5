/* Bad geometry input stops the program with exit code 2 and a message naming the file, the line
 * (or triangle) and what was expected. Each case runs in a child process (the application layer
 * exits on bad input) whose stderr is captured. */
#include <stdio.h>

#include "sabre/common.h"
#include "sabre/sph.h"
#include "testutil.h"
/* testutil.h first */
#include "sph_testfiles.h"

/* Read a case given as text (named case.yaml in the test directory) as `mesh` would. */
static int read_case(void *yaml) {
  char err[512];
  struct cmn_case *c = cmn_case_parse(yaml, test_path("case.yaml"), err, sizeof err);
  if (!c) {
    fprintf(stderr, "parse: %s\n", err);
    return 99;
  }
  struct sph_geometry g;
  struct sph_system s;
  sph_geometry_read(&g, c);
  cmn_case_check_unused(c);
  sph_system_from_geometry(&s, &g);
  sph_system_free(&s);
  sph_geometry_free(&g);
  cmn_case_free(c);
  return 0;
}

static int run_case(const char *yaml, char *msg, size_t len) {
  return test_capture(read_case, (void *)yaml, msg, len);
}

static void expect(const char *yaml, const char *want) {
  char msg[4096];
  int rc = run_case(yaml, msg, sizeof msg);
  if (rc != CMN_EXIT_INPUT || !strstr(msg, want))
    print_error("exit %d, stderr '%s'; wanted exit 2 and '%s'\n", rc, msg, want);
  assert_int_equal(rc, CMN_EXIT_INPUT);
  assert_non_null(strstr(msg, want));
}

#define HEAD2 "geometry:\n  dimension: 2\n  dr: 0.1\n"
#define HEAD3 "geometry:\n  dimension: 3\n  dr: 0.1\n"

static void test_case_errors(void **state) {
  (void)state;
  char msg[4096];
  /* The valid case used as a base below runs cleanly. */
  assert_int_equal(
      run_case(HEAD2 "  walls:\n    - {type: box, lo: [0, 0], hi: [1, 1]}\n", msg, sizeof msg), 0);
  expect(HEAD2 "  walls:\n    - {type: box, lo: [0, 0], hii: [1, 1]}\n",
         "geometry.walls[0].hi: required key missing");
  expect(HEAD2 "  walls:\n    - {type: box, lo: [0, 0], hi: [1, 1], hight: 2}\n",
         "unknown key 'geometry.walls[0].hight'");
  expect(HEAD2 "  walls:\n    - {type: box, lo: [0, 0], hi: [1, -1]}\n",
         "hi must exceed lo in every direction (y: -1 <= 0)");
  expect(HEAD2 "  walls:\n    - {type: cube, lo: [0, 0], hi: [1, 1]}\n",
         "case.yaml:5:14: geometry.walls[0].type: expected one of: interval, box");
  expect(HEAD2 "  walls:\n    - {type: stl, file: a.stl}\n",
         "wall type 'stl' does not exist in 2D");
  expect(HEAD2 "  walls:\n    - {type: channel, lo: [0, 0], hi: [1, 1]}\n",
         "add x to geometry.periodic");
  expect(HEAD3
         "  periodic: [x, y]\n  walls:\n"
         "    - {type: channel, lo: [0, 0, 0], hi: [1, 1, 1], open: [y-]}\n",
         "geometry.walls[0].open[0]: no such face for this wall type in 3D");
  expect(HEAD2 "  walls:\n    - {type: box, lo: [0, 0], hi: [1, 1], open: [z+]}\n",
         "geometry.walls[0].open[0]: no such face");
  expect(HEAD2 "  walls:\n    - {type: polygon, closed: false, points: [[0, 0], [1, 0], [1, 1]]}\n",
         "geometry.walls: geometry.walls[0] (polygon): segment 1: the wall is open at (0, 0)");
  expect(HEAD2
         "  walls:\n    - {type: polygon, closed: false, fluid: inside, points: [[0, 0], "
         "[1, 0]]}\n",
         "an open polyline has the fluid on its left or right");
  expect(HEAD2 "  periodic: [z]\n", "geometry.periodic[0]: no direction z in 2D");
  expect(HEAD2
         "  walls:\n    - {type: box, lo: [0, 0], hi: [1, 1]}\n"
         "    - {type: polygon, fluid: left, closed: false, points: [[1, 1], [0, 1]]}\n",
         "inconsistent orientation");
  /* Files. */
  test_write("bad.poly", "polygon\n0 0\n1 0\n1 1 closed\n");
  expect(HEAD2 "  walls:\n    - {type: polyline_file, file: bad.poly}\n",
         "bad.poly:4: expected 'polygon', 'polyline', or a point");
  test_write("open.poly", "# a floor and a wall\npolyline\n0 0\n1 0\n1 1\n");
  expect(HEAD2 "  walls:\n    - {type: polyline_file, file: open.poly}\n",
         "open.poly:3: segment 1: the wall is open at (0, 0)");
  expect(HEAD2 "  walls:\n    - {type: polyline_file, file: missing.poly}\n",
         "missing.poly: cannot open");
  test_write("bad.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 zero\n");
  expect(HEAD3 "  walls:\n    - {type: stl, file: bad.stl}\n",
         "bad.stl:5: expected three numbers after 'vertex', got 'zero'");
  /* A closed tetrahedron, facets counter-clockwise seen from outside (a proper solid). */
  test_write("tetra.stl",
             "solid t\n"
             "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\n"
             "endloop\nendfacet\n"
             "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\n"
             "endloop\nendfacet\n"
             "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\n"
             "endloop\nendfacet\n"
             "facet normal 0 0 0\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\n"
             "endloop\nendfacet\nendsolid t\n");
  assert_int_equal(
      run_case(HEAD3 "  walls:\n    - {type: stl, file: tetra.stl}\n", msg, sizeof msg), 0);
  /* The same solid with its facets reversed (clockwise from outside): inside out. */
  test_write("inverted.stl",
             "solid t\n"
             "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
             "endloop\nendfacet\n"
             "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 1 0 0\n"
             "endloop\nendfacet\n"
             "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 0 0 1\n"
             "endloop\nendfacet\n"
             "facet normal 0 0 0\nouter loop\nvertex 1 0 0\nvertex 0 0 1\nvertex 0 1 0\n"
             "endloop\nendfacet\nendsolid t\n");
  expect(HEAD3 "  walls:\n    - {type: stl, file: inverted.stl}\n", "inside out");
  /* Three facets only: open surface, named by triangle. */
  test_write("open.stl",
             "solid t\n"
             "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\n"
             "endloop\nendfacet\n"
             "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\n"
             "endloop\nendfacet\n"
             "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\n"
             "endloop\nendfacet\nendsolid t\n");
  expect(HEAD3 "  walls:\n    - {type: stl, file: open.stl}\n", "the surface is open");
  expect(HEAD3 "  walls:\n    - {type: stl, file: open.stl}\n", "open.stl: triangle ");
  /* Open solids: a name the file lacks, a name given twice, and both ways of opening at once. */
  expect(HEAD3 "  walls:\n    - {type: stl, file: tetra.stl, open_solids: [inlet]}\n",
         "tetra.stl: no solid named 'inlet'");
  expect(HEAD3 "  walls:\n    - {type: stl, file: tetra.stl, open_solids: [t, t]}\n",
         "geometry.walls[0].open_solids[1]: solid 't' is named twice (entries 0 and 1)");
  expect(HEAD3 "  walls:\n    - {type: stl, file: tetra.stl, open: true, open_solids: [t]}\n",
         "geometry.walls[0].open_solids: give 'open: true' (the whole file) or 'open_solids'");
}

int main(void) {
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_case_errors)};
  return cmocka_run_group_tests(tests, test_dir_setup, test_dir_teardown);
}
