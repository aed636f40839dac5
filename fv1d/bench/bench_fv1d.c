/* bench-fv1d: cell updates per second per RK stage (one right-hand-side evaluation = one stage)
 * for N = 1e4 and 1e6 cells, each flux, MC reconstruction, on a smooth periodic acoustic field
 * with small noise so that the exact Godunov solver iterates at every face. Brief on purpose. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <sabre/fv1d.h>
#include <stdio.h>
#include <stdlib.h>

int main(void) {
  gsl_set_error_handler_off();
  cmn_set_program_name("bench-fv1d");
  const long sizes[2] = {10000, 1000000};
  printf("%-9s %-8s %10s %8s %12s %22s\n", "N", "flux", "recon", "evals", "seconds",
         "cell-updates/s/stage");
  for (int k = 0; k < 2; ++k) {
    for (int f = 0; f < 3; ++f) {
      struct fv1d_params p;
      fv1d_params_default(&p);
      rmn_eos_init(&p.eos, 1000.0, 20.0, 7.0);
      p.x_min = 0.0, p.x_max = 1.0, p.cells = sizes[k];
      p.flux = (enum fv1d_flux)f;
      p.recon = FV1D_RECON_MC;
      p.bc[0].type = p.bc[1].type = FV1D_BC_PERIODIC;
      p.initial.rho = 1000.0, p.initial.u = 0.0;
      p.t_end = 1.0;
      struct fv1d_solver *s = fv1d_solver_create(&p);
      double *y = fv1d_solver_state(s);
      unsigned long long seed = 12345;
      for (long i = 0; i < p.cells; ++i) {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        double noise = (double)(seed >> 11) * 0x1.0p-53 - 0.5;
        double x = fv1d_solver_x(s, i);
        double rho = 1000.0 * (1.0 + 1e-3 * sin(2.0 * 3.141592653589793 * x) + 1e-5 * noise);
        y[2 * i] = rho, y[2 * i + 1] = rho * 0.01 * cos(2.0 * 3.141592653589793 * x);
      }
      double *ydot = malloc(sizeof(double) * (size_t)fv1d_solver_state_length(s));
      long evals = 0;
      double t0 = cmn_wall_time(), elapsed = 0.0;
      while (elapsed < 0.3 || evals < 2) {
        if (fv1d_rhs_eval(s, 0.0, y, ydot) != 0) {
          fprintf(stderr, "bench-fv1d: %s\n", fv1d_solver_error(s));
          return 1;
        }
        ++evals;
        elapsed = cmn_wall_time() - t0;
      }
      printf("%-9ld %-8s %10s %8ld %12.4f %22.4g\n", p.cells, fv1d_flux_names[f], "mc", evals,
             elapsed, (double)p.cells * (double)evals / elapsed);
      free(ydot);
      fv1d_solver_destroy(s);
    }
  }
  return 0;
}
