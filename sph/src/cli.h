/*
 * Command lines of the case-file commands of sabre-sph (`run`, `scalar`):
 *
 *   sabre-sph <command> CASE.yaml [--set key=value]... [--output DIR] [--<extra> VALUE]...
 *
 * The parsing, the loading of the case with its --set overrides and the run directory with
 * used_case.yaml are common/'s (cmn_cli_*, sabre/common.h); these functions give them the
 * command's name (argv[0]) as the prefix of messages. Bad input stops the program with exit code
 * CMN_EXIT_INPUT.
 */
#ifndef SABRE_SPH_CLI_H
#define SABRE_SPH_CLI_H

#include "sabre/common.h"

/** An option of one command beyond --set and --output, taking one value (e.g. "--threads"). */
struct sph_cli_option {
  const char *name;   /**< with its dashes */
  const char **value; /**< receives the value (left alone when the option is absent) */
};

struct sph_cli {
  const char *case_path; /**< the one positional argument */
  const char *output;    /**< --output, or the command's default */
  struct cmn_cli cmn;    /**< the parsed command line, for sph_cli_load */
};

/**
 * Parse argv[1 .. argc) of a command (argv[0] is its name) with cmn_cli_parse(): one case file,
 * --set (repeatable), --output and the `nextra` options of `extra`. Returns 1 if --help or -h was
 * given (usage then printed on stdout, nothing to free), else 0. Unknown options, a missing value,
 * no case file or two of them stop the program.
 */
int sph_cli_parse(struct sph_cli *cli, int argc, char **argv, const char *usage,
                  const char *default_output, const struct sph_cli_option *extra, int nextra);
/** Load the case file and apply the --set overrides in order (cmn_cli_load()). */
struct cmn_case *sph_cli_load(struct sph_cli *cli);
/** dir/name in a new string (free it). */
char *sph_cli_join(const char *dir, const char *name);
/** Create the run directory and write dir/used_case.yaml (cmn_cli_write_used()). */
void sph_cli_write_used(const struct cmn_case *c, const char *dir);

#endif /* SABRE_SPH_CLI_H */
