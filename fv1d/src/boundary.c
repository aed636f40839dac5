/* Open ends: the imposed signals and the face flux F(U_s) from the riemann/ boundary solver
 * (J §III, docs/theory.md §1.1), evaluated at every right-hand side so that each RK stage is
 * consistent. */
#include <math.h>

#include "internal.h"

const char *const fv1d_bc_names[] = {"wall", "periodic", "transmissive", "open", NULL};
const char *const fv1d_signal_names[] = {"constant", "sinusoid", "ramp", "table", NULL};

double fv1d_signal_eval(const struct fv1d_signal *sig, double t) {
  switch (sig->kind) {
    case FV1D_SIGNAL_CONSTANT:
      return sig->value;
    case FV1D_SIGNAL_SINUSOID:
      return sig->value + sig->amplitude * sin(FV1D_TWO_PI * sig->frequency * t + sig->phase);
    case FV1D_SIGNAL_RAMP: {
      if (t <= sig->t_start) return sig->start;
      if (t >= sig->t_start + sig->duration) return sig->value;
      double w = (t - sig->t_start) / sig->duration;
      return sig->start + w * (sig->value - sig->start);
    }
    case FV1D_SIGNAL_TABLE: /* constant beyond the ends of the table */
      return cmn_interp_linear(sig->ntable, sig->table_t, sig->table_v, 1, t);
  }
  return NAN;
}

int fv1d_boundary_open_flux(struct fv1d_solver *s, int side, double t, double f[2]) {
  const struct fv1d_bc *bc = &s->par.bc[side];
  const long g = FV1D_GHOST, cell = side == 0 ? 0 : s->n - 1;
  const double normal = side == 0 ? 1.0 : -1.0; /* unit normal into the fluid, J §III */
  const double rho_int = s->rho[g + cell], un_int = normal * s->u[g + cell];
  double value = fv1d_signal_eval(&bc->signal, t);
  if (bc->imposed == RMN_IMPOSE_VELOCITY) value *= normal; /* given along +x */
  struct fv1d_boundary_state *b = &s->bnd[side];
  int status = rmn_boundary_solve_normal(&s->par.eos, &s->par.rmn, s->ws, rho_int, un_int,
                                         bc->imposed, value, &b->segment);
  if (status != RMN_SUCCESS) return status;
  b->rho = b->segment.rho;
  b->u = normal * b->segment.un;
  b->p = b->segment.p;
  f[0] = b->rho * b->u;
  f[1] = b->rho * b->u * b->u + b->p;
  return RMN_SUCCESS;
}
