/* Shared helpers for SABRE's cmocka tests: relative/absolute assertions with a stated tolerance,
 * floating-point traps, and a seeded random generator (tests are reproducible). */
#ifndef SABRE_TESTUTIL_H
#define SABRE_TESTUTIL_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
/* cmocka.h needs the three headers above first. */
#include <cmocka.h>

/** Fail unless |x − expected| ≤ tol·max(|expected|, tiny); prints both values. */
#define assert_rel(x, expected, tol) \
  sabre_assert_rel((x), (expected), (tol), #x, __FILE__, __LINE__)
/** Fail unless |x − expected| ≤ tol. */
#define assert_abs(x, expected, tol) \
  sabre_assert_abs((x), (expected), (tol), #x, __FILE__, __LINE__)

void sabre_assert_rel(double x, double expected, double tol, const char *expr, const char *file,
                      int line);
void sabre_assert_abs(double x, double expected, double tol, const char *expr, const char *file,
                      int line);

/** Trap FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW (SIGFPE) for the rest of the test. */
void sabre_fp_traps_on(void);
/** Turn the traps off (for tests that check NaN/inf handling on purpose). */
void sabre_fp_traps_off(void);
/** cmocka group setup: GSL's error handler off (callers check status codes) and the traps on. */
int sabre_setup_gsl_traps(void **state);

/** Deterministic generator (splitmix64) seeded explicitly. */
struct sabre_rng {
  uint64_t state;
};
void sabre_rng_seed(struct sabre_rng *rng, uint64_t seed);
/** Uniform in [lo, hi). */
double sabre_rng_uniform(struct sabre_rng *rng, double lo, double hi);

/**
 * Run `body` in a forked child with its stderr captured in a temporary file (body must exit, e.g.
 * through a fatal error). Returns the child's exit status (-1 if it did not exit normally) and
 * copies up to len − 1 bytes of what it wrote to stderr into out.
 */
int sabre_run_child(void (*body)(void), char *out, size_t len);

#endif
