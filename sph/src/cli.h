/*
 * The helpers of the case-file commands of sabre-sph (`run`, `scalar`, `stability`). Their command
 * lines (CASE.yaml [--set key=value]... [--output DIR] ...) are parsed, loaded and recorded in
 * used_case.yaml by common/'s cmn_cli_* (sabre/common.h), called with the command's name (argv[0])
 * as the prefix of messages.
 */
#ifndef SABRE_SPH_CLI_H
#define SABRE_SPH_CLI_H

/** dir/name in a new string (free it). */
char *sph_cli_join(const char *dir, const char *name);

struct cmn_case;
struct sph_solver;
/** What a command asks of the case before the solver is built (sph_cli_solver). */
struct sph_cli_setup {
  const char *command; /**< the command's name, for messages ("stability") */
  int repack;          /**< run the case's repacking (0: none, as on restart) */
  int closed_only;     /**< refuse a case with open boundaries */
  long max_unknowns;   /**< refuse more than this many dim × fluid unknowns (0: no limit) */
};
/**
 * The solver of a case as `run` and `stability` start it (sph/src/solver/run.c): geometry and
 * numerics read and checked (unused keys refused), particles built, the limits of `setup`
 * checked, dir/used_case.yaml written once the input is known good (no half-written output on
 * bad input), solver initialised (with the case's repacking when setup->repack). Returns a solver
 * owned by the caller (sph_solver_free(), then free()). Bad input exits with CMN_EXIT_INPUT, the
 * message naming case_path and the key.
 */
struct sph_solver *sph_cli_solver(struct cmn_case *c, const char *case_path, const char *dir,
                                  const struct sph_cli_setup *setup);
/**
 * OpenMP threads of a command: --threads N (threads_arg, NULL when absent), else OMP_NUM_THREADS
 * when the user set it, else 1. Returns the count used. A bad N exits with CMN_EXIT_INPUT,
 * "<command>: --threads: expected a whole number in [1, 4096], got '...'".
 */
int sph_cli_threads(const char *threads_arg, const char *command);

#endif /* SABRE_SPH_CLI_H */
