/* sabre-sph: the SPH program. One binary, one subcommand per task:
 *
 *   sabre-sph --version | --help;  sabre-sph <command> --help
 *   sabre-sph run CASE.yaml [--output DIR] [--set key=value ...] [--restart FILE] [--threads N]
 *       run a simulation (sph_cmd_run, sph/src/solver/run.c).
 *   sabre-sph gamma --dim D --dr DR --h-over-dr K --box LO:HI [--stl FILE] --at X,Y[,Z] ...
 *       γ and ∇γ at given points for walls built from a box and/or an STL file (one JSON object
 *       per point on stdout). A public diagnostic: keep its options and output stable.
 *   sabre-sph mesh CASE.yaml --output DIR [--set key=value ...]
 *       mesh the geometry of a case, fill the fluid, compute γ, write VTU files for ParaView.
 *   sabre-sph scalar CASE.yaml [--output DIR] [--set key=value ...]
 *       scalar wave equation on fixed particles with Robin/Neumann/Dirichlet walls
 *       (sph_cmd_scalar, sph/src/scalar/scalar.c; docs/sph-scalar.md).
 *   sabre-sph stability CASE.yaml [--output DIR] [--set key=value ...] [--modes N] [--eps E]
 *       the linearised dynamics of a closed case about its start: growth rates and where the
 *       modes live (sph_cmd_stability, sph/src/solver/stability_cmd.c; docs/sph-solver.md §7.1).
 *   sabre-sph wave stokes5|solitary [options] --at ... [--at ...]
 *       wave generators (Stokes fifth order, solitary wave) at given points and times, one JSON
 *       object per point on stdout (sph_cmd_wave, sph/src/analytic/wave_command.c;
 *       docs/sph-waves.md). A public diagnostic: keep its options and output stable.
 *
 * The commands live in the library (sph_cmd_*) so that tests can run them. Exit codes: 0 success,
 * 2 bad input (CMN_EXIT_INPUT), 1 failure, 3 run stopped at time.max_steps (CMN_EXIT_INCOMPLETE).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sabre/common.h"
#include "sabre/sph.h"
#include "sabre/sph_scalar.h"
#include "sabre/sph_solver.h"
#include "sabre/sph_waves.h"

struct command {
  const char *name;
  int (*run)(int argc, char **argv); /* argv[0] is the command name */
};

static const struct command commands[] = {
    {"run", sph_cmd_run},       {"gamma", sph_cmd_gamma},         {"mesh", sph_cmd_mesh},
    {"scalar", sph_cmd_scalar}, {"stability", sph_cmd_stability}, {"wave", sph_cmd_wave}};

/*
 * OpenMP threads that wait for work spin by default; on a machine whose cores are busy with other
 * jobs a spinning team runs tens of times slower than a passive one (the wedge dam break to 0.05 s
 * with 2 threads: 35 s spinning, 0.6 s passive). libgomp reads OMP_WAIT_POLICY once, when the
 * program is loaded, so setting it later has no effect: unless the user chose a policy, set
 * "passive" and execute the program again (once; if that fails, run on as we are).
 */
static void passive_wait_policy(char **argv) {
#ifdef _OPENMP
  if (getenv("OMP_WAIT_POLICY") != NULL) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  execv("/proc/self/exe", argv);
#else
  (void)argv;
#endif
}

int main(int argc, char **argv) {
  passive_wait_policy(argv);
  cmn_set_program_name("sabre-sph");
  if (argc < 2) {
    sph_cmd_usage(stderr);
    return CMN_EXIT_INPUT;
  }
  if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
      strcmp(argv[1], "help") == 0) {
    sph_cmd_usage(stdout);
    return cmn_stdout_status(0);
  }
  if (strcmp(argv[1], "--version") == 0) {
    cmn_print_version();
    return cmn_stdout_status(0);
  }
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (strcmp(argv[1], commands[i].name) == 0)
      return cmn_stdout_status(commands[i].run(argc - 1, argv + 1));
  cmn_input_error(
      "unknown command '%s' (commands: run, gamma, mesh, scalar, stability, wave; see sabre-sph "
      "--help)",
      argv[1]);
}
