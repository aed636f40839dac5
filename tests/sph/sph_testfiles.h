/* Helpers for the sph tests that write files or run code that exits: a scratch directory per
 * test program (cmocka group setup/teardown), file paths and contents in it, and running a
 * function in a child process with its stdout and stderr captured. Include after testutil.h. */
#ifndef SABRE_SPH_TESTFILES_H
#define SABRE_SPH_TESTFILES_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static char test_dir[64];

/** cmocka group setup: a fresh directory /tmp/sabre-test-XXXXXX. */
static inline int test_dir_setup(void **state) {
  (void)state;
  snprintf(test_dir, sizeof test_dir, "/tmp/sabre-test-XXXXXX");
  return mkdtemp(test_dir) ? 0 : -1;
}

/** cmocka group teardown: remove the directory. */
static inline int test_dir_teardown(void **state) {
  (void)state;
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf %s", test_dir);
  return system(cmd) == 0 ? 0 : -1;
}

/** Path of a file in the directory (a static buffer, valid until the next call). */
static inline const char *test_path(const char *name) {
  static char path[256];
  snprintf(path, sizeof path, "%s/%s", test_dir, name);
  return path;
}

/** Write text to a file of the directory; returns its path (as test_path). */
static inline const char *test_write(const char *name, const char *text) {
  const char *path = test_path(name);
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fputs(text, f);
  fclose(f);
  return path;
}

/** Read up to len − 1 bytes of a file of the directory into buf (NUL-terminated). */
static inline void test_read(const char *name, char *buf, size_t len) {
  FILE *f = fopen(test_path(name), "rb");
  assert_non_null(f);
  size_t n = fread(buf, 1, len - 1, f);
  buf[n] = '\0';
  fclose(f);
}

/**
 * Run fn(arg) in a child process; its stdout and stderr go to out (len bytes, NUL-terminated).
 * Returns the child's exit status (fn's return value, or the code it exited with), −1 if it was
 * killed.
 */
static inline int test_capture(int (*fn)(void *), void *arg, char *out, size_t len) {
  int fd[2];
  assert_int_equal(pipe(fd), 0);
  fflush(NULL);
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    close(fd[0]);
    dup2(fd[1], 1);
    dup2(fd[1], 2);
    int rc = fn(arg);
    fflush(NULL);
    _exit(rc);
  }
  close(fd[1]);
  size_t n = 0;
  ssize_t got;
  char drain[256];
  for (;;) { /* keep reading past len so that the child never blocks on a full pipe */
    if (n + 1 < len)
      got = read(fd[0], out + n, len - 1 - n);
    else
      got = read(fd[0], drain, sizeof drain);
    if (got <= 0) break;
    if (n + 1 < len) n += (size_t)got;
  }
  out[n] = '\0';
  close(fd[0]);
  int status;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

#endif
