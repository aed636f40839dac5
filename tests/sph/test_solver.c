/*
 * Solver invariants (docs/sph-solver.md):
 * - momentum is conserved to round-off in a periodic box without walls (pressure and viscous pair
 *   terms are antisymmetric, M 14 with M 37 and J 8–9), with random positions, velocities and
 *   densities, over several predictor–corrector steps;
 * - the volume-diffusion term of M(84) moves volume between fluid particles only:
 *   Σ_a V_a D_a = 0 to round-off (M §4.2), with and without the gravity correction M(81);
 * - the discrete skew-adjoint defect M(27), <Grad f, B> + <f, Div B>, vanishes without walls for
 *   every k of M(37–38), and with walls approaches the boundary integral −∮ f B·n dS;
 * - vertex masses make the summation density of fluid at rest equal ρ0;
 * - a run stops with a message naming the particle when its density leaves the band, or naming
 *   the lowest index and counting all when particles are behind a wall.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "solver_fixture.h"
#include "testutil.h"
#ifdef _OPENMP
#include <omp.h>
#endif

static void jitter(struct sph_solver *sv, uint64_t seed, double dx, double dv, double drho) {
  struct sabre_rng rng;
  sabre_rng_seed(&rng, seed);
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < f->n; a++) {
    for (int c = 0; c < 2; c++) {
      f->x[c][a] += sabre_rng_uniform(&rng, -dx, dx) * sv->sys.dr;
      f->v[c][a] = sabre_rng_uniform(&rng, -dv, dv);
    }
    f->rho[a] *= 1.0 + sabre_rng_uniform(&rng, -drho, drho);
  }
}

static void momentum(const struct sph_solver *sv, double *p, double *scale) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  p[0] = p[1] = p[2] = *scale = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    for (int c = 0; c < 3; c++) p[c] += f->mass[a] * f->v[c][a];
    *scale += f->mass[a] * hypot(f->v[0][a], f->v[1][a]);
  }
}

static void test_momentum_periodic(void **state) {
  (void)state;
  sabre_fp_traps_on();
  for (int k = 0; k <= 1; k++) {
    struct sph_system s;
    fixture_lattice(&s, 16, 16, 0.01, 2.0, FIX_PERIODIC);
    struct sph_config cfg;
    fixture_config(&cfg);
    cfg.nu = 1e-3;
    cfg.grad_k = k;
    struct sph_solver sv;
    sph_solver_init(&sv, &cfg, &s, NULL, NULL);
    sph_system_free(&s);
    jitter(&sv, 42 + (uint64_t)k, 0.1, 0.5, 0.01);
    double p0[3], p1[3], scale;
    momentum(&sv, p0, &scale);
    char msg[512];
    for (int n = 0; n < 10; n++)
      assert_int_equal(sph_solver_step(&sv, INFINITY, msg, sizeof msg), 0);
    momentum(&sv, p1, &scale);
    print_message("k=%d: momentum change (%.3e, %.3e) for sum m|v| = %.3e\n", k, p1[0] - p0[0],
                  p1[1] - p0[1], scale);
    assert_true(scale > 0.1);
    for (int c = 0; c < 2; c++) assert_abs(p1[c], p0[c], 1e-13 * scale);
    sph_solver_free(&sv);
  }
}

static void test_diffusion_volume(void **state) {
  (void)state;
  sabre_fp_traps_on();
  for (int variant = 0; variant < 4; variant++) {
    struct sph_system s;
    fixture_lattice(&s, 16, 16, 0.01, 2.0, FIX_PERIODIC);
    struct sph_config cfg;
    fixture_config(&cfg);
    cfg.gravity[1] = -9.81;
    cfg.gravity_correction = variant; /* none, linear, local, local */
    cfg.diffusion = variant < 2 ? SPH_DIFFUSION_FERRARI : SPH_DIFFUSION_BREZZI;
    cfg.diffusion_speed = variant == 1 ? SPH_DSPEED_ETA : SPH_DSPEED_MAX;
    struct sph_solver sv;
    sph_solver_init(&sv, &cfg, &s, NULL, NULL);
    sph_system_free(&s);
    jitter(&sv, 7, 0.1, 0.0, 0.02);
    sph_nbrs_build(&sv.nb, &sv.sys, 0.2 * sv.sys.h);
    sph_nbrs_gamma(&sv.nb, &sv.sys, &sv.kernel);
    sph_solver_sync(&sv);
    sph_solver_boundary_values(&sv);
    sph_solver_forces(&sv);
    const struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
    double sum = 0.0, mag = 0.0;
    for (size_t a = 0; a < f->n; a++) {
      sum += f->mass[a] / f->rho[a] * sv.diff[a];
      mag += fabs(f->mass[a] / f->rho[a] * sv.diff[a]);
    }
    print_message("variant %d: sum V D = %.3e of %.3e\n", variant, sum, mag);
    assert_true(mag > 0.0);
    assert_abs(sum, 0.0, 1e-13 * mag);
    sph_solver_free(&sv);
  }
}

/* Random smooth-ish fields per kind. */
static void random_fields(const struct sph_solver *sv, uint64_t seed, double *f[SPH_NKINDS],
                          double *B[SPH_NKINDS][3], int channel) {
  struct sabre_rng rng;
  sabre_rng_seed(&rng, seed);
  for (int k = 0; k < SPH_NKINDS; k++) {
    size_t n = sv->sys.part[k].n + 1;
    f[k] = calloc(n, sizeof(double));
    for (int c = 0; c < 3; c++) B[k][c] = calloc(n, sizeof(double));
    for (size_t i = 0; i < sv->sys.part[k].n; i++) {
      const double x = sv->sys.part[k].x[0][i], y = sv->sys.part[k].x[1][i];
      if (channel) { /* f = 1 + y, B = (sin 2πx/L, y): B·n ≠ 0 on the top wall only */
        const double L = sv->sys.domain.hi[0];
        f[k][i] = 1.0 + y;
        B[k][0][i] = sin(2 * 3.141592653589793 * x / L);
        B[k][1][i] = y;
      } else {
        f[k][i] = sabre_rng_uniform(&rng, -1.0, 1.0);
        B[k][0][i] = sabre_rng_uniform(&rng, -1.0, 1.0);
        B[k][1][i] = sabre_rng_uniform(&rng, -1.0, 1.0);
      }
    }
  }
}

static void free_fields(double *f[SPH_NKINDS], double *B[SPH_NKINDS][3]) {
  for (int k = 0; k < SPH_NKINDS; k++) {
    free(f[k]);
    for (int c = 0; c < 3; c++) free(B[k][c]);
  }
}

static void test_skew_adjoint(void **state) {
  (void)state;
  sabre_fp_traps_on();
  /* Without walls: zero to round-off for k = 0, 1/2, 1, with random fields and densities. */
  const double ks[3] = {0.0, 0.5, 1.0};
  for (int i = 0; i < 3; i++) {
    struct sph_system s;
    fixture_lattice(&s, 16, 16, 0.01, 2.0, FIX_PERIODIC);
    struct sph_config cfg;
    fixture_config(&cfg);
    cfg.grad_k = ks[i];
    struct sph_solver sv;
    sph_solver_init(&sv, &cfg, &s, NULL, NULL);
    sph_system_free(&s);
    jitter(&sv, 99, 0.2, 0.0, 0.05);
    sph_nbrs_build(&sv.nb, &sv.sys, 0.2 * sv.sys.h);
    sph_nbrs_gamma(&sv.nb, &sv.sys, &sv.kernel);
    double *f[SPH_NKINDS], *B[SPH_NKINDS][3];
    random_fields(&sv, 5, f, B, 0);
    double sa =
        sph_skew_adjoint_defect(&sv, (const double *const *)f, (const double *const(*)[3])B);
    /* scale: the same sum with |·| on each product */
    const struct sph_op op = {&sv.sys, &sv.kernel, &sv.nb, 0};
    double scale = 0.0;
    const struct sph_parts *fl = &sv.sys.part[SPH_KIND_FLUID];
    for (size_t a = 0; a < fl->n; a++) {
      double g[3];
      sph_op_grad(&op, ks[i], (const double *const *)f, a, g);
      double div = sph_op_div(&op, ks[i], (const double *const(*)[3])B, a);
      scale += fl->mass[a] / fl->rho[a] *
               (fabs(g[0] * B[0][0][a]) + fabs(g[1] * B[0][1][a]) + fabs(f[0][a] * div));
    }
    print_message("no walls, k=%.1f: SA = %.3e (scale %.3e)\n", ks[i], sa, scale);
    assert_true(scale > 0.1);
    assert_abs(sa, 0.0, 1e-13 * scale);
    free_fields(f, B);
    sph_solver_free(&sv);
  }
  /* With walls: measured, against −∮ f B·n dS = (1 + H) H L (top wall, n = −e_y, B·n = −H). */
  double rel[2];
  for (int r = 0; r < 2; r++) {
    int n = 24 * (r + 1);
    struct sph_system s;
    fixture_lattice(&s, n, n, 1.0 / n, 2.0, FIX_CHANNEL);
    struct sph_config cfg;
    fixture_config(&cfg);
    struct sph_solver sv;
    sph_solver_init(&sv, &cfg, &s, NULL, NULL);
    sph_system_free(&s);
    double *f[SPH_NKINDS], *B[SPH_NKINDS][3];
    random_fields(&sv, 5, f, B, 1);
    double sa =
        sph_skew_adjoint_defect(&sv, (const double *const *)f, (const double *const(*)[3])B);
    const double H = sv.sys.domain.hi[1], L = sv.sys.domain.hi[0];
    const double exact = (1.0 + H) * H * L;
    rel[r] = fabs(sa - exact) / exact;
    print_message("channel %dx%d: SA = %.6f, -int f B.n = %.6f (rel. diff %.3e)\n", n, n, sa, exact,
                  rel[r]);
    free_fields(f, B);
    sph_solver_free(&sv);
  }
  /* Not skew-adjoint with walls (M §3.1), but close to M(27)'s boundary term; at fixed h/Δr the
   * gap (3.7–3.8 % here, the zeroth-order defect of test_operators) does not shrink. */
  for (int r = 0; r < 2; r++) assert_true(rel[r] > 1e-3 && rel[r] < 0.06);
}

static void test_vertex_masses(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_system s;
  fixture_lattice(&s, 24, 12, 0.01, 2.0, FIX_CHANNEL);
  struct sph_config cfg;
  fixture_config(&cfg);
  struct sph_solver sv;
  sph_solver_init(&sv, &cfg, &s, NULL, NULL);
  sph_system_free(&s);
  /* Σ_b m_b w_ab / γ_a over F ∪ V against ρ0, before and after the least-squares vertex masses. */
  const struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID], *v = &sv.sys.part[SPH_KIND_VERTEX];
  double err_v = 0.0, err_0 = 0.0;
  for (size_t a = 0; a < f->n; a++) {
    double sf = f->mass[a] * sph_kernel_w(&sv.kernel, 0.0), sv_ = 0.0;
    for (size_t b = 0; b < f->n; b++) {
      double d[3];
      sph_domain_delta(&sv.sys.domain, (double[]){f->x[0][b], f->x[1][b], 0},
                       (double[]){f->x[0][a], f->x[1][a], 0}, d);
      if (b != a) sf += f->mass[b] * sph_kernel_w(&sv.kernel, hypot(d[0], d[1]));
    }
    for (size_t b = 0; b < v->n; b++) {
      double d[3];
      sph_domain_delta(&sv.sys.domain, (double[]){v->x[0][b], v->x[1][b], 0},
                       (double[]){f->x[0][a], f->x[1][a], 0}, d);
      sv_ += v->mass[b] * sph_kernel_w(&sv.kernel, hypot(d[0], d[1]));
    }
    err_0 = fmax(err_0, fabs(sf / f->gamma[a] / cfg.rho0 - 1.0));
    err_v = fmax(err_v, fabs((sf + sv_) / f->gamma[a] / cfg.rho0 - 1.0));
  }
  print_message("summation density error: fluid only %.3e, with vertex masses %.3e\n", err_0,
                err_v);
  assert_true(err_v < 0.5 * err_0);
  assert_true(err_v < 6e-3);
  sph_solver_free(&sv);
}

/* numerics.wall_vertex_mass: density: in a channel compressed along x (ρ = ρ0 (1 + 10⁻³ cos kx)),
 * one step gives every wall vertex the mass V_v ρ_v of its density at the start of the step (the
 * same bits), and the start state of the step's time summation, ρ_a^n, gains Σ_v Δm_v w(r_av)/γ_a,
 * checked against a brute-force sum over every vertex; the diagnostics' mass, which counts the
 * wall vertices at their set-up masses, stays the same. */
static void test_wall_vertex_mass_density(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_system s;
  const double dr = 0.01;
  fixture_lattice_offset(&s, 24, 12, dr, 2.0, FIX_CHANNEL, 1.0); /* first rows Δr from the walls */
  struct sph_config cfg;
  fixture_config(&cfg);
  cfg.diffusion = SPH_DIFFUSION_NONE;
  cfg.wall_vertex_mass_density = 1;
  struct sph_solver sv;
  sph_solver_init(&sv, &cfg, &s, NULL, NULL);
  sph_system_free(&s);
  struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
  const struct sph_parts *v = &sv.sys.part[SPH_KIND_VERTEX];
  const double L = sv.sys.domain.hi[0] - sv.sys.domain.lo[0];
  for (size_t a = 0; a < f->n; a++)
    f->rho[a] = cfg.rho0 * (1.0 + 1e-3 * cos(2.0 * 3.14159265358979323846 * f->x[0][a] / L));
  sph_solver_sync(&sv);
  sph_solver_evaluate(&sv);
  const size_t n = f->n, nv = v->n;
  double *rho_v = malloc(nv * sizeof *rho_v), *m0 = malloc(nv * sizeof *m0);
  double *rho_a = malloc(n * sizeof *rho_a), *gam = malloc(n * sizeof *gam);
  double(*x0)[2] = malloc(n * sizeof *x0);
  for (size_t i = 0; i < nv; i++) {
    rho_v[i] = v->rho[i];
    m0[i] = v->mass[i];
    if (!(v->volume[i] > 0.0 && v->wall_mass[i] == v->mass[i]))
      fail_msg("vertex %zu: volume %g, wall mass %g, mass %g", i, v->volume[i], v->wall_mass[i],
               v->mass[i]);
  }
  for (size_t a = 0; a < n; a++) {
    rho_a[a] = f->rho[a];
    gam[a] = f->gamma[a];
    x0[a][0] = f->x[0][a];
    x0[a][1] = f->x[1][a];
  }
  struct sph_diagnostics d0, d1;
  sph_solver_diagnostics(&sv, &d0);
  char msg[512];
  assert_int_equal(sph_solver_step(&sv, INFINITY, msg, sizeof msg), 0);
  sph_solver_diagnostics(&sv, &d1);
  assert_true(d1.mass == d0.mass); /* the wall layer's compression moves no mass */
  double dm_max = 0.0, drho_max = 0.0, err = 0.0;
  for (size_t i = 0; i < nv; i++) {
    assert_true(v->mass[i] == v->volume[i] * rho_v[i]);
    dm_max = fmax(dm_max, fabs(v->mass[i] / m0[i] - 1.0));
  }
  for (size_t a = 0; a < n; a++) {
    double sum = 0.0;
    for (size_t b = 0; b < nv; b++) {
      double d[3];
      sph_domain_delta(&sv.sys.domain, (double[]){v->x[0][b], v->x[1][b], 0},
                       (double[]){x0[a][0], x0[a][1], 0}, d);
      sum += (v->mass[b] - m0[b]) * sph_kernel_w(&sv.kernel, hypot(d[0], d[1]));
    }
    const double want = rho_a[a] + sum / gam[a];
    drho_max = fmax(drho_max, fabs(sum / gam[a]) / cfg.rho0);
    err = fmax(err, fabs(sv.rho_n[a] - want) / cfg.rho0);
  }
  print_message(
      "wall vertex masses follow rho_v: largest change %.3e, largest rho^n change %.3e "
      "rho0, against brute force %.2e\n",
      dm_max, drho_max, err);
  assert_true(dm_max > 5e-4 && dm_max < 2e-3); /* the wall layer compressed with the fluid */
  assert_true(drho_max > 1e-5);
  assert_true(err < 1e-14);
  free(rho_v);
  free(m0);
  free(rho_a);
  free(gam);
  free(x0);
  sph_solver_free(&sv);
}

/* numerics.lone_particle: a particle with no other fluid within its support (a droplet) takes no
 * tension and does not stop the run on the density band's lower bound; one inside the pool and
 * one on its free surface keep p(ρ) < 0 (their kernels hold fluid fractions of about 1 and 0.69).
 * With the default (eos) the droplet keeps p(ρ) and stops the run. */
#define LONE_CASE                                              \
  "geometry:\n"                                                \
  "  dimension: 2\n"                                           \
  "  dr: 0.01\n"                                               \
  "  first_row: 1\n"                                           \
  "  walls: [{type: box, lo: [0, 0], hi: [0.4, 0.2]}]\n"       \
  "  fluid: [{type: box, lo: [0, 0], hi: [0.1, 0.05]},\n"      \
  "          {type: box, lo: [0.3, 0.1], hi: [0.31, 0.11]}]\n" \
  "fluid: {rho0: 1000, c0: 20}\n"                              \
  "time: {end: 1}\n"
static void lone_run(const char *extra, double *p_lone, double *p_pool, double *p_surf, int *rc,
                     char *msg, size_t msglen) {
  char text[2048];
  snprintf(text, sizeof text, "%s%s", LONE_CASE, extra);
  struct sph_solver *sv = fixture_solver_from_case(text);
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  size_t lone = f->n, pool = f->n, surf = f->n;
  double top = 0.0;
  for (size_t a = 0; a < f->n; a++)
    if (f->x[0][a] < 0.2) top = fmax(top, f->x[1][a]);
  for (size_t a = 0; a < f->n; a++) {
    if (f->x[0][a] > 0.2) {
      assert_true(lone == f->n); /* one particle in the second box */
      lone = a;
    } else if (fabs(f->x[0][a] - 0.05) < 0.006 && fabs(f->x[1][a] - 0.025) < 0.006) {
      pool = a;
    }
    if (f->x[1][a] == top && fabs(f->x[0][a] - 0.05) < 0.006) surf = a; /* the free surface */
  }
  assert_true(lone < f->n && pool < f->n && surf < f->n);
  f->rho[lone] = 0.6 * 1000.0;
  f->rho[pool] = 0.999 * 1000.0;
  f->rho[surf] = 0.999 * 1000.0;
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
  *p_lone = f->p[lone];
  *p_pool = f->p[pool];
  *p_surf = f->p[surf];
  f->rho[lone] = 0.4 * 1000.0; /* below the band's 0.5 */
  sph_solver_sync(sv);
  *rc = sph_solver_step(sv, INFINITY, msg, msglen);
  fixture_solver_destroy(sv);
}

static void test_lone_particle(void **state) {
  (void)state;
  sabre_fp_traps_on();
  double pl, pp, ps;
  int rc;
  char msg[512];
  lone_run("numerics: {lone_particle: ambient}\n", &pl, &pp, &ps, &rc, msg, sizeof msg);
  print_message("ambient: droplet p = %g Pa, pool p = %g, surface p = %g Pa, step rc %d\n", pl, pp,
                ps, rc);
  assert_true(pl == 0.0);
  assert_true(pp < -10.0 && ps < -10.0);
  assert_int_equal(rc, 0);
  lone_run("", &pl, &pp, &ps, &rc, msg, sizeof msg);
  print_message("eos: droplet p = %g Pa, pool p = %g, surface p = %g Pa, step rc %d: %s\n", pl, pp,
                ps, rc, msg);
  assert_true(pl < -1e4);
  assert_true(pp < -10.0 && ps < -10.0);
  assert_int_equal(rc, -1);
  assert_non_null(strstr(msg, "density outside"));
}

static void test_density_band_stop(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_system s;
  fixture_lattice(&s, 16, 16, 0.01, 2.0, FIX_PERIODIC);
  struct sph_config cfg;
  fixture_config(&cfg);
  cfg.density_band[1] = 1.001;
  struct sph_solver sv;
  sph_solver_init(&sv, &cfg, &s, NULL, NULL);
  sph_system_free(&s);
  sv.sys.part[SPH_KIND_FLUID].rho[37] *= 1.01;
  char msg[512];
  assert_int_equal(sph_solver_step(&sv, INFINITY, msg, sizeof msg), -1);
  print_message("%s\n", msg);
  assert_non_null(strstr(msg, "density outside"));
  assert_non_null(strstr(msg, "step 1"));
  sph_solver_free(&sv);
}

/* The predictor–corrector is second order in time: an acoustic wave in a periodic box (viscous,
 * with diffusion) integrated to the same time with Δt, Δt/2, Δt/4 (Δt set by dt_max): successive
 * differences of the positions and velocities shrink by ≈ 4. */
static void run_fixed(struct sph_solver *sv, int nsteps, double T) {
  struct sph_system s;
  fixture_lattice(&s, 12, 12, 0.01, 2.0, FIX_PERIODIC);
  struct sph_config cfg;
  fixture_config(&cfg);
  cfg.nu = 1e-4;
  cfg.dt_max = T / nsteps;
  cfg.cfl = 1.0; /* let dt_max set Δt */
  sph_solver_init(sv, &cfg, &s, NULL, NULL);
  sph_system_free(&s);
  struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < f->n; a++) {
    f->v[0][a] = 0.3 * sin(2 * 3.141592653589793 * f->x[1][a] / 0.12);
    f->v[1][a] = 0.2 * sin(2 * 3.141592653589793 * f->x[0][a] / 0.12);
  }
  char msg[512];
  for (int n = 0; n < nsteps; n++) {
    assert_int_equal(sph_solver_step(sv, T - sv->time, msg, sizeof msg), 0);
    assert_true(sv->dt == T / nsteps || n == nsteps - 1);
  }
  assert_abs(sv->time, T, 1e-15);
}

static double state_diff(const struct sph_solver *a, const struct sph_solver *b) {
  const struct sph_parts *fa = &a->sys.part[SPH_KIND_FLUID], *fb = &b->sys.part[SPH_KIND_FLUID];
  double d = 0.0;
  for (size_t i = 0; i < fa->n; i++)
    for (int c = 0; c < 2; c++) {
      double dx[3];
      sph_domain_delta(&a->sys.domain, (double[]){fa->x[0][i], fa->x[1][i], 0},
                       (double[]){fb->x[0][i], fb->x[1][i], 0}, dx);
      d = fmax(d, fabs(dx[c]) / 0.01 + fabs(fa->v[c][i] - fb->v[c][i]) / 0.3);
    }
  return d;
}

static void test_time_order(void **state) {
  (void)state;
  sabre_fp_traps_on();
  const double T = 4e-3; /* 20, 40, 80 steps: 0.2 to 0.05 h/c0 per step; measured ratio 4.00 */
  struct sph_solver s1, s2, s4;
  run_fixed(&s1, 20, T);
  run_fixed(&s2, 40, T);
  run_fixed(&s4, 80, T);
  double e1 = state_diff(&s1, &s2), e2 = state_diff(&s2, &s4);
  print_message("differences %.3e, %.3e: ratio %.2f\n", e1, e2, e1 / e2);
  assert_true(e1 > 1e-8 && e1 / e2 > 3.5 && e1 / e2 < 5.5);
  sph_solver_free(&s1);
  sph_solver_free(&s2);
  sph_solver_free(&s4);
}

/* The dynamic γ, M(4) (trapezoidal rule), agrees with the closed form: fluid moving obliquely
 * towards the floor of a channel; the gap max|γ_dyn − γ(r)| after the same time shrinks by ≈ 4
 * when Δt halves. */
static double gamma_gap(int nsteps) {
  struct sph_system s;
  fixture_lattice(&s, 16, 10, 0.01, 2.0, FIX_CHANNEL);
  struct sph_config cfg;
  fixture_config(&cfg);
  cfg.gamma_dynamic = 1;
  cfg.cfl = 1.0;
  const double T = 6e-3;
  cfg.dt_max = T / nsteps;
  struct sph_solver sv;
  sph_solver_init(&sv, &cfg, &s, NULL, NULL);
  sph_system_free(&s);
  struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < f->n; a++) {
    f->v[0][a] = 0.4;
    f->v[1][a] = -0.3 * sin(3.141592653589793 * f->x[1][a] / 0.1);
  }
  char msg[512];
  for (int n = 0; n < nsteps; n++)
    assert_int_equal(sph_solver_step(&sv, T - sv.time, msg, sizeof msg), 0);
  double *dyn = malloc(f->n * sizeof *dyn), gap = 0.0, moved = 0.0;
  memcpy(dyn, f->gamma, f->n * sizeof *dyn);
  sph_nbrs_gamma(&sv.nb, &sv.sys, &sv.kernel); /* closed form at the final positions */
  for (size_t a = 0; a < f->n; a++) {
    gap = fmax(gap, fabs(dyn[a] - f->gamma[a]));
    moved = fmax(moved, fabs(f->gamma[a] - sv.gamma_n[a]));
  }
  print_message(
      "%d steps: max |gamma_dyn - gamma| = %.3e (gamma changed by up to %.3e over the "
      "last step)\n",
      nsteps, gap, moved);
  free(dyn);
  sph_solver_free(&sv);
  return gap;
}

static void test_gamma_dynamic(void **state) {
  (void)state;
  sabre_fp_traps_on();
  double g1 = gamma_gap(10), g2 = gamma_gap(20);
  assert_true(g1 > 0.0 && g1 < 1e-3 && g1 / g2 > 3.0 && g1 / g2 < 5.5);
}

/* Laminar viscosity with the wall shear stress (J 8–9, M 19–20): plane Poiseuille flow driven by a
 * body force g_x between the walls of a periodic channel reaches u(y) = g y (H − y)/(2ν) (measured:
 * 1.1 % of u_max at steady state, 0.7 % with the first row at dr/2). */
static void test_poiseuille(void **state) {
  (void)state;
  sabre_fp_traps_on();
  {
    struct sph_system s;
    const double dr = 0.01, y0 = 1.0; /* first row at dr (docs/sph-solver.md §7) */
    fixture_lattice_offset(&s, 10, 10, dr, 2.0, FIX_CHANNEL, y0);
    struct sph_config cfg;
    fixture_config(&cfg);
    const double H = s.domain.hi[1], nu = 0.01, g = 1.0, umax = g * H * H / (8 * nu);
    cfg.nu = nu;
    cfg.gravity[0] = g;
    cfg.c0 = 10 * umax;
    struct sph_solver sv;
    sph_solver_init(&sv, &cfg, &s, NULL, NULL);
    sph_system_free(&s);
    char msg[512];
    while (sv.time < 0.6 * H * H / nu) /* the slowest mode has decayed to e^(-0.6 π²) */
      assert_int_equal(sph_solver_step(&sv, INFINITY, msg, sizeof msg), 0);
    const struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
    double err = 0.0;
    for (size_t a = 0; a < f->n; a++) {
      const double y = f->x[1][a], exact = g * y * (H - y) / (2 * nu);
      err = fmax(err, fabs(f->v[0][a] - exact) / umax);
    }
    print_message(
        "Poiseuille, first row at %.1f dr, H = %g m: max |u - u_exact| / u_max = %.3e "
        "(%ld steps)\n",
        y0, H, err, sv.step);
    assert_true(err < 0.03);
    sph_solver_free(&sv);
  }
}

/* Vertices of a side wall above the free surface: the hydrostatic correction must not give them a
 * negative pressure (it would suck the fluid up the wall); below the surface it gives ρ g depth. */
static void test_vertex_above_surface(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_system s;
  const double dr = 0.01, H = 0.105; /* rows at y = dr ... 0.1, surface dr/2 above the top row */
  fixture_tank(&s, 0.2, 0.2, dr, 19, 10);
  struct sph_config cfg;
  fixture_config(&cfg);
  cfg.gravity[1] = -9.81;
  cfg.hydrostatic = 1;
  cfg.free_surface = H;
  struct sph_solver sv;
  sph_solver_init(&sv, &cfg, &s, NULL, NULL);
  sph_system_free(&s);
  const struct sph_parts *v = &sv.sys.part[SPH_KIND_VERTEX];
  int above = 0;
  for (size_t i = 0; i < v->n; i++) {
    const double x = v->x[0][i], y = v->x[1][i], p = sv.sys.part[SPH_KIND_VERTEX].p[i];
    if (y > H && y < H + 4 * dr && (x == 0.0 || x == 0.2)) {
      assert_true(p >= 0.0);
      above++;
    } else if (y < H - 2 * dr && y > 0.0 && (x == 0.0 || x == 0.2)) {
      assert_rel(p, 1000 * 9.81 * (H - y), 0.03);
    }
  }
  assert_true(above >= 6);
  sph_solver_free(&sv);
}

/* Hydrostatic water at rest: the Shepard vertex pressure with the hydrostatic correction reads the
 * floor pressure, and the floor force (segment pressure integral) carries the column's weight. */
static void test_hydrostatic_floor(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_system s;
  const int nx = 16, ny = 24;
  const double dr = 0.02;
  fixture_lattice(&s, nx, ny, dr, 2.0, FIX_CHANNEL);
  struct sph_config cfg;
  fixture_config(&cfg);
  cfg.gravity[1] = -9.81;
  cfg.hydrostatic = 1;
  cfg.nforces = 1;
  snprintf(cfg.forces[0].name, sizeof cfg.forces[0].name, "floor");
  cfg.forces[0].wall = 0;
  cfg.forces[0].nedges = 1;
  cfg.forces[0].edges[0] = 1;
  const struct sph_parts *sg = &s.part[SPH_KIND_SEGMENT];
  int *wall = calloc(sg->n + 1, sizeof *wall);
  long *edge = calloc(sg->n + 1, sizeof *edge);
  for (size_t j = 0; j < sg->n; j++) edge[j] = sg->normal[1][j] > 0 ? 1 : 3; /* box edge numbers */
  struct sph_solver sv;
  sph_solver_init(&sv, &cfg, &s, wall, edge);
  sph_system_free(&s);
  free(wall);
  free(edge);
  const double H = ny * dr,
               p_floor = rmn_eos_pressure(&sv.eos, sv.sys.part[SPH_KIND_FLUID].rho[0]) +
                         0.5 * dr * 9.81 * sv.sys.part[SPH_KIND_FLUID].rho[0];
  const struct sph_parts *v = &sv.sys.part[SPH_KIND_VERTEX];
  for (size_t i = 0; i < v->n; i++)
    if (v->x[1][i] < 0.5 * dr) assert_rel(sv.sys.part[SPH_KIND_VERTEX].p[i], p_floor, 2e-3);
  sph_solver_evaluate(&sv);
  double f[SPH_MAX_FORCE_GROUPS][3];
  sph_solver_wall_forces(&sv, f);
  double weight = 0.0;
  const struct sph_parts *fl = &sv.sys.part[SPH_KIND_FLUID];
  for (size_t a = 0; a < fl->n; a++) weight += fl->mass[a] * 9.81;
  print_message("floor force %.6g N for a weight %.6g N (H = %g m)\n", -f[0][1], weight, H);
  assert_rel(-f[0][1], weight, 3e-3);
  assert_abs(f[0][0], 0.0, 1e-9 * weight);
  sph_solver_free(&sv);
}

/* Two particles put behind the floor are both counted and the lower index is named, with any
 * thread count; a non-finite velocity is reported by name too. */
static void test_escape_and_nan(void **state) {
  (void)state;
  for (int which = 0; which < 2; which++) {
    struct sph_system s;
    fixture_lattice(&s, 16, 8, 0.01, 2.0, FIX_CHANNEL);
    struct sph_config cfg;
    fixture_config(&cfg);
    struct sph_solver sv;
    sph_solver_init(&sv, &cfg, &s, NULL, NULL);
    sph_system_free(&s);
    struct sph_parts *f = &sv.sys.part[SPH_KIND_FLUID];
    if (which == 0) {
      sabre_fp_traps_on();
      /* below the floor y = 0: index 3 of the first row and index 100 of the seventh, at
       * different x (3.5 Δr and 4.5 Δr) */
      f->x[1][3] = -0.3 * sv.sys.dr;
      f->x[1][100] = -0.415 * sv.sys.dr;
      sph_nbrs_build(&sv.nb, &sv.sys, 0.2 * sv.sys.h);
#ifdef _OPENMP
      const int threads = omp_get_max_threads();
      for (int t = 1; t <= 3; t++) {
        omp_set_num_threads(t);
#endif
        sph_nbrs_gamma(&sv.nb, &sv.sys, &sv.kernel);
        assert_int_equal(sv.nb.escaped, 3);
        assert_int_equal(sv.nb.nescaped, 2);
#ifdef _OPENMP
      }
      omp_set_num_threads(threads);
#endif
      f->x[1][3] = 0.5 * sv.sys.dr;
      sph_nbrs_gamma(&sv.nb, &sv.sys, &sv.kernel);
      assert_int_equal(sv.nb.escaped, 100);
      assert_int_equal(sv.nb.nescaped, 1);
      f->x[1][100] = 6.5 * sv.sys.dr;
      sph_nbrs_gamma(&sv.nb, &sv.sys, &sv.kernel);
      assert_int_equal(sv.nb.escaped, -1);
      assert_int_equal(sv.nb.nescaped, 0);
      f->x[1][3] = -0.3 * sv.sys.dr;
      f->x[1][100] = -0.415 * sv.sys.dr;
    } else {
      /* The NaN must reach the check, not trap: traps off, and on this thread only (OpenMP workers
       * keep the trapping environment they were created with). */
      sabre_fp_traps_off();
#ifdef _OPENMP
      omp_set_num_threads(1);
#endif
      f->v[0][5] = NAN;
    }
    char msg[512];
    assert_int_equal(sph_solver_step(&sv, INFINITY, msg, sizeof msg), -1);
    print_message("%s\n", msg);
    assert_non_null(strstr(msg, "step 1"));
    assert_non_null(strstr(msg, which ? "non-finite" : "through a wall"));
    assert_non_null(strstr(msg, which ? "id " : "(index 3)"));
    if (which == 0) { /* both, and only they (the NaN spreads to every neighbour within a step) */
      char count[64];
      snprintf(count, sizeof count, "; 2 of %zu fluid particles fail", f->n);
      assert_non_null(strstr(msg, count));
    }
    sph_solver_free(&sv);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_momentum_periodic),
      cmocka_unit_test(test_diffusion_volume),
      cmocka_unit_test(test_skew_adjoint),
      cmocka_unit_test(test_vertex_masses),
      cmocka_unit_test(test_wall_vertex_mass_density),
      cmocka_unit_test(test_density_band_stop),
      cmocka_unit_test(test_lone_particle),
      cmocka_unit_test(test_escape_and_nan),
      cmocka_unit_test(test_hydrostatic_floor),
      cmocka_unit_test(test_time_order),
      cmocka_unit_test(test_gamma_dynamic),
      cmocka_unit_test(test_poiseuille),
      cmocka_unit_test(test_vertex_above_surface),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
