/* Riemann benchmark: boundary solves per second (expansion and shock branches, imposed pressure
 * and imposed velocity) and exact Riemann solves per second, on one core. Inputs are drawn from a
 * seeded generator around water at rest (ξ = 7), so branch and iteration counts are realistic. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "sabre/riemann.h"

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static unsigned long long rng_state = 0x2545F4914F6CDD1DULL;
static double uniform(double lo, double hi) {
  rng_state ^= rng_state << 13;
  rng_state ^= rng_state >> 7;
  rng_state ^= rng_state << 17;
  return lo + (hi - lo) * (double)(rng_state >> 11) * 0x1.0p-53;
}

enum { N = 4096 };

struct sample {
  double rho, un, value;
};

static double bench_boundary(const struct rmn_eos *eos, const struct rmn_params *par,
                             struct rmn_workspace *ws, enum rmn_imposed imposed, enum rmn_wave want,
                             const struct sample *s, double seconds) {
  double t0 = now(), t;
  long count = 0;
  double sink = 0.0;
  do {
    for (int i = 0; i < N; ++i) {
      struct rmn_normal_state out;
      if (rmn_boundary_solve_normal(eos, par, ws, s[i].rho, s[i].un, imposed, s[i].value, &out) !=
              RMN_SUCCESS ||
          out.wave != want) {
        fprintf(stderr, "bench-riemann: unexpected solver result\n");
        exit(EXIT_FAILURE);
      }
      sink += out.rho;
    }
    count += N;
    t = now();
  } while (t - t0 < seconds);
  if (sink == 42.0) puts("");
  return (double)count / (t - t0);
}

int main(void) {
  gsl_set_error_handler_off();
  struct rmn_eos eos;
  rmn_eos_init(&eos, 1000.0, 20.0, 7.0);
  struct rmn_params par;
  rmn_params_default(&par);
  struct rmn_workspace *ws = rmn_workspace_alloc();
  if (!ws) return EXIT_FAILURE;
  static struct sample expand_p[N], shock_p[N], expand_u[N], shock_u[N], lefts[N], rights[N];
  for (int i = 0; i < N; ++i) {
    double rho = 1000.0 * uniform(0.98, 1.02), un = uniform(-2.0, 2.0);
    double p = rmn_eos_pressure(&eos, rho);
    expand_p[i] = (struct sample){rho, un, p - uniform(10.0, 5000.0)};
    shock_p[i] = (struct sample){rho, un, p + uniform(10.0, 5000.0)};
    expand_u[i] = (struct sample){rho, un, un - uniform(0.01, 1.0)};
    shock_u[i] = (struct sample){rho, un, un + uniform(0.01, 1.0)};
    lefts[i] = (struct sample){1000.0 * uniform(0.95, 1.05), uniform(-2.0, 2.0), 0.0};
    rights[i] = (struct sample){1000.0 * uniform(0.95, 1.05), uniform(-2.0, 2.0), 0.0};
  }
  const double seconds = 0.5;
  printf("riemann/ benchmark (one core, xi = 7, rho0 = 1000, c0 = 20, %.1f s per line)\n", seconds);
  printf("%-44s %14s\n", "case", "solves/s");
  printf(
      "%-44s %14.3e\n", "boundary, imposed pressure, expansion",
      bench_boundary(&eos, &par, ws, RMN_IMPOSE_PRESSURE, RMN_WAVE_EXPANSION, expand_p, seconds));
  printf("%-44s %14.3e\n", "boundary, imposed pressure, shock (Newton)",
         bench_boundary(&eos, &par, ws, RMN_IMPOSE_PRESSURE, RMN_WAVE_SHOCK, shock_p, seconds));
  printf(
      "%-44s %14.3e\n", "boundary, imposed velocity, expansion",
      bench_boundary(&eos, &par, ws, RMN_IMPOSE_VELOCITY, RMN_WAVE_EXPANSION, expand_u, seconds));
  printf("%-44s %14.3e\n", "boundary, imposed velocity, shock (Newton)",
         bench_boundary(&eos, &par, ws, RMN_IMPOSE_VELOCITY, RMN_WAVE_SHOCK, shock_u, seconds));
  {
    double t0 = now(), t, sink = 0.0;
    long count = 0;
    do {
      for (int i = 0; i < N; ++i) {
        struct rmn_exact sol;
        if (rmn_exact_solve(&eos, &par, ws, lefts[i].rho, lefts[i].un, rights[i].rho, rights[i].un,
                            &sol) != RMN_SUCCESS)
          return EXIT_FAILURE;
        sink += sol.rho_star;
      }
      count += N;
      t = now();
    } while (t - t0 < seconds);
    if (sink == 42.0) puts("");
    printf("%-44s %14.3e\n", "exact Riemann problem (random states)", (double)count / (t - t0));
  }
  {
    /* What the SPH calls every step: the batch over 3D segments (frame, normal problem,
     * tangential rules), half expansions and half shocks, imposed pressure. */
    static struct rmn_boundary_input in[N];
    static struct rmn_boundary_result res[N];
    for (int i = 0; i < N; ++i) {
      in[i] =
          (struct rmn_boundary_input){.normal = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)},
                                      .rho = expand_p[i].rho,
                                      .u = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)},
                                      .imposed = RMN_IMPOSE_PRESSURE,
                                      .value = i % 2 ? expand_p[i].value : shock_p[i].value};
    }
    double t0 = now(), t;
    long count = 0;
    do {
      if (rmn_boundary_solve_batch(&eos, &par, ws, 3, N, in, res, NULL) != RMN_SUCCESS)
        return EXIT_FAILURE;
      count += N;
      t = now();
    } while (t - t0 < seconds);
    printf("%-44s %14.3e\n", "batch, 3D segments, 50% shocks", (double)count / (t - t0));
  }
  rmn_workspace_free(ws);
  return 0;
}
