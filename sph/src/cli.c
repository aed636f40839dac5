/* Command lines of the case-file commands (sph/src/cli.h) on common/'s cmn_cli_*. */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"

int sph_cli_parse(struct sph_cli *cli, int argc, char **argv, const char *usage,
                  const char *default_output, const struct sph_cli_option *extra, int nextra) {
  struct cmn_cli_option *options = cmn_malloc((size_t)(nextra > 0 ? nextra : 1) * sizeof *options);
  for (int e = 0; e < nextra; e++)
    options[e] = (struct cmn_cli_option){.name = extra[e].name, .value = extra[e].value};
  const char *command = argc > 0 ? argv[0] : "sabre-sph";
  int help = cmn_cli_parse(&cli->cmn, argc, argv, command, usage, default_output, options, nextra);
  free(options);
  cli->case_path = cli->cmn.case_path;
  cli->output = cli->cmn.output;
  return help;
}

struct cmn_case *sph_cli_load(struct sph_cli *cli) {
  return cmn_cli_load(&cli->cmn);
}

char *sph_cli_join(const char *dir, const char *name) {
  size_t len = strlen(dir) + strlen(name) + 2;
  char *p = cmn_malloc(len);
  snprintf(p, len, "%s/%s", dir, name);
  return p;
}

void sph_cli_write_used(const struct cmn_case *c, const char *dir) { cmn_cli_write_used(c, dir); }
