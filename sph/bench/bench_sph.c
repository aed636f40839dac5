/* Throughput of the whole solver step (lists, γ, boundary values, forces, predictor–corrector)
 * on a small 2D and a small 3D dam break, and a 2D channel with walls only or with an inlet and
 * an outlet (the cost of the open boundaries), through the solver API, with 1 and 2 threads:
 *
 *   particle-steps/s            = fluid particles × steps / wall seconds
 *   fluid–fluid interactions/s  = Σ over the steps of the ordered fluid–fluid pairs closer than
 *                                 2h at the end of the step / wall seconds
 *
 * (each step evaluates the forces twice, predictor and corrector, so a pair is visited about
 * twice per step and per operator; the figure counts it once). Set-up (meshing, γ, the vertex
 * layer fit) and the pair count are outside the timed region; each thread count starts from the
 * same initial state. The case files are inline and follow docs/sph-solver.md §7: the first fluid
 * row Δr from the walls, the free surface Δr/2 above the top row.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "sabre/common.h"
#include "sabre/sph.h"
#include "sabre/sph_solver.h"

struct bench_case {
  const char *name;
  const char *yaml;
  long steps;
};

/* 2D: a 0.5 m × 1 m column (25 × 50 particles) in a 2.2 m × 1.2 m tank, Δr = 0.02 m. */
static const char case_2d[] =
    "geometry:\n"
    "  dimension: 2\n"
    "  dr: 0.02\n"
    "  h_over_dr: 2\n"
    "  walls:\n"
    "    - {type: box, lo: [0, 0], hi: [2.2, 1.2]}\n"
    "  fluid:\n"
    "    - {type: box, lo: [0.01, 0.01], hi: [0.51, 1.01]}\n"
    "fluid: {rho0: 1000, c0: 40, nu: 1.0e-6}\n"
    "gravity: [0, -9.81]\n"
    "initial: {pressure: hydrostatic}\n"
    "time: {end: 10}\n";

/* 3D: a 0.2 m × 0.2 m × 0.3 m column across a 0.6 m × 0.2 m × 0.4 m box (10 × 9 × 15 particles,
 * the first rows Δr from the walls), Δr = 0.02 m, h = 1.3 Δr. */
static const char case_3d[] =
    "geometry:\n"
    "  dimension: 3\n"
    "  dr: 0.02\n"
    "  h_over_dr: 1.3\n"
    "  walls:\n"
    "    - {type: box, lo: [0, 0, 0], hi: [0.6, 0.2, 0.4]}\n"
    "  fluid:\n"
    "    - {type: box, lo: [0.01, 0.01, 0.01], hi: [0.21, 0.21, 0.31]}\n"
    "fluid: {rho0: 1000, c0: 25, nu: 1.0e-6}\n"
    "gravity: [0, 0, -9.81]\n"
    "initial: {pressure: hydrostatic}\n"
    "time: {end: 10}\n";

/* 2D channel, 2 m × 0.4 m full of fluid (100 × 20 particles, Δr = 0.02 m, no gravity), flowing at
 * 0.2 m/s: closed (walls only, the fluid starts with the velocity and slides along the walls) and
 * open (the same box with a velocity inlet at x = 0 and an outlet at 0 Pa at x = 2 m: the boundary
 * problems, vertex masses, creation and deletion on top of the same particles and walls). */
static const char case_channel[] =
    "geometry:\n"
    "  dimension: 2\n"
    "  dr: 0.02\n"
    "  h_over_dr: 2\n"
    "  first_row: 1\n"
    "  walls:\n"
    "    - {type: box, lo: [0, 0], hi: [2, 0.4]%s}\n"
    "  fluid:\n"
    "    - {type: box, lo: [0, 0], hi: [2, 0.4]}\n"
    "fluid: {rho0: 1000, c0: 20}\n"
    "initial: {velocity: [0.2, 0]}\n"
    "time: {end: 10}\n"
    "%s";

/* Ordered fluid–fluid pairs closer than 2h, from the step's neighbour list (radius 2h + skin). */
static double count_pairs(const struct sph_solver *sv) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const struct sph_nlist *nl = &sv->nb.list[SPH_KIND_FLUID];
  const double r2 = 4.0 * sv->sys.h * sv->sys.h;
  double count = 0.0;
  for (size_t a = 0; a < nl->n && a < f->n; a++)
    for (size_t k = nl->offset[a]; k < nl->offset[a + 1]; k++) {
      const size_t b = nl->index[k];
      const double xa[3] = {f->x[0][a], f->x[1][a], f->x[2][a]};
      const double xb[3] = {f->x[0][b], f->x[1][b], f->x[2][b]};
      double dx[3];
      sph_domain_delta(&sv->sys.domain, xa, xb, dx);
      if (dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2] < r2) count += 1.0;
    }
  return count;
}

static struct sph_solver *setup(const struct bench_case *bc) {
  return bench_solver(bc->yaml, bc->name);
}

static void run(const struct bench_case *bc, int threads) {
  bench_set_threads(threads);
  struct sph_solver *sv = setup(bc);
  const size_t nfluid = sv->sys.part[SPH_KIND_FLUID].n;
  double wall = 0.0, pairs = 0.0;
  long steps = 0;
  for (; steps < bc->steps; steps++) {
    char msg[1024];
    double t0 = cmn_wall_time();
    int status = sph_solver_step(sv, INFINITY, msg, sizeof msg);
    wall += cmn_wall_time() - t0;
    if (status != 0) {
      fprintf(stderr, "bench-sph: %s: step failed: %s\n", bc->name, msg);
      break;
    }
    pairs += count_pairs(sv); /* pairs at the end of the step (the list still holds them) */
  }
  printf("| %-17s | %7d | %15zu | %5ld | %6.2f | %16.3e | %26.3e |\n", bc->name, threads, nfluid,
         steps, wall, (double)nfluid * (double)steps / wall, pairs / wall);
  fflush(stdout);
  sph_solver_free(sv);
  free(sv);
}

int main(void) {
  char closed[2048], open[2048];
  snprintf(closed, sizeof closed, case_channel, "", "");
  snprintf(open, sizeof open, case_channel, ", open: [x-, x+]",
           "open_boundaries:\n"
           "  - {name: inlet, wall: 0, faces: [x-], impose: velocity, normal_velocity: 0.2}\n"
           "  - {name: outlet, wall: 0, faces: [x+], impose: pressure, pressure: 0}\n");
  const struct bench_case cases[] = {
      {"2D dam break", case_2d, 200},
      {"3D dam break", case_3d, 20},
      {"2D channel, walls", closed, 200},
      {"2D channel, open", open, 200},
  };
  const int threads[] = {1, 2};
  printf(
      "bench-sph: solver steps of a small dam break and of a channel closed or open (t from 0; "
      "fixed step counts)\n");
  printf(
      "| case              | threads | fluid particles | steps | wall s | particle-steps/s | "
      "fluid-fluid interactions/s |\n");
  printf("|---|---|---|---|---|---|---|\n");
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    for (size_t t = 0; t < sizeof threads / sizeof threads[0]; t++) run(&cases[i], threads[t]);
  return 0;
}
