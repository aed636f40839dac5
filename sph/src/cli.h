/*
 * A helper of the case-file commands of sabre-sph (`run`, `scalar`). Their command lines
 * (CASE.yaml [--set key=value]... [--output DIR] ...) are parsed, loaded and recorded in
 * used_case.yaml by common/'s cmn_cli_* (sabre/common.h), called with the command's name (argv[0])
 * as the prefix of messages.
 */
#ifndef SABRE_SPH_CLI_H
#define SABRE_SPH_CLI_H

/** dir/name in a new string (free it). */
char *sph_cli_join(const char *dir, const char *name);

#endif /* SABRE_SPH_CLI_H */
