/* Imposed volume flux, M §5: the slice measurement M(56–57) against exact fluxes of known
 * profiles, and the driving-force formulas M(58), M(62–63) as a controller of a toy model.
 *
 * What the toy model proves: dU/dt = F − kU, advanced by the explicit step
 * U^n = U^{n−1} + Δt (F^n − k U^{n−1}) that M(60) describes, is the simplest flow with an internal
 * force the controller does not know. It checks the controller algebra (fixed points, decay rate,
 * variable steps), not the SPH channel: there the internal force also carries pressure noise and
 * the measured ṽ the slice sampling error. */
#include <math.h>
#include <string.h>

#include "sabre/sph.h"
#include "sabre/sph_flux.h"
#include "testutil.h"

#define NMAX 4096

static double xs[3][NMAX], vs[3][NMAX], vol[NMAX];

/* 2D periodic channel, y ∈ [0, hc], Poiseuille profile v_x = U 4y(hc − y)/hc² on the lattice
 * ((i + ½)Δr, (j + ½)Δr). Returns the particle count. */
static size_t channel_2d(double dr, int nx, int ny, double u_max, double theta) {
  const double hc = ny * dr, c = cos(theta), s = sin(theta);
  size_t n = 0;
  for (int i = 0; i < nx; i++)
    for (int j = 0; j < ny; j++) {
      const double x = (i + 0.5) * dr, y = (j + 0.5) * dr;
      const double vx = u_max * 4.0 * y * (hc - y) / (hc * hc), vy = 0.37 * u_max * sin(9.1 * x);
      xs[0][n] = c * x - s * y;
      xs[1][n] = s * x + c * y;
      vs[0][n] = c * vx - s * vy;
      vs[1][n] = s * vx + c * vy;
      vol[n] = dr * dr;
      n++;
    }
  return n;
}

/* Q_SPH of a parabolic profile is the midpoint rule of ∫v dy over the particle rows:
 * Q_SPH = (2/3) U hc + U Δr²/(3 hc) exactly (the midpoint rule errs by hc Δr² v''/24). */
static void test_poiseuille_2d(void **state) {
  (void)state;
  const double dr = 0.0173, u = 0.0234;
  const int nx = 24, ny = 20;
  const double hc = ny * dr;
  const size_t n = channel_2d(dr, nx, ny, u, 0.0);
  const double *const x[3] = {xs[0], xs[1], xs[2]}, *const v[3] = {vs[0], vs[1], vs[2]};
  struct sph_flux_slice sl = {{7.0 * dr, 0.3, 0.0}, {1.0, 0.0, 0.0}, 2.0 * dr, hc};
  double q, vm;
  assert_int_equal(sph_flux_measure(2, &sl, NULL, n, x, v, vol, &q, &vm), 0);
  const double q_exact = 2.0 / 3.0 * u * hc, q_midpoint = q_exact + u * dr * dr / (3.0 * hc);
  assert_rel(q, q_midpoint, 1e-13);
  assert_rel(vm, q_midpoint / hc, 1e-13);
  print_message("Poiseuille 2D: Q_SPH/Q - 1 = %.3e (midpoint rule: (dr/hc)^2/2 = %.3e)\n",
                q / q_exact - 1.0, 0.5 * (dr / hc) * (dr / hc));
  /* Across the periodic boundary: the slice at x = 0 needs the minimum image. */
  struct sph_domain dom = {2, {0.0, 0.0, 0.0}, {nx * dr, hc, 0.0}, {1, 0, 0}};
  sl.point[0] = 0.0;
  assert_int_equal(sph_flux_measure(2, &sl, &dom, n, x, v, vol, &q, NULL), 0);
  assert_rel(q, q_midpoint, 1e-13);
  assert_int_equal(sph_flux_measure(2, &sl, NULL, n, x, v, vol, &q, NULL), 0);
  assert_rel(q, 0.5 * q_midpoint, 1e-13); /* only the column at +Δr/2 without the wrap */
  /* The same channel rotated by 0.3 rad: the flux through the rotated slice is unchanged. */
  const double th = 0.3;
  channel_2d(dr, nx, ny, u, th);
  struct sph_flux_slice sr = {
      {cos(th) * 7.0 * dr - sin(th) * 0.3, sin(th) * 7.0 * dr + cos(th) * 0.3, 0.0},
      {cos(th), sin(th), 0.0},
      2.0 * dr,
      hc};
  assert_int_equal(sph_flux_measure(2, &sr, NULL, n, x, v, vol, &q, NULL), 0);
  assert_rel(q, q_midpoint, 1e-12);
}

/* 3D rectangular duct with the separable profile v_x = U f(y/a) f(z/b), f(s) = 4s(1 − s):
 * Q_SPH = U (2a/3 + Δr²/(3a)) (2b/3 + Δr²/(3b)). */
static void test_duct_3d(void **state) {
  (void)state;
  const double dr = 0.011, u = 1.37;
  const int nx = 6, ny = 14, nz = 9;
  const double a = ny * dr, b = nz * dr;
  size_t n = 0;
  for (int i = 0; i < nx; i++)
    for (int j = 0; j < ny; j++)
      for (int k = 0; k < nz; k++) {
        const double y = (j + 0.5) * dr, z = (k + 0.5) * dr;
        xs[0][n] = (i + 0.5) * dr;
        xs[1][n] = y;
        xs[2][n] = z;
        vs[0][n] = u * 4.0 * y * (a - y) / (a * a) * 4.0 * z * (b - z) / (b * b);
        vs[1][n] = -0.2 * u;
        vs[2][n] = 0.1 * u;
        vol[n] = dr * dr * dr;
        n++;
      }
  const double *const x[3] = {xs[0], xs[1], xs[2]}, *const v[3] = {vs[0], vs[1], vs[2]};
  struct sph_flux_slice sl = {{3.0 * dr, 0.0, 0.0}, {1.0, 0.0, 0.0}, 2.0 * dr, a * b};
  double q, vm;
  assert_int_equal(sph_flux_measure(3, &sl, NULL, n, x, v, vol, &q, &vm), 0);
  const double my = 2.0 * a / 3.0 + dr * dr / (3.0 * a), mz = 2.0 * b / 3.0 + dr * dr / (3.0 * b);
  assert_rel(q, u * my * mz, 1e-13);
  assert_rel(vm, u * my * mz / (a * b), 1e-13);
}

/* Half-open slices tile a periodic box: summed over the slices, every particle counts once, also
 * those lying exactly on slice faces. 1D, random positions and velocities. */
static void test_slices_tile(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 56u);
  const double w = 0.125, len = 8 * w;
  const size_t n = 300;
  double total = 0.0;
  for (size_t b = 0; b < n; b++) {
    xs[0][b] = b % 10 == 0 ? (double)(b % 8) * w : sabre_rng_uniform(&rng, 0.0, len);
    vs[0][b] = sabre_rng_uniform(&rng, -1.0, 2.0);
    vol[b] = sabre_rng_uniform(&rng, 0.5, 1.5) * 1e-3;
    total += vol[b] * vs[0][b];
  }
  const double *const x[3] = {xs[0], NULL, NULL}, *const v[3] = {vs[0], NULL, NULL};
  struct sph_domain dom = {1, {0.0, 0.0, 0.0}, {len, 0.0, 0.0}, {1, 0, 0}};
  double sum = 0.0;
  for (int s = 0; s < 8; s++) {
    struct sph_flux_slice sl = {{(s + 0.5) * w, 0.0, 0.0}, {1.0, 0.0, 0.0}, w, 1.0};
    double q;
    assert_int_equal(sph_flux_measure(1, &sl, &dom, n, x, v, vol, &q, NULL), 0);
    sum += q * w;
  }
  assert_rel(sum, total, 1e-13);
}

/* The particle-store form (V = m/ρ) agrees with the array form. */
static void test_parts(void **state) {
  (void)state;
  const double dr = 0.0173;
  const size_t n = channel_2d(dr, 10, 8, 0.5, 0.0);
  struct sph_parts p;
  sph_parts_init(&p, SPH_KIND_FLUID);
  sph_parts_append(&p, n);
  for (size_t b = 0; b < n; b++) {
    p.x[0][b] = xs[0][b];
    p.x[1][b] = xs[1][b];
    p.v[0][b] = vs[0][b];
    p.v[1][b] = vs[1][b];
    p.rho[b] = 1000.0 + 3.0 * (double)(b % 7);
    p.mass[b] = p.rho[b] * dr * dr;
    vol[b] = p.mass[b] / p.rho[b];
  }
  struct sph_flux_slice sl = {{4.0 * dr, 0.0, 0.0}, {1.0, 0.0, 0.0}, 2.0 * dr, 8 * dr};
  const double *const x[3] = {xs[0], xs[1], xs[2]}, *const v[3] = {vs[0], vs[1], vs[2]};
  double q1, q2, v1, v2;
  assert_int_equal(sph_flux_measure(2, &sl, NULL, n, x, v, vol, &q1, &v1), 0);
  assert_int_equal(sph_flux_measure_parts(2, &sl, NULL, &p, &q2, &v2), 0);
  assert_true(q1 == q2 && v1 == v2);
  assert_int_equal(sph_flux_measure_parts(2, &sl, NULL, NULL, &q2, &v2), -1);
  assert_true(isnan(q2) && isnan(v2));
  sph_parts_free(&p);
}

static void test_measure_bad_input(void **state) {
  (void)state;
  const double *const x[3] = {xs[0], xs[1], xs[2]}, *const v[3] = {vs[0], vs[1], vs[2]};
  const double *const xnull[3] = {xs[0], NULL, NULL};
  const struct sph_flux_slice good = {{0.0, 0.0, 0.0}, {0.6, 0.8, 0.0}, 0.1, 1.0};
  struct sph_flux_slice sl;
  double q, vm;
  assert_int_equal(sph_flux_measure(2, &good, NULL, 0, NULL, NULL, NULL, &q, &vm), 0);
  assert_true(q == 0.0 && vm == 0.0);
  assert_int_equal(sph_flux_measure(2, &good, NULL, 5, x, v, vol, NULL, &vm), -1);
  assert_true(isnan(vm));
  assert_int_equal(sph_flux_measure(2, NULL, NULL, 5, x, v, vol, &q, &vm), -1);
  assert_int_equal(sph_flux_measure(0, &good, NULL, 5, x, v, vol, &q, &vm), -1);
  assert_int_equal(sph_flux_measure(4, &good, NULL, 5, x, v, vol, &q, &vm), -1);
  assert_int_equal(sph_flux_measure(2, &good, NULL, 5, NULL, v, vol, &q, &vm), -1);
  assert_int_equal(sph_flux_measure(2, &good, NULL, 5, x, NULL, vol, &q, &vm), -1);
  assert_int_equal(sph_flux_measure(2, &good, NULL, 5, x, v, NULL, &q, &vm), -1);
  assert_int_equal(sph_flux_measure(2, &good, NULL, 5, xnull, v, vol, &q, &vm), -1);
  assert_int_equal(sph_flux_measure(1, &good, NULL, 5, xnull, v, vol, &q, &vm), -1); /* |n| */
  sl = good;
  sl.normal[1] = 0.81;
  assert_int_equal(sph_flux_measure(2, &sl, NULL, 5, x, v, vol, &q, &vm), -1);
  sl = good;
  sl.width = 0.0;
  assert_int_equal(sph_flux_measure(2, &sl, NULL, 5, x, v, vol, &q, &vm), -1);
  sl = good;
  sl.area = -1.0;
  assert_int_equal(sph_flux_measure(2, &sl, NULL, 5, x, v, vol, &q, &vm), -1);
  sabre_fp_traps_off();
  sl = good;
  sl.width = NAN;
  assert_int_equal(sph_flux_measure(2, &sl, NULL, 5, x, v, vol, &q, &vm), -1);
  sl = good;
  sl.point[0] = INFINITY;
  assert_int_equal(sph_flux_measure(2, &sl, NULL, 5, x, v, vol, &q, &vm), -1);
  sabre_fp_traps_on();
  assert_true(isnan(q) && isnan(vm));
}

/* The variable-step form M(62) is M(63) for a constant step; M(58) has half M(63)'s first term and
 * no memory of the previous force. */
static void test_formulas(void **state) {
  (void)state;
  const double v = 0.0123, a = 0.0111, b = 0.0097, dt = 2.385e-4, f = 3.3;
  assert_rel(sph_flux_force_m63(v, a, b, dt, dt, f), (v - 2.0 * a + b) / dt + f, 1e-14);
  assert_rel(sph_flux_force_m58(v, a, b, dt), (v - 2.0 * a + b) / (2.0 * dt), 1e-15);
  assert_rel(sph_flux_force_m63(v, a, b, dt, 2.0 * dt, 0.0), (v - a) / dt - (a - b) / (2.0 * dt),
             1e-14);
}

/* Toy channel dU/dt = F − kU, advanced as M(60) describes. */
struct toy {
  double k, u;
};
static double toy_step(struct toy *m, double force, double dt) {
  m->u += dt * (force - m->k * m->u);
  return m->u;
}

/* M(63) drives U to the target: the error obeys e^n = −kΔt (e^{n−1} − e^{n−2}), which decays as
 * ρ^n with ρ the largest root modulus of z² + kΔt z − kΔt = 0, and the force settles at the
 * equilibrium F = kv, M(59). */
static void test_m63_converges(void **state) {
  (void)state;
  const double v = 0.0123, k = 37.5, dt = 1e-3, eps = k * dt;
  const double rho = 0.5 * (eps + sqrt(eps * eps + 4.0 * eps));
  struct toy m = {k, 0.0};
  struct sph_flux_ctrl c;
  sph_flux_ctrl_init(&c, SPH_FLUX_M63, v, 0.0);
  double err[41], f = 0.0;
  for (int n = 1; n <= 40; n++) {
    f = sph_flux_ctrl_update(&c, m.u, dt);
    toy_step(&m, f, dt);
    err[n] = fabs(m.u - v);
  }
  const double rate = pow(err[20] / err[10], 0.1);
  print_message(
      "M(63): |U - v|/v after 1, 5, 10, 20 steps: %.2e %.2e %.2e %.2e; rate %.4f "
      "(predicted %.4f)\n",
      err[1] / v, err[5] / v, err[10] / v, err[20] / v, rate, rho);
  assert_rel(rate, rho, 0.05);
  assert_true(err[40] <= 1e-14 * v);
  assert_rel(f, k * v, 1e-12);
  assert_int_equal((int)c.steps, 40);
}

/* M(58), the baseline: its fixed point is U* = v/(1 + 2kΔt) with F* = kU* < kv: the force is
 * underestimated because the internal force is ignored (M §5, Fig. 4). */
static void test_m58_baseline(void **state) {
  (void)state;
  const double v = 0.0123, k = 37.5, dt = 1e-3;
  struct toy m = {k, 0.0};
  struct sph_flux_ctrl c;
  sph_flux_ctrl_init(&c, SPH_FLUX_M58, v, 0.0);
  double f = 0.0;
  for (int n = 1; n <= 300; n++) {
    f = sph_flux_ctrl_update(&c, m.u, dt);
    toy_step(&m, f, dt);
  }
  const double u_star = v / (1.0 + 2.0 * k * dt);
  assert_rel(m.u, u_star, 1e-12);
  assert_rel(f, k * u_star, 1e-12);
  print_message("M(58): U converges to v/(1 + 2k dt): relative error (U - v)/v = %.3e\n",
                (m.u - v) / v);
  assert_true((v - m.u) / v > 0.06);
}

/* Variable steps (as from a CFL condition): M(62) still converges to the target, and a sudden
 * change of the internal force (k jumps) is absorbed. */
static void test_m62_variable_steps(void **state) {
  (void)state;
  struct sabre_rng rng;
  sabre_rng_seed(&rng, 62u);
  const double v = 0.0123;
  struct toy m = {37.5, 0.002};
  struct sph_flux_ctrl c;
  sph_flux_ctrl_init(&c, SPH_FLUX_M63, v, 0.3);
  for (int n = 1; n <= 200; n++) {
    if (n == 100) m.k = 61.0;
    const double dt = 1e-3 * sabre_rng_uniform(&rng, 0.5, 1.5);
    const double f = sph_flux_ctrl_update(&c, m.u, dt);
    toy_step(&m, f, dt);
    if (n == 99 || n == 200) {
      assert_rel(m.u, v, 1e-13);
      assert_rel(f, m.k * v, 1e-10);
    }
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_poiseuille_2d),      cmocka_unit_test(test_duct_3d),
      cmocka_unit_test(test_slices_tile),        cmocka_unit_test(test_parts),
      cmocka_unit_test(test_measure_bad_input),  cmocka_unit_test(test_formulas),
      cmocka_unit_test(test_m63_converges),      cmocka_unit_test(test_m58_baseline),
      cmocka_unit_test(test_m62_variable_steps),
  };
  return cmocka_run_group_tests(tests, sabre_setup_gsl_traps, NULL);
}
