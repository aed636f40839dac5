#define _GNU_SOURCE /* feenableexcept */
#include "testutil.h"

#include <fenv.h>
#include <float.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

void sabre_assert_rel(double x, double expected, double tol, const char *expr, const char *file,
                      int line) {
  double scale = fmax(fabs(expected), DBL_MIN);
  double err = fabs(x - expected) / scale;
  if (!(err <= tol)) {
    print_error("%s = %.17g, expected %.17g: relative error %.3e > %.3e\n", expr, x, expected, err,
                tol);
    _fail(file, line);
  }
}

void sabre_assert_abs(double x, double expected, double tol, const char *expr, const char *file,
                      int line) {
  double err = fabs(x - expected);
  if (!(err <= tol)) {
    print_error("%s = %.17g, expected %.17g: absolute error %.3e > %.3e\n", expr, x, expected, err,
                tol);
    _fail(file, line);
  }
}

void sabre_fp_traps_on(void) {
  feclearexcept(FE_ALL_EXCEPT);
  feenableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
}

int sabre_setup_gsl_traps(void **state) {
  (void)state;
  gsl_set_error_handler_off();
  sabre_fp_traps_on();
  return 0;
}

void sabre_fp_traps_off(void) {
  fedisableexcept(FE_ALL_EXCEPT);
  feclearexcept(FE_ALL_EXCEPT);
}

void sabre_rng_seed(struct sabre_rng *rng, uint64_t seed) { rng->state = seed; }

double sabre_rng_uniform(struct sabre_rng *rng, double lo, double hi) {
  uint64_t z = (rng->state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return lo + (hi - lo) * ((double)(z >> 11) * 0x1.0p-53);
}

/* Run `body` in a child with stderr in a file; return the exit status and the captured text. */
int sabre_run_child(void (*body)(void), char *out, size_t len) {
  char path[] = "/tmp/sabre_test_stderr_XXXXXX";
  int fd = mkstemp(path);
  assert_true(fd >= 0);
  fflush(NULL);
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    dup2(fd, 2);
    body();
    _exit(99);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  FILE *f = fdopen(fd, "r");
  rewind(f);
  size_t got = fread(out, 1, len - 1, f);
  out[got] = '\0';
  fclose(f);
  remove(path);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
