/* Command lines of the case-file programs (common.h, "Command lines"): parsing, loading the case
 * with its --set overrides, and the run directory with used_case.yaml. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"

/* cmn_input_error() with the command's name first, when there is one. */
static _Noreturn void cli_error(const struct cmn_cli *cli, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static _Noreturn void cli_error(const struct cmn_cli *cli, const char *fmt, ...) {
  char buf[2048];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  if (cli->command != NULL) cmn_input_error("%s: %s", cli->command, buf);
  cmn_input_error("%s", buf);
}

int cmn_cli_parse(struct cmn_cli *cli, int argc, char **argv, const char *command,
                  const char *usage, const char *default_output,
                  const struct cmn_cli_option *options, int noptions) {
  memset(cli, 0, sizeof *cli);
  cli->command = command;
  cli->output = default_output;
  int *given = cmn_calloc((size_t)noptions + 1, sizeof *given); /* options, then --output */
  /* At most one --set per two arguments: argc entries are plenty. */
  cli->sets = cmn_malloc((size_t)(argc > 0 ? argc : 1) * sizeof *cli->sets);
  for (int k = 1; k < argc; k++) {
    const char *a = argv[k];
    if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0 || strcmp(a, "--version") == 0) {
      if (a[2] == 'v')
        cmn_print_version();
      else
        fputs(usage, stdout);
      free(cli->sets);
      cli->sets = NULL;
      free(given);
      return 1;
    }
    const char **slot = NULL;
    const struct cmn_cli_option *opt = NULL;
    if (strcmp(a, "--set") == 0)
      slot = &cli->sets[cli->nsets];
    else if (strcmp(a, "--output") == 0)
      slot = &cli->output;
    else
      for (int e = 0; e < noptions && opt == NULL; e++)
        if (strcmp(a, options[e].name) == 0) opt = &options[e];
    /* Each option once: a second value would silently replace the first. */
    if (opt != NULL || slot == &cli->output) {
      int *seen = opt != NULL ? &given[opt - options] : &given[noptions];
      if (*seen) {
        free(given);
        cli_error(cli, "%s given twice: give each option once", a);
      }
      *seen = 1;
    }
    if (opt != NULL && opt->flag) {
      *opt->value = opt->name;
      continue;
    }
    if (opt != NULL) slot = opt->value;
    if (slot != NULL) {
      if (k + 1 >= argc) cli_error(cli, "%s: missing value (see --help)", a);
      *slot = argv[++k];
      if (slot == &cli->sets[cli->nsets]) cli->nsets++;
    } else if (a[0] == '-') {
      cli_error(cli, "unknown option '%s' (see --help)", a);
    } else if (cli->case_path == NULL) {
      cli->case_path = a;
    } else {
      cli_error(cli, "one case file only ('%s' and '%s')", cli->case_path, a);
    }
  }
  free(given);
  if (cli->case_path == NULL) cli_error(cli, "missing case file (see --help)");
  return 0;
}

struct cmn_case *cmn_cli_load(struct cmn_cli *cli) {
  char err[2048];
  struct cmn_case *c = cmn_case_load(cli->case_path, err, sizeof err);
  if (c == NULL) cmn_input_error("%s", err);
  /* The case is in fatal mode: a bad assignment exits with the case's message. */
  for (int i = 0; i < cli->nsets; i++) cmn_case_set(c, cli->sets[i]);
  free(cli->sets);
  cli->sets = NULL;
  cli->nsets = 0;
  return c;
}

void cmn_cli_write_used(const struct cmn_case *c, const char *dir) {
  if (cmn_mkdir_p(dir) != 0)
    cmn_input_error("cannot create the output directory '%s': %s", dir, strerror(errno));
  size_t len = strlen(dir) + sizeof "/used_case.yaml";
  char *path = cmn_malloc(len);
  snprintf(path, len, "%s/used_case.yaml", dir);
  errno = 0;
  if (cmn_case_write_file(c, path) != 0)
    cmn_input_error("cannot write '%s': %s", path, errno ? strerror(errno) : "write error");
  free(path);
}
