/* Command lines of the case-file commands (sph/src/cli.h). */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"

int sph_cli_parse(struct sph_cli *cli, int argc, char **argv, const char *usage,
                  const char *default_output, const struct sph_cli_option *extra, int nextra) {
  memset(cli, 0, sizeof *cli);
  cli->command = argc > 0 ? argv[0] : "sabre-sph";
  cli->output = default_output;
  cli->sets = cmn_malloc((size_t)(argc + 1) * sizeof *cli->sets);
  for (int k = 1; k < argc; k++) {
    const char *a = argv[k];
    if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
      fputs(usage, stdout);
      free(cli->sets);
      cli->sets = NULL;
      return 1;
    }
    const char **slot = NULL;
    if (strcmp(a, "--set") == 0)
      slot = &cli->sets[cli->nsets];
    else if (strcmp(a, "--output") == 0)
      slot = &cli->output;
    for (int e = 0; e < nextra && !slot; e++)
      if (strcmp(a, extra[e].name) == 0) slot = extra[e].value;
    if (slot) {
      if (k + 1 >= argc) cmn_input_error("%s: %s: missing value (see --help)", cli->command, a);
      *slot = argv[++k];
      if (slot == &cli->sets[cli->nsets]) cli->nsets++;
    } else if (a[0] == '-') {
      cmn_input_error("%s: unknown option '%s' (see --help)", cli->command, a);
    } else if (!cli->case_path) {
      cli->case_path = a;
    } else {
      cmn_input_error("%s: one case file only ('%s' and '%s')", cli->command, cli->case_path, a);
    }
  }
  if (!cli->case_path) cmn_input_error("%s: no case file given\n%s", cli->command, usage);
  return 0;
}

struct cmn_case *sph_cli_load(struct sph_cli *cli) {
  char err[2048];
  struct cmn_case *c = cmn_case_load(cli->case_path, err, sizeof err);
  if (!c) cmn_input_error("%s", err);
  for (int i = 0; i < cli->nsets; i++)
    if (cmn_case_set(c, cli->sets[i]) != 0)
      cmn_input_error("--set %s: %s", cli->sets[i], cmn_case_error(c));
  free(cli->sets);
  cli->sets = NULL;
  cli->nsets = 0;
  return c;
}

char *sph_cli_join(const char *dir, const char *name) {
  size_t len = strlen(dir) + strlen(name) + 2;
  char *p = cmn_malloc(len);
  snprintf(p, len, "%s/%s", dir, name);
  return p;
}

void sph_cli_write_used(const struct cmn_case *c, const char *dir) {
  if (cmn_mkdir_p(dir) != 0) cmn_input_error("cannot create the output directory '%s'", dir);
  char *used = sph_cli_join(dir, "used_case.yaml");
  if (cmn_case_write_file(c, used) != 0) cmn_input_error("cannot write '%s'", used);
  free(used);
}
