/* Outside consumer of the installed riemann library: water hammer against Joukowsky. */
#include <math.h>
#include <sabre/riemann.h>
#include <stdio.h>

int main(void) {
  struct rmn_eos eos;
  struct rmn_params par;
  if (rmn_eos_init(&eos, 1000.0, 1480.0, 7.0) != RMN_SUCCESS) return 1;
  rmn_params_default(&par);
  struct rmn_workspace *ws = rmn_workspace_alloc();
  struct rmn_normal_state s;
  int st = rmn_boundary_solve_normal(&eos, &par, ws, 1000.0, -1.0, RMN_IMPOSE_VELOCITY, 0.0, &s);
  rmn_workspace_free(ws);
  double joukowsky = 1000.0 * 1480.0 * 1.0;
  printf("status %s, wave %s, p = %.6g Pa (Joukowsky %.6g Pa)\n", rmn_status_name(st),
         rmn_wave_name(s.wave), s.p, joukowsky);
  return st == RMN_SUCCESS && fabs(s.p / joukowsky - 1.0) < 0.01 ? 0 : 1;
}
