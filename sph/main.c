/* sabre-sph: the SPH program. One binary, one subcommand per task:
 *
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
 *
 * The commands live in the library (sph_cmd_*) so that tests can run them. Exit codes: 0 success,
 * 2 bad input (CMN_EXIT_INPUT), 1 failure. */
#include <stdio.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph.h"
#include "sabre/sph_scalar.h"
#include "sabre/sph_solver.h"

struct command {
  const char *name;
  int (*run)(int argc, char **argv); /* argv[0] is the command name */
};

static const struct command commands[] = {{"run", sph_cmd_run},
                                          {"gamma", sph_cmd_gamma},
                                          {"mesh", sph_cmd_mesh},
                                          {"scalar", sph_cmd_scalar}};

int main(int argc, char **argv) {
  cmn_set_program_name("sabre-sph");
  if (argc < 2) {
    sph_cmd_usage(stderr);
    return CMN_EXIT_INPUT;
  }
  if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
      strcmp(argv[1], "help") == 0) {
    sph_cmd_usage(stdout);
    return 0;
  }
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (strcmp(argv[1], commands[i].name) == 0) return commands[i].run(argc - 1, argv + 1);
  cmn_input_error("unknown command '%s' (commands: run, gamma, mesh, scalar; see sabre-sph --help)",
                  argv[1]);
}
