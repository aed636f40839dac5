/* Why the time step of sph_solver_step() is not positive (sph_solver_explain_dt, sph_solver.h):
 * the limit that gave it, at the fluid particle that set it. */
#include <math.h>
#include <stdio.h>

#include "sabre/sph_solver.h"

void sph_solver_explain_dt(const struct sph_solver *sv, double dt, char *msg, size_t msglen) {
  const struct sph_config *cfg = &sv->cfg;
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const double h = sv->sys.h;
  size_t worst_a = 0, worst_v = 0;
  double amax = -1.0, vmax = -1.0;
  for (size_t a = 0; a < f->n; a++) {
    double v2 = 0.0, a2 = 0.0;
    for (int c = 0; c < 3; c++) {
      v2 += f->v[c][a] * f->v[c][a];
      a2 += sv->acc[c][a] * sv->acc[c][a];
    }
    const int bad = !isfinite(v2) || !isfinite(a2) || !isfinite(f->rho[a]) ||
                    !isfinite(f->x[0][a] + f->x[1][a] + f->x[2][a]);
    if (bad) {
      snprintf(msg, msglen,
               "time step %g s is not positive: fluid particle id %lld at (%g, %g, %g) has a "
               "non-finite state (|v|^2 = %g m^2/s^2, |a|^2 = %g m^2/s^4, rho = %g kg/m^3): the "
               "flow blew up (too large a time.end for the resolution, numerics.cfl, or an "
               "initial state far from equilibrium)",
               dt, (long long)f->id[a], f->x[0][a], f->x[1][a], f->x[2][a], v2, a2, f->rho[a]);
      return;
    }
    if (a2 > amax) amax = a2, worst_a = a;
    if (v2 > vmax) vmax = v2, worst_v = a;
  }
  if (f->n == 0) {
    snprintf(msg, msglen, "time step %g s is not positive: no fluid particles left", dt);
    return;
  }
  amax = sqrt(amax);
  vmax = sqrt(vmax);
  const double dt_force = amax > 0.0 ? cfg->force_factor * sqrt(h / amax) : INFINITY;
  const double dt_cfl = cfg->cfl * h / (cfg->c0 + vmax);
  if (dt_force <= dt_cfl)
    snprintf(msg, msglen,
             "time step %g s is not positive: the force limit numerics.force_factor sqrt(h/|a|) "
             "= %g s, from |a| = %g m/s^2 at fluid particle id %lld (%g, %g, %g) (a particle "
             "pushed into a wall?)",
             dt, dt_force, amax, (long long)f->id[worst_a], f->x[0][worst_a], f->x[1][worst_a],
             f->x[2][worst_a]);
  else
    snprintf(msg, msglen,
             "time step %g s is not positive: the CFL limit numerics.cfl h/(c + |v|) = %g s, from "
             "|v| = %g m/s at fluid particle id %lld (%g, %g, %g)",
             dt, dt_cfl, vmax, (long long)f->id[worst_v], f->x[0][worst_v], f->x[1][worst_v],
             f->x[2][worst_v]);
}
