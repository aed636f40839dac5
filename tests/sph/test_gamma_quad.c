/*
 * Every gamma_term and ∇γ_as against brute-force adaptive quadrature of their definitions (GSL
 * qagp, nested in 3D; tests/sph/test_gamma_ref.h), on random points near random segments and
 * triangles: generic, clipped by the support, nearly tangent to it, very close to the plane, and
 * behind the element. Tolerance 1e-10 on gamma_term and on h·∇γ_as. Larger sweep:
 * invariant_gamma.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/sph_walls.h"
#include "test_gamma_ref.h"
#include "testutil.h"

static const double H = 0.0237;

static void test_segments(void **state) {
  (void)state;
  ref_sweep_segments(60, 101, H);
}

static void test_triangles(void **state) {
  (void)state;
  ref_sweep_triangles(12, 103, H);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_segments),
      cmocka_unit_test(test_triangles),
  };
  return cmocka_run_group_tests(tests, sabre_setup_gsl_traps, NULL);
}
