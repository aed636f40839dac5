/* Method of lines with SUNDIALS ARKODE ERKStep (docs/theory.md §2): an SSP-RK3 (Shu–Osher) Butcher
 * table through ERKStepSetTable by default, or any ARKODE ERK table by name; a fixed CFL step
 * chosen before every step, or ARKODE's error control with the CFL step as stability bound. */
#include <arkode/arkode_erkstep.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_context.h>

#include "internal.h"

/* Every SUNDIALS call goes through this check: on a negative flag record the call, the flag name
 * and the source location, then leave through `fail`. */
#define FV1D_SUNCHECK(s, call)                                         \
  do {                                                                 \
    int flag_ = (call);                                                \
    if (flag_ < 0) {                                                   \
      sundials_error((s), __FILE__, __func__, __LINE__, #call, flag_); \
      goto fail;                                                       \
    }                                                                  \
  } while (0)

static void sundials_error(struct fv1d_solver *s, const char *file, const char *func, int line,
                           const char *call, int flag) {
  char *name = ERKStepGetReturnFlagName(flag); /* malloc'ed by SUNDIALS */
  char detail[sizeof s->err];
  snprintf(detail, sizeof detail, "%s", s->err);
  if (flag == ARK_RHSFUNC_FAIL || flag == ARK_REPTD_RHSFUNC_ERR || flag == ARK_UNREC_RHSFUNC_ERR) {
    fv1d_set_error(s, "%s:%s:%d: %s returned %s: %s", file, func, line, call, name ? name : "?",
                   detail);
  } else {
    fv1d_set_error(s, "%s:%s:%d: %s returned %s (%d)", file, func, line, call, name ? name : "?",
                   flag);
  }
  free(name);
}

/** SSP-RK3 of Shu and Osher in Butcher form, with Heun's method (b̂ = (½, ½, 0)) as a
 *  second-order embedding so that ARKODE's error control can be used with it too. */
static ARKodeButcherTable ssprk3_table(void) {
  realtype c[3] = {0.0, 1.0, 0.5};
  realtype a[9] = {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.25, 0.25, 0.0};
  realtype b[3] = {1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0};
  realtype d[3] = {0.5, 0.5, 0.0};
  return ARKodeButcherTable_Create(3, 3, 2, c, a, b, d);
}

/* The ERK tables of ARKODE 6.4 (arkode_butcher_erk.h), checked here so that a typo gets our
 * message rather than ARKODE's print on stderr. */
static const char *const erk_names[] = {
    "ARKODE_HEUN_EULER_2_1_2",      "ARKODE_BOGACKI_SHAMPINE_4_2_3",
    "ARKODE_ARK324L2SA_ERK_4_2_3",  "ARKODE_ZONNEVELD_5_3_4",
    "ARKODE_ARK436L2SA_ERK_6_3_4",  "ARKODE_SAYFY_ABURUB_6_3_4",
    "ARKODE_CASH_KARP_6_4_5",       "ARKODE_FEHLBERG_6_4_5",
    "ARKODE_DORMAND_PRINCE_7_4_5",  "ARKODE_ARK548L2SA_ERK_8_4_5",
    "ARKODE_VERNER_8_5_6",          "ARKODE_FEHLBERG_13_7_8",
    "ARKODE_KNOTH_WOLKE_3_3",       "ARKODE_ARK437L2SA_ERK_7_3_4",
    "ARKODE_ARK548L2SAb_ERK_8_4_5", NULL};

int fv1d_method_check(const char *name, int adaptive, char *err, size_t errlen) {
  if (strcmp(name, "ssprk3") == 0) return 0;
  int known = 0;
  for (int k = 0; erk_names[k]; ++k) known |= strcmp(name, erk_names[k]) == 0;
  if (!known) {
    snprintf(err, errlen,
             "expected 'ssprk3' or an ARKODE ERK table name (ARKODE_HEUN_EULER_2_1_2, "
             "ARKODE_BOGACKI_SHAMPINE_4_2_3, ..., see docs/fv1d.md), got '%s'",
             name);
    return -1;
  }
  ARKodeButcherTable table = ARKodeButcherTable_LoadERKByName(name);
  if (!table) {
    snprintf(err, errlen, "ARKODE cannot load the ERK table '%s'", name);
    return -1;
  }
  const int s = table->stages;
  int embedded = table->d != NULL && table->p > 0;
  /* SUNDIALS 6.4 (and, to be safe, anything before 6.7) treats every ERK table whose last node is
   * c_s = 1 as "first same as last" and reuses its last stage as the next step's first, which is
   * wrong unless the last row of A equals b (LLNL/sundials issue #311, fixed by PR #324):
   * ARKODE_HEUN_EULER_2_1_2 and the ARKODE_ARK*_ERK tables then lose their order. Refuse them
   * rather than give wrong answers. */
  int not_fsal = 0;
  for (int j = 0; j < s; ++j) not_fsal |= table->A[s - 1][j] != table->b[j];
  int broken = table->c[s - 1] == 1.0 && not_fsal;
  ARKodeButcherTable_Free(table);
#if SUNDIALS_VERSION_MAJOR < 6 || (SUNDIALS_VERSION_MAJOR == 6 && SUNDIALS_VERSION_MINOR < 7)
  if (broken) {
    snprintf(err, errlen,
             "table '%s' has c_s = 1 without being first-same-as-last, which SUNDIALS %s "
             "integrates wrongly (LLNL/sundials issue #311, fixed upstream by PR #324): "
             "choose another",
             name, SUNDIALS_VERSION);
    return -1;
  }
#else
  (void)broken;
#endif
  if (adaptive && !embedded) {
    snprintf(err, errlen, "table '%s' has no embedding: time.adaptive needs one", name);
    return -1;
  }
  return 0;
}

static int arkode_rhs(realtype t, N_Vector y, N_Vector ydot, void *user) {
  struct fv1d_solver *s = user;
  ++s->arkode_rhs_calls;
  return fv1d_rhs_eval(s, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
}

/* Explicit stability bound for ARKODE's adaptivity: ARKODE takes cfl × this. */
static int arkode_stability(N_Vector y, realtype t, realtype *h_stab, void *user) {
  struct fv1d_solver *s = user;
  double a = fv1d_max_wave_speed(s, N_VGetArrayPointer(y));
  if (!(a > 0.0) || !isfinite(a)) return 1;
  *h_stab = s->dx / a;
  return 0;
}

int fv1d_integrate(struct fv1d_solver *s, fv1d_observer_fn observer, void *user,
                   struct fv1d_stats *stats) {
  const struct fv1d_params *p = &s->par;
  const long len = fv1d_solver_state_length(s);
  SUNContext ctx = NULL;
  N_Vector y = NULL, atol = NULL;
  ARKodeButcherTable table = NULL;
  void *mem = NULL;
  int result = -1;
  long step = 0;
  double wall0 = cmn_wall_time();
  const long calls0 = s->arkode_rhs_calls;
  s->err[0] = '\0';

  if (SUNContext_Create(NULL, &ctx) != 0) {
    fv1d_set_error(s, "%s:%s:%d: SUNContext_Create failed", __FILE__, __func__, __LINE__);
    return -1;
  }
  y = N_VMake_Serial(len, s->y, ctx); /* ARKODE writes the solution into s->y */
  if (!y) {
    fv1d_set_error(s, "%s:%s:%d: N_VMake_Serial failed", __FILE__, __func__, __LINE__);
    goto fail;
  }
  mem = ERKStepCreate(arkode_rhs, s->t, y, ctx);
  if (!mem) {
    fv1d_set_error(s, "%s:%s:%d: ERKStepCreate failed", __FILE__, __func__, __LINE__);
    goto fail;
  }
  FV1D_SUNCHECK(s, ERKStepSetUserData(mem, s));
  FV1D_SUNCHECK(s, ERKStepSetErrFile(mem, NULL)); /* failures are reported through s->err */
  table = strcmp(p->method, "ssprk3") == 0 ? ssprk3_table()
                                           : ARKodeButcherTable_LoadERKByName(p->method);
  if (!table) {
    fv1d_set_error(s, "unknown time-integration method '%s'", p->method);
    goto fail;
  }
  FV1D_SUNCHECK(s, ERKStepSetTable(mem, table));
  FV1D_SUNCHECK(s, ERKStepSetMaxNumSteps(mem, p->max_steps));
  if (p->adaptive) {
    atol = N_VClone(y);
    if (!atol) {
      fv1d_set_error(s, "%s:%s:%d: N_VClone failed", __FILE__, __func__, __LINE__);
      goto fail;
    }
    double *a = N_VGetArrayPointer(atol);
    const double rho_scale = p->eos.rho0, m_scale = p->eos.rho0 * p->eos.c0;
    for (long i = 0; i < s->n; ++i)
      a[2 * i] = p->atol * rho_scale, a[2 * i + 1] = p->atol * m_scale;
    for (int k = 0; k < FV1D_NFLUXINT; ++k) a[2 * s->n + k] = 1e300; /* bookkeeping only */
    FV1D_SUNCHECK(s, ERKStepSVtolerances(mem, p->rtol, atol));
    FV1D_SUNCHECK(s, ERKStepSetStabilityFn(mem, arkode_stability, s));
    FV1D_SUNCHECK(s, ERKStepSetCFLFraction(mem, p->cfl));
    double a0 = fv1d_max_wave_speed(s, s->y);
    FV1D_SUNCHECK(s, ERKStepSetInitStep(mem, 0.1 * p->cfl * s->dx / a0));
  }

  struct cmn_progress progress;
  cmn_progress_start(&progress, s->t, p->t_end);
  progress.enabled = p->progress;
  s->integrator = mem;
  if (observer && observer(s, FV1D_EVENT_START, 0, s->t, 0.0, user) != 0) goto abort;

  for (size_t k = 0; k < p->noutput; ++k) {
    const double tout = p->output_times[k];
    if (tout <= s->t) continue;
    FV1D_SUNCHECK(s, ERKStepSetStopTime(mem, tout));
    while (s->t < tout) {
      double dt = 0.0;
      if (!p->adaptive) {
        double a = fv1d_max_wave_speed(s, s->y);
        if (!(a > 0.0) || !isfinite(a)) {
          fv1d_set_error(s, "t = %.9g s: maximal wave speed is %g", s->t, a);
          goto fail;
        }
        dt = p->cfl * s->dx / a;
        /* land on the output time without a sliver step */
        if (s->t + 1.0000001 * dt >= tout) dt = tout - s->t;
        FV1D_SUNCHECK(s, ERKStepSetFixedStep(mem, dt));
      }
      if (step >= p->max_steps) {
        fv1d_set_error(s, "time.max_steps = %ld reached at t = %.9g s, before time.end",
                       p->max_steps, s->t);
        result = 1;
        goto done;
      }
      double tret = s->t;
      FV1D_SUNCHECK(s, ERKStepEvolve(mem, tout, y, &tret, ARK_ONE_STEP));
      FV1D_SUNCHECK(s, ERKStepGetLastStep(mem, &dt));
      s->t = tret;
      /* ARKODE stops at tout to within its round-off; call it tout */
      if (fabs(tout - s->t) <= 1e-12 * fmax(fabs(tout), dt)) s->t = tout;
      ++step;
      if (observer && observer(s, FV1D_EVENT_STEP, step, s->t, dt, user) != 0) goto abort;
      cmn_progress_report(&progress, step, s->t, dt, s->n, 0);
    }
    if (observer && observer(s, FV1D_EVENT_OUTPUT, step, s->t, 0.0, user) != 0) goto abort;
  }
  cmn_progress_report(&progress, step, s->t, 0.0, s->n, 1);
  result = 0;
  goto done;
abort:
  if (!s->err[0]) fv1d_set_error(s, "run stopped by the observer at t = %.9g s", s->t);
fail:
  result = -1;
done:
  if (stats) {
    long nrhs = 0, fails = 0;
    if (mem) { /* checked, but a failure here must not hide the run's own status */
      if (ERKStepGetNumRhsEvals(mem, &nrhs) < 0) nrhs = -1;
      if (ERKStepGetNumErrTestFails(mem, &fails) < 0) fails = -1;
    }
    stats->steps = step;
    stats->rhs_evals = s->arkode_rhs_calls - calls0;
    stats->arkode_rhs_evals = nrhs;
    stats->failed_steps = fails;
    stats->wall_time = cmn_wall_time() - wall0;
  }
  s->integrator = NULL;
  if (mem) ERKStepFree(&mem);
  if (table) ARKodeButcherTable_Free(table);
  if (atol) N_VDestroy(atol);
  if (y) N_VDestroy(y);
  if (ctx) SUNContext_Free(&ctx);
  return result;
}
