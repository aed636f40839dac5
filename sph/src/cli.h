/*
 * Command lines of the case-file commands of sabre-sph (`run`, `scalar`), parsed once here:
 *
 *   sabre-sph <command> CASE.yaml [--set key=value]... [--output DIR] [--<extra> VALUE]...
 *
 * then the case loaded with its --set overrides applied, and the run directory prepared. Bad input
 * stops the program with a message naming the command and exit code CMN_EXIT_INPUT (common/).
 */
#ifndef SABRE_SPH_CLI_H
#define SABRE_SPH_CLI_H

struct cmn_case;

/** An option of one command beyond --set and --output, taking one value (e.g. "--threads"). */
struct sph_cli_option {
  const char *name;   /**< with its dashes */
  const char **value; /**< receives the value (left alone when the option is absent) */
};

struct sph_cli {
  const char *command;   /**< argv[0], for messages */
  const char *case_path; /**< the one positional argument */
  const char *output;    /**< --output, or the command's default */
  int nsets;
  const char **sets; /**< the --set assignments in order (owned; freed by sph_cli_load) */
};

/**
 * Parse argv[1 .. argc) of a command (argv[0] is its name): one case file, --set (repeatable),
 * --output and the `nextra` options of `extra`. Returns 1 if --help or -h was given (usage then
 * printed on stdout, nothing to free), else 0. Unknown options, a missing value, no case file or
 * two of them stop the program.
 */
int sph_cli_parse(struct sph_cli *cli, int argc, char **argv, const char *usage,
                  const char *default_output, const struct sph_cli_option *extra, int nextra);
/** Load the case file and apply the --set overrides in order (stops the program on error). */
struct cmn_case *sph_cli_load(struct sph_cli *cli);
/** dir/name in a new string (free it). */
char *sph_cli_join(const char *dir, const char *name);
/** Create the run directory (mkdir -p) and write the case as used into dir/used_case.yaml. */
void sph_cli_write_used(const struct cmn_case *c, const char *dir);

#endif /* SABRE_SPH_CLI_H */
