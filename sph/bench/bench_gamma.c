/*
 * γ / ∇γ evaluations per second (sph/src/walls/): one evaluation is gamma_term and ∇γ_as of one
 * element at one point (sph_gamma_element), with the point within the support of the element
 * (elements of size Δr = h/1.3 at random distances, as met in a neighbour loop). Also
 * sph_gamma_eval over a particle's wall neighbours (a plane wall meshed at Δr). Figures on stdout.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "sabre/sph_walls.h"

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint64_t state = 0x853c49e6748fea9bULL;
static double uniform(double lo, double hi) {
  state ^= state << 13;
  state ^= state >> 7;
  state ^= state << 17;
  return lo + (hi - lo) * (double)(state >> 11) * 0x1.0p-53;
}

enum { NE = 4096 };

static double bench_elements(int dim, double *checksum) {
  const double h = 0.013, dr = h / 1.3;
  struct sph_kernel k;
  sph_kernel_init(&k, dim, h);
  static struct sph_wall_element e[NE];
  static double a[NE][3];
  for (int i = 0; i < NE; i++) {
    for (int j = 0; j < 3; j++)
      for (int c = 0; c < 3; c++) e[i].x[j][c] = 0.0;
    e[i].x[0][0] = 0.0;
    e[i].x[1][0] = dr;
    if (dim == 3) {
      e[i].x[2][0] = uniform(0.0, dr);
      e[i].x[2][1] = dr;
    }
    e[i].normal[0] = e[i].normal[1] = e[i].normal[2] = 0.0;
    e[i].normal[dim - 1] = 1.0;
    a[i][0] = uniform(-1.5 * h, 1.5 * h);
    a[i][1] = dim == 2 ? uniform(0.0, 2.0 * h) : uniform(-1.5 * h, 1.5 * h);
    a[i][2] = dim == 3 ? uniform(0.0, 2.0 * h) : 0.0;
  }
  double sum = 0.0;
  long evals = 0;
  const double t0 = now();
  double t1 = t0;
  while (t1 - t0 < 0.5) {
    for (int i = 0; i < NE; i++) {
      double term, grad[3];
      sph_gamma_element(&k, a[i], &e[i], &term, grad);
      sum += term + grad[dim - 1];
    }
    evals += NE;
    t1 = now();
  }
  *checksum += sum;
  return (double)evals / (t1 - t0);
}

/* sph_gamma_eval at points above a plane wall meshed at Δr, passing the elements within 2h. */
static double bench_eval(int dim, double *checksum) {
  const double h = 0.013, dr = h / 1.3;
  struct sph_kernel k;
  sph_kernel_init(&k, dim, h);
  enum { M = 10 };
  static struct sph_wall_element e[2 * M * M];
  size_t n = 0;
  for (int i = 0; i < M; i++) {
    if (dim == 2) {
      struct sph_wall_element s = {{{(i - M / 2) * dr, 0, 0}, {(i + 1 - M / 2) * dr, 0, 0}},
                                   {0, 1, 0}};
      e[n++] = s;
      continue;
    }
    for (int j = 0; j < M; j++) {
      const double x0 = (i - M / 2) * dr, y0 = (j - M / 2) * dr;
      struct sph_wall_element t1 = {{{x0, y0, 0}, {x0 + dr, y0, 0}, {x0 + dr, y0 + dr, 0}},
                                    {0, 0, 1}};
      struct sph_wall_element t2 = {{{x0, y0, 0}, {x0 + dr, y0 + dr, 0}, {x0, y0 + dr, 0}},
                                    {0, 0, 1}};
      e[n++] = t1;
      e[n++] = t2;
    }
  }
  double sum = 0.0;
  long points = 0, pairs = 0;
  const double t0 = now();
  double t1 = t0;
  while (t1 - t0 < 0.5) {
    for (int i = 0; i < 1000; i++) {
      double a[3] = {uniform(-0.5 * dr, 0.5 * dr), 0.0, 0.0};
      if (dim == 2) a[1] = uniform(0.0, 2.0 * h);
      if (dim == 3) a[1] = uniform(-0.5 * dr, 0.5 * dr), a[2] = uniform(0.0, 2.0 * h);
      /* the elements within the support, as a neighbour search would give */
      struct sph_wall_element near[2 * M * M];
      size_t nn = 0;
      const double reach = 2.0 * h + 1.5 * dr; /* support + element size */
      for (size_t s = 0; s < n; s++) {
        double r2 = 0.0;
        for (int c = 0; c < 3; c++) r2 += (e[s].x[0][c] - a[c]) * (e[s].x[0][c] - a[c]);
        if (r2 < reach * reach) near[nn++] = e[s];
      }
      double gamma, g[3];
      if (sph_gamma_eval(&k, a, nn, near, &gamma, g) != 0) abort();
      sum += gamma;
      pairs += (long)nn;
    }
    points += 1000;
    t1 = now();
  }
  *checksum += sum;
  printf("  sph_gamma_eval %dD: %.3g points/s (%.1f elements per point, %.3g element terms/s)\n",
         dim, (double)points / (t1 - t0), (double)pairs / (double)points,
         (double)pairs / (t1 - t0));
  return (double)points / (t1 - t0);
}

int main(void) {
  double checksum = 0.0;
  printf("bench_gamma: closed-form γ / ∇γ_as of one element at one point (sph_gamma_element)\n");
  for (int dim = 1; dim <= 3; dim++)
    printf("  %dD: %.3g γ/∇γ evaluations per second\n", dim, bench_elements(dim, &checksum));
  for (int dim = 2; dim <= 3; dim++) bench_eval(dim, &checksum);
  printf("  (checksum %.6g)\n", checksum);
  return 0;
}
