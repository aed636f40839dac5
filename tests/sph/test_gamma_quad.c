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

#ifndef QUAD_CASES_2D
#define QUAD_CASES_2D 60
#endif
#ifndef QUAD_CASES_3D
#define QUAD_CASES_3D 12
#endif

static const double H = 0.0237;

/* Random point relative to an element with unit normal n and in-plane foot point f: kind selects
 * the regime. Returns the signed distance chosen. */
static double random_delta(struct sabre_rng *rng, int kind) {
  const double sgn = sabre_rng_uniform(rng, 0.0, 1.0) < 0.85 ? 1.0 : -1.0;
  switch (kind % 4) {
    case 0: /* generic */
      return sgn * sabre_rng_uniform(rng, 0.0, 2.05) * H;
    case 1: /* close to the plane */
      return sgn * pow(10.0, -sabre_rng_uniform(rng, 2.0, 7.0)) * H;
    case 2: /* nearly tangent: the support sphere just reaches the plane */
      return sgn * 2.0 * H * (1.0 - pow(10.0, -sabre_rng_uniform(rng, 2.0, 9.0)));
    default: /* moderate */
      return sgn * sabre_rng_uniform(rng, 0.5, 1.9) * H;
  }
}

static double max_err_term = 0.0, max_err_grad = 0.0;

static void compare(double term, const double *grad, double ref_term, const double *ref_grad,
                    int dim) {
  max_err_term = fmax(max_err_term, fabs(term - ref_term));
  assert_abs(term, ref_term, 1e-10);
  for (int c = 0; c < dim; c++) {
    max_err_grad = fmax(max_err_grad, fabs(grad[c] - ref_grad[c]) * H);
    assert_abs(grad[c] * H, ref_grad[c] * H, 1e-10);
  }
}

static void test_segments(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 101);
  struct sph_kernel k;
  sph_kernel_init(&k, 2, H);
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(2000);
  max_err_term = max_err_grad = 0.0;
  for (int i = 0; i < QUAD_CASES_2D; i++) {
    /* segment from (0, 0) to (L, 0) with the fluid above, then a random rigid motion */
    const double L = sabre_rng_uniform(&rng, 0.1, 6.0) * H;
    struct sph_wall_element e = ref_seg(0.0, 0.0, L, 0.0);
    const double delta = random_delta(&rng, i);
    double a[3] = {sabre_rng_uniform(&rng, -2.5 * H, L + 2.5 * H), delta, 0.0};
    if (i % 5 == 4 && fabs(delta) < 2.0 * H) {
      /* clipped at an end, nearly tangent: the support circle just reaches x = 0 or x = L */
      const double R = sqrt(4.0 * H * H - delta * delta);
      const double gap = R * pow(10.0, -sabre_rng_uniform(&rng, 1.0, 8.0));
      a[0] = (i % 2 ? -R + gap : L + R - gap);
    }
    struct ref_motion m = ref_motion_random(&rng, 2, 3.0 * H);
    ref_apply_element(&m, &e);
    ref_apply(&m, a, a);
    double term, grad[3], rterm, rgrad[3];
    sph_gamma_element(&k, a, &e, &term, grad);
    ref_segment(&k, a, &e, &rterm, rgrad, ws);
    if (getenv("SABRE_VERBOSE"))
      printf("segment %d: delta/h %.3e term %.6e (error %.1e), h|∇γ_as| %.6e (error %.1e)\n", i,
             delta / H, term, term - rterm, hypot(grad[0], grad[1]) * H,
             hypot(grad[0] - rgrad[0], grad[1] - rgrad[1]) * H);
    compare(term, grad, rterm, rgrad, 2);
  }
  printf("2D, %d segments: max |Δ gamma_term| = %.2e, max h|Δ ∇γ_as| = %.2e\n", QUAD_CASES_2D,
         max_err_term, max_err_grad);
  gsl_integration_workspace_free(ws);
}

static void test_triangles(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 103);
  struct sph_kernel k;
  sph_kernel_init(&k, 3, H);
  gsl_integration_workspace *wo = gsl_integration_workspace_alloc(2000);
  gsl_integration_workspace *wi = gsl_integration_workspace_alloc(2000);
  max_err_term = max_err_grad = 0.0;
  for (int i = 0; i < QUAD_CASES_3D; i++) {
    /* triangle in z = 0 with random vertices (possibly larger than the support) */
    const double size = sabre_rng_uniform(&rng, 0.5, 6.0) * H;
    double p[3][3];
    for (int j = 0; j < 3; j++) {
      p[j][0] = sabre_rng_uniform(&rng, -1.0, 1.0) * size;
      p[j][1] = sabre_rng_uniform(&rng, -1.0, 1.0) * size;
      p[j][2] = 0.0;
    }
    struct sph_wall_element e = ref_tri(p[0], p[1], p[2]);
    if (e.normal[2] < 0.0) e = ref_tri(p[0], p[2], p[1]);
    double delta = random_delta(&rng, i);
    if (i % 4 == 1) delta = (delta > 0.0 ? 1.0 : -1.0) * fmax(fabs(delta), 1e-5 * H);
    /* foot point inside the triangle or near it (barycentric coordinates in [−0.3, 1.3]) */
    double u = sabre_rng_uniform(&rng, -0.3, 1.0), v = sabre_rng_uniform(&rng, -0.3, 1.3 - u);
    if (i % 3 == 0) { /* inside */
      u = sabre_rng_uniform(&rng, 0.0, 1.0);
      v = sabre_rng_uniform(&rng, 0.0, 1.0 - u);
    }
    double a[3] = {p[0][0] + u * (p[1][0] - p[0][0]) + v * (p[2][0] - p[0][0]),
                   p[0][1] + u * (p[1][1] - p[0][1]) + v * (p[2][1] - p[0][1]), delta};
    if (i % 6 == 5 && fabs(delta) < 2.0 * H) {
      /* support disc nearly touching a vertex from outside or inside */
      const double R = sqrt(4.0 * H * H - delta * delta);
      const double gap = pow(10.0, -sabre_rng_uniform(&rng, 1.0, 7.0)) * (i % 2 ? 1.0 : -1.0);
      const double th = sabre_rng_uniform(&rng, 0.0, 2.0 * REF_PI);
      a[0] = p[0][0] + R * (1.0 + gap) * cos(th);
      a[1] = p[0][1] + R * (1.0 + gap) * sin(th);
    }
    struct ref_motion m = ref_motion_random(&rng, 3, 3.0 * H);
    ref_apply_element(&m, &e);
    ref_apply(&m, a, a);
    double term, grad[3], rterm, rgrad[3];
    sph_gamma_element(&k, a, &e, &term, grad);
    ref_triangle(&k, a, &e, &rterm, rgrad, wo, wi);
    if (getenv("SABRE_VERBOSE"))
      printf("triangle %d: delta/h %.3e term %.6e (error %.1e), h∇γ_as·e_x %.6e (error %.1e)\n", i,
             delta / H, term, term - rterm, grad[0] * H, (grad[0] - rgrad[0]) * H);
    compare(term, grad, rterm, rgrad, 3);
  }
  printf("3D, %d triangles: max |Δ gamma_term| = %.2e, max h|Δ ∇γ_as| = %.2e\n", QUAD_CASES_3D,
         max_err_term, max_err_grad);
  gsl_integration_workspace_free(wo);
  gsl_integration_workspace_free(wi);
}

static int setup(void **state) {
  (void)state;
  gsl_set_error_handler_off();
  sabre_fp_traps_on();
  return 0;
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_segments),
      cmocka_unit_test(test_triangles),
  };
  return cmocka_run_group_tests(tests, setup, NULL);
}
