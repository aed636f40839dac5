/* Messages, fatal errors, checked allocation, strict CLI number parsing, mkdir -p and progress
 * lines. Everything here may exit: this layer belongs to the applications, not to riemann/. */
#include <errno.h>
#include <fenv.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>

#include "sabre/common.h"

static char program_name[64] = "sabre";

void cmn_set_program_name(const char *name) {
  if (name == NULL || name[0] == '\0') name = "sabre";
  /* argv[0] may be a path: keep what a user would type. */
  const char *slash = strrchr(name, '/');
  if (slash != NULL && slash[1] != '\0') name = slash + 1;
  snprintf(program_name, sizeof program_name, "%s", name);
}

const char *cmn_program_name(void) { return program_name; }

void cmn_print_version(void) { printf("%s %s\n", program_name, SABRE_VERSION); }

int cmn_stdout_status(int status) {
  static int reported = 0; /* one message, however many callers check */
  errno = 0;
  if (fflush(stdout) != 0 || ferror(stdout)) {
    if (reported++) return CMN_EXIT_FAILURE;
    fprintf(stderr, "%s: error: cannot write the output: %s\n", program_name,
            errno ? strerror(errno) : "write error");
    return CMN_EXIT_FAILURE;
  }
  return status;
}

static void vreport(const char *kind, const char *fmt, va_list ap) {
  /* One fprintf per line would interleave with other threads' output less than several. */
  char buf[4096];
  vsnprintf(buf, sizeof buf, fmt, ap);
  if (kind != NULL)
    fprintf(stderr, "%s: %s: %s\n", program_name, kind, buf);
  else
    fprintf(stderr, "%s: %s\n", program_name, buf);
}

void cmn_message(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vreport(NULL, fmt, ap);
  va_end(ap);
}

void cmn_warning(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vreport("warning", fmt, ap);
  va_end(ap);
}

_Noreturn void cmn_input_error(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vreport("error", fmt, ap);
  va_end(ap);
  exit(CMN_EXIT_INPUT);
}

_Noreturn void cmn_fatal_at(const char *file, const char *func, int line, const char *fmt, ...) {
  char buf[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  fflush(stdout);
  fprintf(stderr, "%s: error: %s:%d: %s(): %s\n", program_name, file, line, func, buf);
  exit(CMN_EXIT_FAILURE);
}

void *cmn_malloc(size_t n) {
  void *p = malloc(n > 0 ? n : 1);
  if (p == NULL) cmn_error("out of memory allocating %zu bytes", n);
  return p;
}

void *cmn_calloc(size_t count, size_t size) {
  void *p = calloc(count > 0 ? count : 1, size > 0 ? size : 1);
  if (p == NULL) cmn_error("out of memory allocating %zu x %zu bytes", count, size);
  return p;
}

void *cmn_realloc(void *p, size_t n) {
  void *q = realloc(p, n > 0 ? n : 1);
  if (q == NULL) cmn_error("out of memory reallocating to %zu bytes", n);
  return q;
}

int cmn_parse_double(const char *text, double *value) {
  if (text == NULL || text[0] == '\0') return -1;
  /* strtod skips leading blanks; a strict parser must not. */
  if (strchr(" \t\n\v\f\r", text[0]) != NULL) return -1;
  /* Overflowing input ("1e400") raises FE_OVERFLOW inside strtod: keep that away from callers
   * that trap floating-point exceptions, then restore their environment untouched. */
  fenv_t env;
  feholdexcept(&env);
  char *end = NULL;
  errno = 0;
  double x = strtod(text, &end);
  int finite = isfinite(x);
  fesetenv(&env);
  if (end == text || *end != '\0' || !finite) return -1;
  *value = x;
  return 0;
}

int cmn_parse_doubles(const char *text, double *values, int max) {
  if (text == NULL || max <= 0) return -1;
  /* Validate everything first so that `values` is only written on success. */
  for (int pass = 0; pass < 2; ++pass) {
    int count = 0;
    const char *p = text;
    for (;;) {
      const char *comma = strchr(p, ',');
      size_t len = comma != NULL ? (size_t)(comma - p) : strlen(p);
      while (len > 0 && (*p == ' ' || *p == '\t')) ++p, --len;
      while (len > 0 && (p[len - 1] == ' ' || p[len - 1] == '\t')) --len;
      char item[128];
      if (len == 0 || len >= sizeof item || count >= max) return -1;
      memcpy(item, p, len);
      item[len] = '\0';
      double x;
      if (cmn_parse_double(item, &x) != 0) return -1;
      if (pass == 1) values[count] = x;
      ++count;
      if (comma == NULL) break;
      p = comma + 1;
    }
    if (pass == 1) return count;
  }
  return -1;
}

int cmn_parse_long(const char *text, long lo, long hi, long *value) {
  if (text == NULL || text[0] == '\0') return -1;
  if (strchr(" \t\n\v\f\r", text[0]) != NULL) return -1;
  char *end = NULL;
  errno = 0;
  long x = strtol(text, &end, 10);
  if (end == text || *end != '\0' || errno == ERANGE || x < lo || x > hi) return -1;
  *value = x;
  return 0;
}

int cmn_mkdir_p(const char *path) {
  if (path == NULL || path[0] == '\0') {
    errno = ENOENT;
    return -1;
  }
  size_t len = strlen(path);
  char *buf = cmn_malloc(len + 1);
  memcpy(buf, path, len + 1);
  int status = 0;
  /* Create each prefix ending before a '/', then the whole path. */
  for (size_t i = 1; i <= len && status == 0; ++i) {
    if (i < len && buf[i] != '/') continue;
    if (i < len && buf[i - 1] == '/') continue; /* "a//b" */
    char saved = buf[i];
    buf[i] = '\0';
    if (mkdir(buf, 0777) != 0) {
      int err = errno;
      struct stat st;
      if (err == EEXIST && stat(buf, &st) == 0 && S_ISDIR(st.st_mode)) {
        /* already there */
      } else {
        errno = (err == EEXIST) ? ENOTDIR : err;
        status = -1;
      }
    }
    buf[i] = saved;
  }
  free(buf);
  return status;
}

/* ---------------------------------------------------------------------------------------------
 * Progress
 * ------------------------------------------------------------------------------------------- */

double cmn_wall_time(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void cmn_progress_start(struct cmn_progress *p, double t_start, double t_end) {
  p->t_start = t_start;
  p->t_end = t_end;
  p->wall_start = cmn_wall_time();
  p->wall_last = p->wall_start;
  p->interval = 1.0;
  p->enabled = 1;
}

/* "hh:mm:ss" left until `done` reaches t_end at the mean rate so far, or dashes while unknown. */
static void progress_eta(const struct cmn_progress *p, double now, double done, char *eta,
                         size_t len) {
  snprintf(eta, len, "--:--:--");
  double span = p->t_end - p->t_start;
  double elapsed = now - p->wall_start;
  if (span > 0.0 && done > p->t_start && elapsed >= 0.0) {
    double frac = (done - p->t_start) / span;
    if (frac > 1.0) frac = 1.0;
    double remaining = elapsed * (1.0 - frac) / frac;
    /* Early estimates can be absurd; show dashes rather than a meaningless number. */
    if (remaining < 1.0e8) {
      long s = lround(remaining);
      snprintf(eta, len, "%02ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
    }
  }
}

static void progress_format(const struct cmn_progress *p, double now, long step, double t,
                            double dt, long count, char *buf, size_t len) {
  char eta[32];
  progress_eta(p, now, t, eta, sizeof eta);
  if (count >= 0)
    snprintf(buf, len, "step %ld  t = %.4g s  dt = %.2g s  N = %ld  ETA %s", step, t, dt, count,
             eta);
  else
    snprintf(buf, len, "step %ld  t = %.4g s  dt = %.2g s  ETA %s", step, t, dt, eta);
}

/* 1 (and the time in *now) when a line is due: enabled, and forced or `interval` has passed. */
static int progress_due(struct cmn_progress *p, int force, double *now) {
  if (!p->enabled) return 0;
  *now = cmn_wall_time();
  if (!force && *now - p->wall_last < p->interval) return 0;
  p->wall_last = *now;
  return 1;
}

void cmn_progress_task(struct cmn_progress *p, double done, int force, const char *fmt, ...) {
  double now;
  if (!progress_due(p, force, &now)) return;
  char eta[32];
  progress_eta(p, now, done, eta, sizeof eta);
  va_list ap;
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fprintf(stderr, "  ETA %s\n", eta);
}

void cmn_progress_report(struct cmn_progress *p, long step, double t, double dt, long count,
                         int force) {
  double now;
  if (!progress_due(p, force, &now)) return;
  char line[256];
  progress_format(p, now, step, t, dt, count, line, sizeof line);
  fprintf(stderr, "%s\n", line);
}
