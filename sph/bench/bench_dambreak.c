/* The 3D dam break against an obstacle of DualSPHysics' CaseDambreak, run by SABRE's solver for a
 * fixed number of steps from t = 0, so that its speed can be set beside DualSPHysics' figures
 * (README.md "Performance"):
 *
 *   tank 1.6 × 0.67 m (x, y), water column 0.4 × 0.67 × 0.3 m at x = 0, a box obstacle
 *   0.12 × 0.12 × 0.45 m standing on the floor at x = 0.9–1.02 m, y = 0.24–0.36 m;
 *   c0 = 20 sqrt(g × 0.3 m) = 34.3 m/s as DualSPHysics; SABRE's own kernel (Wendland C2),
 *   h = 2Δr (DualSPHysics: cubic spline, h = sqrt(3) Δr, so about 1.5 times fewer neighbours),
 *   first fluid row Δr from the walls, Ferrari volume diffusion, ν = 10⁻⁶ m²/s.
 *
 * DualSPHysics' tank is open at the top (z = 0.4 m); SABRE's walls must be closed, so the tank
 * here has a lid at z = 0.5 m, above the obstacle (sph/bench/dambreak_tank.stl, written by
 * cases/sph/dam_break_3d_obstacle/make_tank_stl.py --tank 1.6,0.67,0.5 --obstacle
 * 0.9,1.02,0.24,0.36,0.45). The first steps from rest do not reach the lid; the lid adds vertices
 * and segments but no fluid particle.
 *
 * Each resolution also runs the same fluid with no walls (the column's box periodic in x, y and z,
 * uniform pressure, no gravity), the wall-free reference of the same particle count and h.
 *
 * Printed per case, resolution and thread count: fluid particles, vertices, segments, mean
 * neighbours of a fluid particle within 2h (fluid, vertex, segment), fluid particle-steps/s,
 * fluid–fluid interactions/s (pairs closer than 2h, counted once per step), the time per step split
 * into neighbour lists, wall integrals (γ, ∇γ_as), vertex values, the pair loops of the forces and
 * of the continuity, and the rest (integration, checks), and the peak resident memory per particle
 * (fluid + vertex + segment; dam break rows only), and the builds of the neighbour lists per step.
 * Set-up is not timed.
 *
 * usage: bench-dambreak [--dr LIST] [--steps LIST] [--threads LIST] [--rebuild MODE]
 *        (comma-separated; the defaults: Δr 0.025,0.012,0.0085 m with 20,6,3 steps; threads 1,2;
 *        MODE numerics.list_rebuild, when_needed (default) or every_step)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "bench_common.h"
#include "operators/pair.h"
#include "sabre/common.h"
#include "sabre/sph.h"
#include "sabre/sph_solver.h"

#define MAXLIST 8

static const char case_fmt[] =
    "geometry:\n"
    "  dimension: 3\n"
    "  dr: %.17g\n"
    "  h_over_dr: 2\n"
    "  first_row: 1\n"
    "  walls:\n"
    "    - {type: stl, file: dambreak_tank.stl, fluid: inside}\n"
    "  fluid:\n"
    "    - {type: box, lo: [0, 0, 0], hi: [0.4, 0.67, 0.3]}\n"
    "fluid: {rho0: 1000, c0: 34.31, xi: 7, nu: 1.0e-6}\n"
    "gravity: [0, 0, -9.81]\n"
    "initial: {pressure: hydrostatic}\n"
    "numerics: {diffusion: ferrari, list_rebuild: %s}\n"
    "time: {end: 1.5}\n";

/* The same fluid with no walls: the water column's box made periodic in x, y and z (0.65 m across
 * in y, so that the particle count is the dam break's at Δr = 0.025 m), at a uniform 1 kPa, no
 * gravity; the same kernel, h, c0, diffusion and viscosity. Its time per particle-step is the
 * wall-free reference of the "walls cost at most 1.5 times a wall-free periodic box". */
static const char periodic_fmt[] =
    "geometry:\n"
    "  dimension: 3\n"
    "  dr: %.17g\n"
    "  h_over_dr: 2\n"
    "  periodic: [x, y, z]\n"
    "  domain: {lo: [0, 0, 0], hi: [0.4, 0.65, 0.3]}\n"
    "  fluid:\n"
    "    - {type: box, lo: [0, 0, 0], hi: [0.4, 0.65, 0.3]}\n"
    "fluid: {rho0: 1000, c0: 34.31, xi: 7, nu: 1.0e-6}\n"
    "gravity: [0, 0, 0]\n"
    "initial: {pressure: '1000'}\n"
    "numerics: {diffusion: ferrari, list_rebuild: %s}\n"
    "time: {end: 1.5}\n";

static const char *rebuild = "when_needed";

static struct sph_solver *setup(double dr, int periodic) {
  char yaml[2048];
  snprintf(yaml, sizeof yaml, periodic ? periodic_fmt : case_fmt, dr, rebuild);
  return bench_solver(yaml, SABRE_BENCH_DIR "/casedambreak.yaml");
}

/* Mean neighbours of a fluid particle within 2h: fluid and vertex particles (closer than 2h) and
 * segments (in the list: within 2h of the segment). */
static void neighbours(const struct sph_solver *sv, double mean[3], double *ff_pairs) {
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  double count[3] = {0.0, 0.0, 0.0};
  for (int kind = SPH_KIND_FLUID; kind <= SPH_KIND_VERTEX; kind++) {
    const struct sph_nlist *nl = &sv->nb.list[kind];
    const struct sph_parts *pb = &sv->sys.part[kind];
    for (size_t a = 0; a < f->n; a++)
      for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
        struct sph_pair pr;
        if (sph_pair_eval(&sv->kernel, &sv->sys, f, a, pb, nl->index[q], &pr)) count[kind] += 1.0;
      }
  }
  const struct sph_nlist *ns = &sv->nb.list[SPH_KIND_SEGMENT];
  count[2] = (double)ns->offset[f->n];
  for (int k = 0; k < 3; k++) mean[k] = count[k] / (double)f->n;
  *ff_pairs = count[0];
}

static double peak_rss_bytes(void) {
  struct rusage ru;
  if (getrusage(RUSAGE_SELF, &ru) != 0) return NAN;
  return 1024.0 * (double)ru.ru_maxrss;
}

static void run(double dr, long steps, int threads, int periodic) {
  bench_set_threads(threads);
  struct sph_solver *sv = setup(dr, periodic);
  const struct sph_system *s = &sv->sys;
  const size_t nf = s->part[SPH_KIND_FLUID].n, nv = s->part[SPH_KIND_VERTEX].n,
               ns = s->part[SPH_KIND_SEGMENT].n;
  double mean[3], pairs = 0.0, ff;
  neighbours(sv, mean, &ff);
  for (int p = 0; p < SPH_NPHASES; p++) sv->timing[p] = 0.0;
  sv->list_builds = 0;
  long done = 0;
  for (; done < steps; done++) {
    char msg[1024];
    if (sph_solver_step(sv, INFINITY, msg, sizeof msg) != 0) {
      fprintf(stderr, "bench-dambreak: dr = %g m: step failed: %s\n", dr, msg);
      break;
    }
    double m[3];
    neighbours(sv, m, &ff);
    pairs += ff;
  }
  const double *t = sv->timing, wall = t[SPH_PHASE_STEP];
  const double rest = wall - t[SPH_PHASE_LISTS] - t[SPH_PHASE_WALLS] - t[SPH_PHASE_VERTEX] -
                      t[SPH_PHASE_FORCES] - t[SPH_PHASE_CONTINUITY];
  const double ms = done > 0 ? 1e3 / (double)done : NAN;
  /* The process's peak so far: that of the dam break run before a periodic box, so "-" there. */
  char peak[32] = "-";
  if (!periodic) snprintf(peak, sizeof peak, "%.0f", peak_rss_bytes() / (double)(nf + nv + ns));
  printf(
      "| %s | %6.4f | %d | %7zu | %6zu | %6zu | %3.0f / %3.0f / %3.0f | %9.3e | %9.3e | %8.1f | "
      "%6.1f | %6.1f | %6.1f | %6.1f | %6.1f | %6.1f | %5s | %4.2f |\n",
      periodic ? "periodic box" : "dam break", dr, threads, nf, nv, ns, mean[0], mean[1], mean[2],
      (double)nf * (double)done / wall, pairs / wall, wall * ms, t[SPH_PHASE_LISTS] * ms,
      t[SPH_PHASE_WALLS] * ms, t[SPH_PHASE_VERTEX] * ms, t[SPH_PHASE_FORCES] * ms,
      t[SPH_PHASE_CONTINUITY] * ms, rest * ms, peak, (double)sv->list_builds / (double)done);
  fflush(stdout);
  sph_solver_free(sv);
  free(sv);
}

/* Comma-separated list of positive numbers; exits 2 naming the option on a bad one. */
static int parse_list(const char *opt, const char *text, double *out) {
  int n = 0;
  const char *p = text;
  while (*p) {
    char *end;
    const double v = strtod(p, &end);
    if (end == p || !(v > 0.0) || !isfinite(v) || n == MAXLIST || (*end && *end != ',')) {
      fprintf(stderr,
              "bench-dambreak: %s: expected up to %d positive numbers separated by "
              "commas, got '%s'\n",
              opt, MAXLIST, text);
      exit(2);
    }
    out[n++] = v;
    p = *end ? end + 1 : end;
  }
  if (n == 0) {
    fprintf(stderr, "bench-dambreak: %s: empty list\n", opt);
    exit(2);
  }
  return n;
}

int main(int argc, char **argv) {
  double drs[MAXLIST] = {0.025, 0.012, 0.0085}, steps[MAXLIST] = {20, 6, 3}, thr[MAXLIST] = {1, 2};
  int ndr = 3, nsteps = 3, nthr = 2;
  for (int i = 1; i < argc; i++) {
    if (i + 1 >= argc) {
      fprintf(stderr, "bench-dambreak: %s needs a value (see the header of bench_dambreak.c)\n",
              argv[i]);
      return 2;
    }
    if (strcmp(argv[i], "--dr") == 0)
      ndr = parse_list(argv[i], argv[i + 1], drs);
    else if (strcmp(argv[i], "--steps") == 0)
      nsteps = parse_list(argv[i], argv[i + 1], steps);
    else if (strcmp(argv[i], "--threads") == 0)
      nthr = parse_list(argv[i], argv[i + 1], thr);
    else if (strcmp(argv[i], "--rebuild") == 0) {
      rebuild = argv[i + 1];
      if (strcmp(rebuild, "when_needed") != 0 && strcmp(rebuild, "every_step") != 0) {
        fprintf(stderr, "bench-dambreak: --rebuild: expected when_needed or every_step, got '%s'\n",
                rebuild);
        return 2;
      }
    } else {
      fprintf(stderr, "bench-dambreak: unknown option %s (--dr, --steps, --threads, --rebuild)\n",
              argv[i]);
      return 2;
    }
    i++;
  }
  printf(
      "bench-dambreak: DualSPHysics' CaseDambreak geometry, %s steps from t = 0, lists rebuilt %s "
      "(ms per step; walls = gamma and grad gamma_as; rest = integration and checks)\n",
      "fixed", rebuild);
  printf(
      "| case | dr m | thr | fluid | vertices | segments | neighbours F / V / S | fluid "
      "particle-steps/s | F-F interactions/s | ms/step | lists | walls | vertex | forces | "
      "continuity | rest | peak B/particle | list builds/step |\n");
  printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int i = 0; i < ndr; i++)
    for (int periodic = 0; periodic <= 1; periodic++)
      for (int t = 0; t < nthr; t++)
        run(drs[i], (long)steps[i < nsteps ? i : nsteps - 1], (int)thr[t], periodic);
  return 0;
}
