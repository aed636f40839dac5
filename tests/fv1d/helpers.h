/* Helpers shared by the fv1d tests: parameter sets built in code, and running to a time. */
#ifndef SABRE_TEST_FV1D_HELPERS_H
#define SABRE_TEST_FV1D_HELPERS_H

#include <math.h>
#include <sabre/fv1d.h>

#include "testutil.h"

#define FV1D_TEST_TWO_PI 6.283185307179586476925286766559

/** Params on [x_min, x_max] with n cells, the given EOS, uniform (rho, u), transmissive ends. */
static inline void th_params(struct fv1d_params *p, double x_min, double x_max, long n, double rho0,
                             double c0, double xi) {
  fv1d_params_default(p);
  assert_int_equal(rmn_eos_init(&p->eos, rho0, c0, xi), RMN_SUCCESS);
  p->x_min = x_min, p->x_max = x_max, p->cells = n;
  p->initial.rho = rho0, p->initial.u = 0.0;
  p->progress = 0;
}

/** Integrate the solver to t_end (one output time); fails the test on a solver error. */
static inline void th_run(struct fv1d_solver *s, struct fv1d_params *p, double t_end,
                          struct fv1d_stats *stats) {
  (void)p;
  int status = fv1d_integrate(s, NULL, NULL, stats);
  if (status != 0) print_error("fv1d_integrate: %s\n", fv1d_solver_error(s));
  assert_int_equal(status, 0);
  assert_rel(fv1d_solver_time(s), t_end, 1e-14);
}

/** Least-squares slope of log(err) against log(1/N): the observed order. */
static inline double th_order(int count, const long *n, const double *err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int k = 0; k < count; ++k) {
    double x = -log((double)n[k]), y = log(err[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (count * sxy - sx * sy) / (count * sxx - sx * sx);
}

#endif
