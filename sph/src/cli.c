/* A helper of the case-file commands (sph/src/cli.h). */
#include "cli.h"

#include <stdio.h>
#include <string.h>

#include "sabre/common.h"

char *sph_cli_join(const char *dir, const char *name) {
  size_t len = strlen(dir) + strlen(name) + 2;
  char *p = cmn_malloc(len);
  snprintf(p, len, "%s/%s", dir, name);
  return p;
}
