/* fv1d/ private declarations shared by the source files of the library. */
#ifndef SABRE_FV1D_INTERNAL_H
#define SABRE_FV1D_INTERNAL_H

#include <sabre/fv1d.h>

/** Number of ghost cells on each side (enough for one limited slope at the end faces). */
#define FV1D_GHOST 2
/** Extra state components: ∫F_left dt (3) and ∫F_right dt (3). */
#define FV1D_NFLUXINT 6
/** 2π (M_PI is not ISO C). */
#define FV1D_TWO_PI 6.283185307179586476925286766559

struct fv1d_solver {
  struct fv1d_params par; /* shallow copy: tables stay owned by the caller */
  long n;                 /* cells */
  double dx;
  double t;  /* current time */
  double *y; /* state (2n + 6), owned */
  /* RHS work arrays with FV1D_GHOST ghosts on each side: primitives and slopes. */
  double *rho, *u, *srho, *su;
  double *face; /* 2 (n + 1) face fluxes */
  struct rmn_workspace *ws;
  struct fv1d_boundary_state bnd[2];
  char err[512];
  void *integrator;      /* ARKODE memory while integrating */
  long arkode_rhs_calls; /* right-hand sides evaluated for ARKODE (stages) */
};

/** Set the solver error message (printf style). */
void fv1d_set_error(struct fv1d_solver *s, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/** Fill ghost cells of the primitive arrays according to the boundary types. */
void fv1d_recon_ghosts(struct fv1d_solver *s);
/** Limited slopes of ρ and u in every cell (and the first ghost on each side). */
void fv1d_recon_slopes(struct fv1d_solver *s);

/**
 * Face flux at an open end (side 0 left, 1 right) from the adjacent cell state at time t, filling
 * s->bnd[side]. Returns RMN_SUCCESS or the riemann/ status.
 */
int fv1d_boundary_open_flux(struct fv1d_solver *s, int side, double t, double f[2]);

/** Energy flux (E + p) u with E = ½ρu² + W(ρ) [W/m²]. */
double fv1d_energy_flux(const struct rmn_eos *eos, double rho, double u);

/** 0 if `name` is "ssprk3" or an ARKODE ERK table (with an embedding when adaptive), else -1
 *  with a message in err. */
int fv1d_method_check(const char *name, int adaptive, char *err, size_t errlen);

/** Point value of the initial background (table, expressions or uniform state) at x. */
void fv1d_initial_point(const struct fv1d_params *p, double x, double *rho, double *u);

#endif
