/* CSV output: one header line, then rows of numbers printed with %.17g so that reading a file
 * back gives the very doubles that were written. Write errors are remembered and reported by
 * cmn_csv_close(), so a long run need not check every row. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"

struct cmn_csv {
  FILE *out;
  int ncols;
  int failed;
};

/* A column name needs quotes (RFC 4180) if it holds a separator, a quote or a line break; also,
 * for cmn_table_read() to give it back unchanged, if it starts with '#' (a comment line) or
 * starts or ends with a blank (dropped around unquoted cells). */
static int needs_quotes(const char *name) {
  size_t len = strlen(name);
  if (strpbrk(name, ",\"\r\n") != NULL || name[0] == '#') return 1;
  return len > 0 && (strchr(" \t", name[0]) != NULL || strchr(" \t", name[len - 1]) != NULL);
}

static int write_name(FILE *out, const char *name) {
  if (!needs_quotes(name)) return fputs(name, out) < 0 ? -1 : 0;
  if (fputc('"', out) == EOF) return -1;
  for (const char *p = name; *p != '\0'; ++p) {
    if (*p == '"' && fputc('"', out) == EOF) return -1;
    if (fputc(*p, out) == EOF) return -1;
  }
  return fputc('"', out) == EOF ? -1 : 0;
}

struct cmn_csv *cmn_csv_open(const char *path, int ncols, const char *const *names) {
  FILE *out = fopen(path, "w");
  if (out == NULL) return NULL;
  struct cmn_csv *csv = cmn_malloc(sizeof *csv);
  csv->out = out;
  csv->ncols = ncols;
  csv->failed = 0;
  for (int i = 0; i < ncols; ++i) {
    if ((i > 0 && fputc(',', out) == EOF) || write_name(out, names[i]) != 0) csv->failed = 1;
  }
  if (fputc('\n', out) == EOF) csv->failed = 1;
  if (csv->failed) {
    fclose(out);
    free(csv);
    return NULL;
  }
  return csv;
}

int cmn_csv_row(struct cmn_csv *csv, const double *values) {
  for (int i = 0; i < csv->ncols; ++i) {
    if (fprintf(csv->out, i > 0 ? ",%.17g" : "%.17g", values[i]) < 0) csv->failed = 1;
  }
  if (fputc('\n', csv->out) == EOF) csv->failed = 1;
  return csv->failed ? -1 : 0;
}

int cmn_csv_flush(struct cmn_csv *csv) {
  if (fflush(csv->out) != 0) csv->failed = 1;
  return csv->failed ? -1 : 0;
}

int cmn_csv_close(struct cmn_csv *csv) {
  if (csv == NULL) return 0;
  int failed = csv->failed || ferror(csv->out);
  if (fclose(csv->out) != 0) failed = 1;
  free(csv);
  return failed ? -1 : 0;
}
