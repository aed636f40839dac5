/*
 * Restart is bit-identical (same thread count): a run to time.end, and the same run stopped at
 * time.max_steps (exit 3) and continued with --restart, give byte-identical diagnostics.csv,
 * probes.csv, forces.csv, VTU files and final checkpoint (with an imposed flux, with the set-up
 * before t = 0 — repacking, layer equilibrium, settling — and with an open boundary and its
 * open_<name>.csv, too, and with the wall vertices' masses following their density); so does a
 * run stopped by SIGTERM and
 * restarted. A restart whose case differs outside `time` is refused. Also the library level: N
 * steps, or k steps + checkpoint write + read into a fresh solver + N − k steps, give bitwise equal
 * particle stores.
 */
#define _POSIX_C_SOURCE 200809L /* fork, kill, nanosleep, mkdtemp */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "sabre/common.h"
#include "solver_fixture.h"
#include "testutil.h"

static const char case_text[] =
    "geometry:\n"
    "  dimension: 2\n"
    "  dr: 0.025\n"
    "  walls:\n"
    "    - type: box\n"
    "      lo: [0, 0]\n"
    "      hi: [0.5, 0.4]\n"
    "  fluid:\n"
    "    - type: box\n"
    "      lo: [0, 0]\n"
    "      hi: [0.2, 0.2]\n"
    "fluid:\n"
    "  rho0: 1000\n"
    "  c0: 15\n"
    "  nu: 1.0e-4\n"
    "gravity: [0, -9.81]\n"
    "initial:\n"
    "  pressure: hydrostatic\n"
    "time:\n"
    "  end: 0.03\n"
    "  output_interval: 0.01\n"
    "probes:\n"
    "  pressure: [[0.05, 0.05]]\n"
    "  gauges: [[0.1, 0]]\n"
    "forces:\n"
    "  - name: tank\n"
    "    wall: 0\n";

static char dir[256];

static void sleep_ms(long ms) {
  struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
  nanosleep(&ts, NULL);
}

static char *path(const char *a, const char *b) {
  static char buf[4][512];
  static int k = 0;
  k = (k + 1) % 4;
  snprintf(buf[k], sizeof buf[k], "%s/%s%s%s", dir, a, b ? "/" : "", b ? b : "");
  return buf[k];
}

static char *slurp(const char *p, size_t *len) {
  FILE *f = fopen(p, "rb");
  assert_non_null(f);
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *buf = malloc((size_t)n + 1);
  assert_int_equal(fread(buf, 1, (size_t)n, f), (size_t)n);
  fclose(f);
  *len = (size_t)n;
  return buf;
}

static void same_file(const char *a, const char *b) {
  size_t la, lb;
  char *x = slurp(a, &la), *y = slurp(b, &lb);
  if (la != lb || memcmp(x, y, la) != 0) fail_msg("%s and %s differ", a, b);
  free(x);
  free(y);
}

static int run(const char *out, const char *set, const char *restart) {
  char *argv[32];
  int argc = 0;
  argv[argc++] = "run";
  argv[argc++] = path("case.yaml", NULL);
  argv[argc++] = "--output";
  argv[argc++] = (char *)out;
  argv[argc++] = "--threads";
  argv[argc++] = "1";
  /* set: one or more "key=value" separated by ';' */
  static char sets[8][256];
  int ns = 0;
  for (const char *p = set; p && *p && ns < 8; ns++) {
    const char *e = strchr(p, ';');
    size_t len = e ? (size_t)(e - p) : strlen(p);
    snprintf(sets[ns], sizeof sets[ns], "%.*s", (int)len, p);
    argv[argc++] = "--set";
    argv[argc++] = sets[ns];
    p = e ? e + 1 : NULL;
  }
  if (restart) {
    argv[argc++] = "--restart";
    argv[argc++] = (char *)restart;
  }
  argv[argc] = NULL;
  return sph_cmd_run(argc, argv);
}

/* The case with `set` (NULL: as it is; "key=value" items separated by ';') run to time.end in
 * <name>_full, and stopped at time.max_steps (exit 3, as sabre-fv1d; checkpoint written) then
 * continued with --restart in <name>_split: the listed files must be byte-identical. */
static void split_run(const char *name, const char *set, const char *const *files, size_t n) {
  char a[600], b[600], stop[700], ck[700];
  snprintf(a, sizeof a, "%s_full", path(name, NULL));
  snprintf(b, sizeof b, "%s_split", path(name, NULL));
  snprintf(stop, sizeof stop, "%s%stime.max_steps=23", set ? set : "", set ? ";" : "");
  assert_int_equal(run(a, set, NULL), 0);
  assert_int_equal(run(b, stop, NULL), CMN_EXIT_INCOMPLETE);
  snprintf(ck, sizeof ck, "%s/checkpoint.bin", b);
  assert_int_equal(run(b, set, ck), 0);
  for (size_t i = 0; i < n; i++) {
    char pa[800], pb[800];
    snprintf(pa, sizeof pa, "%s/%s", a, files[i]);
    snprintf(pb, sizeof pb, "%s/%s", b, files[i]);
    same_file(pa, pb);
  }
}

static void test_command_restart(void **state) {
  (void)state;
  snprintf(dir, sizeof dir, "/tmp/sabre-test-restart-XXXXXX");
  assert_non_null(mkdtemp(dir));
  FILE *f = fopen(path("case.yaml", NULL), "w");
  fputs(case_text, f);
  fclose(f);
  const char *files[] = {"diagnostics.csv", "probes.csv",    "forces.csv",
                         "checkpoint.bin",  "particles.pvd", "fluid_000003.vtu"};
  const size_t nfiles = sizeof files / sizeof files[0];
  split_run("plain", NULL, files, nfiles);
  /* The same with an imposed flux: M(62–63) depend on the last measured velocities, so the
   * controller's history must travel in the checkpoint for the restart to be bit-identical. */
  split_run("flux", "imposed_flux={velocity: 0.05, area: 0.2, point: [0.1, 0.1]}", files, nfiles);

  /* The same with an open face (the column's left wall, hydrostatic with the measured level):
   * the open-boundary values are recomputed from the store at every evaluation, so nothing but
   * the store travels in the checkpoint, and open_left.csv continues byte for byte. */
  const char *open_files[] = {"diagnostics.csv", "open_left.csv", "forces.csv",
                              "checkpoint.bin",  "particles.pvd", "boundary_000003.vtu"};
  split_run("open",
            "geometry.walls[0].open=[x-];open_boundaries=[{name: left, wall: 0, impose: pressure, "
            "hydrostatic: {depth: measured}}]",
            open_files, sizeof open_files / sizeof open_files[0]);

  /* The same with the wall vertices' masses following their density (their volumes V_v travel
   * in the store), the no-pull rule's normal form, an open face and a repacked start (that last
   * pair alone diverged after the restart until the open vertices' wall masses and the fitted
   * wall layer's thickness travelled in the checkpoint: the restart does not repeat the set-up,
   * whose repacking fixed them). */
  split_run("vmass",
            "numerics.wall_vertex_mass=density;numerics.no_pull=normal;repack.steps=50;"
            "geometry.walls[0].open=[x-];open_boundaries=[{name: left, wall: 0, impose: pressure, "
            "hydrostatic: {depth: measured}}]",
            open_files, sizeof open_files / sizeof open_files[0]);

  /* The same with the set-up before t = 0 (repacking, layer equilibrium, settling run), whose
   * result (positions, densities, masses) the checkpoint holds. */
  split_run("setup", "repack.steps=50;repack.layer_equilibrium=true;repack.settle=0.02", files,
            nfiles);
  /* ... and its start differs from the plain run's (the set-up did something) */
  {
    size_t la, lb;
    char *x = slurp(path("plain_full", "fluid_000000.vtu"), &la);
    char *y = slurp(path("setup_full", "fluid_000000.vtu"), &lb);
    assert_true(la != lb || memcmp(x, y, la) != 0);
    free(x);
    free(y);
  }

  /* SIGTERM: the run writes a checkpoint and exits with 128 + 15; restarting it ends like the
   * uninterrupted run, byte for byte. */
  const char *sig_set = "time.end=3;time.output_interval=0.5;gravity=[0, 0];initial.pressure=zero";
  char c[600], cf[600];
  snprintf(c, sizeof c, "%s", path("signal", NULL));
  snprintf(cf, sizeof cf, "%s", path("signal_full", NULL));
  assert_int_equal(run(cf, sig_set, NULL), 0);
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) _exit(run(c, sig_set, NULL));
  char ckc[700];
  snprintf(ckc, sizeof ckc, "%s/diagnostics.csv", c);
  for (int i = 0; i < 600 && access(ckc, F_OK) != 0; i++) sleep_ms(10);
  sleep_ms(300);
  kill(pid, SIGTERM);
  int status;
  assert_int_equal(waitpid(pid, &status, 0), pid);
  assert_true(WIFEXITED(status));
  assert_int_equal(WEXITSTATUS(status), 128 + SIGTERM);
  snprintf(ckc, sizeof ckc, "%s/checkpoint.bin", c);
  assert_int_equal(access(ckc, F_OK), 0);
  assert_int_equal(run(c, sig_set, ckc), 0);
  const char *sig_files[] = {"diagnostics.csv", "probes.csv",    "forces.csv",
                             "checkpoint.bin",  "particles.pvd", "fluid_000006.vtu"};
  for (size_t i = 0; i < sizeof sig_files / sizeof sig_files[0]; i++) {
    char pa[800], pb[800];
    snprintf(pa, sizeof pa, "%s/%s", cf, sig_files[i]);
    snprintf(pb, sizeof pb, "%s/%s", c, sig_files[i]);
    same_file(pa, pb);
  }
  /* The run really was split: the uninterrupted run has many rows. */
  size_t n;
  char *d = slurp(path("plain_full", "diagnostics.csv"), &n);
  int rows = 0;
  for (size_t i = 0; i < n; i++) rows += d[i] == '\n';
  free(d);
  assert_true(rows > 30);

  /* A restart with other numerics is refused (exit 2, naming the section); one with a later
   * time.end is not. */
  char ce[600], cke[700];
  snprintf(ce, sizeof ce, "%s", path("changed", NULL));
  assert_int_equal(run(ce, "time.max_steps=10", NULL), CMN_EXIT_INCOMPLETE);
  snprintf(cke, sizeof cke, "%s/checkpoint.bin", ce);
  pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) _exit(run(ce, "numerics.cfl=0.2", cke));
  assert_int_equal(waitpid(pid, &status, 0), pid);
  assert_true(WIFEXITED(status));
  assert_int_equal(WEXITSTATUS(status), CMN_EXIT_INPUT);
  pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) _exit(run(ce, "fluid.c0=15.0;time.end=0.04", cke)); /* 15.0: same value */
  assert_int_equal(waitpid(pid, &status, 0), pid);
  assert_true(WIFEXITED(status));
  assert_int_equal(WEXITSTATUS(status), 0);
  char cmd[700];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  assert_int_equal(system(cmd), 0);
}

static void library_restart(int gamma_dynamic) {
  struct sph_solver x, y;
  for (int i = 0; i < 2; i++) {
    struct sph_system s;
    fixture_lattice(&s, 12, 8, 0.02, 2.0, FIX_CHANNEL);
    struct sph_config cfg;
    fixture_config(&cfg);
    cfg.gravity[1] = -9.81;
    cfg.hydrostatic = 1;
    cfg.nu = 1e-4;
    cfg.u0[0] = 0.3;
    cfg.gamma_dynamic = gamma_dynamic;
    sph_solver_init(i ? &y : &x, &cfg, &s, NULL, NULL);
    sph_system_free(&s);
  }
  char msg[512], ck[] = "/tmp/sabre-test-ckpt-XXXXXX";
  int fd = mkstemp(ck);
  assert_true(fd >= 0);
  close(fd);
  for (int n = 0; n < 12; n++) assert_int_equal(sph_solver_step(&x, INFINITY, msg, sizeof msg), 0);
  for (int n = 0; n < 5; n++) assert_int_equal(sph_solver_step(&y, INFINITY, msg, sizeof msg), 0);
  struct sph_run_counters rc = {.next_output = 0.5};
  assert_int_equal(sph_checkpoint_write(&y, &rc, ck), 0);
  sph_solver_free(&y);
  {
    struct sph_system s;
    fixture_lattice(&s, 12, 8, 0.02, 2.0, FIX_CHANNEL);
    struct sph_config cfg = x.cfg;
    sph_solver_init(&y, &cfg, &s, NULL, NULL);
    sph_system_free(&s);
  }
  assert_int_equal(sph_checkpoint_read(&y, &rc, ck, msg, sizeof msg), 0);
  assert_int_equal(y.step, 5);
  for (int n = 0; n < 7; n++) assert_int_equal(sph_solver_step(&y, INFINITY, msg, sizeof msg), 0);
  const struct sph_parts *px = &x.sys.part[SPH_KIND_FLUID], *py = &y.sys.part[SPH_KIND_FLUID];
  assert_int_equal(px->n, py->n);
  assert_memory_equal(px->rho, py->rho, px->n * sizeof(double));
  assert_memory_equal(px->gamma, py->gamma, px->n * sizeof(double));
  for (int c = 0; c < 2; c++) {
    assert_memory_equal(px->x[c], py->x[c], px->n * sizeof(double));
    assert_memory_equal(px->v[c], py->v[c], px->n * sizeof(double));
  }
  assert_true(x.time == y.time);
  /* Bad checkpoints are reported, not crashed on. */
  FILE *f = fopen(ck, "wb");
  fputs("not a checkpoint", f);
  fclose(f);
  assert_int_equal(sph_checkpoint_read(&y, &rc, ck, msg, sizeof msg), -1);
  assert_non_null(strstr(msg, "not a SABRE SPH checkpoint"));
  remove(ck);
  free(rc.output_times);
  sph_solver_free(&x);
  sph_solver_free(&y);
}

/* Both forms of γ: with the dynamic one, γ is state and restored from the checkpoint. */
static void test_library_restart(void **state) {
  (void)state;
  sabre_fp_traps_on();
  library_restart(0);
  library_restart(1);
}

int main(void) {
  cmn_set_program_name("test_restart");
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_library_restart),
      cmocka_unit_test(test_command_restart),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
