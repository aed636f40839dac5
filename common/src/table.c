/* CSV tables: the reader for the files cmn_csv_open()/cmn_csv_row() write, and for tables users
 * write by hand or export from a spreadsheet; linear interpolation in them.
 *
 * The whole file is read into memory before parsing: tables are small, a quoted name may then
 * span lines (RFC 4180), and no line is ever too long for a buffer. Every problem is reported
 * with the file, the line of the record and, for a cell, its column, so that a user can go
 * straight to it. */
#include <errno.h>
#include <fenv.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"

/* ---------------------------------------------------------------------------------------------
 * Messages
 * ------------------------------------------------------------------------------------------- */

/* "<path>:<line>: <message>", or "<path>: <message>" for line 0. Always returns -1. */
static int vfail(char *err, size_t errlen, const char *path, long line, const char *fmt,
                 va_list ap) {
  if (err == NULL || errlen == 0) return -1;
  char msg[768];
  vsnprintf(msg, sizeof msg, fmt, ap);
  if (line > 0)
    snprintf(err, errlen, "%s:%ld: %s", path, line, msg);
  else
    snprintf(err, errlen, "%s: %s", path, msg);
  return -1;
}

static int fail(char *err, size_t errlen, const char *path, long line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
static int fail(char *err, size_t errlen, const char *path, long line, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vfail(err, errlen, path, line, fmt, ap);
  va_end(ap);
  return -1;
}

/* Cell text as quoted in a message: at most 40 characters, so that a binary or misformatted
 * file does not flood the terminal. */
static const char *shown(const char *text, char *buf, size_t buflen) {
  enum { MAX = 40 };
  size_t len = strlen(text);
  if (len <= MAX) return text;
  snprintf(buf, buflen, "%.*s...", MAX, text);
  return buf;
}

/* A %g form that reads back to x: 15 significant digits (trailing zeros dropped) when they are
 * enough, so that values in messages look like the file, 17 when needed. */
static void format_exact(double x, char *buf, size_t buflen) {
  for (int prec = 15; prec <= 17; ++prec) {
    if (snprintf(buf, buflen, "%.*g", prec, x) >= (int)buflen) break;
    if (strtod(buf, NULL) == x) return;
  }
  snprintf(buf, buflen, "%.17g", x);
}

static char *copy_string(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = cmn_malloc(n);
  memcpy(d, s, n);
  return d;
}

/* ---------------------------------------------------------------------------------------------
 * Parser
 * ------------------------------------------------------------------------------------------- */

/* Growable text of one cell, NUL-terminated. */
struct cell {
  char *s;
  size_t len, cap;
};

static void cell_clear(struct cell *c) {
  if (c->cap == 0) {
    c->cap = 64;
    c->s = cmn_malloc(c->cap);
  }
  c->len = 0;
  c->s[0] = '\0';
}

static void cell_put(struct cell *c, char ch) {
  if (c->len + 1 >= c->cap) {
    c->cap *= 2;
    c->s = cmn_realloc(c->s, c->cap);
  }
  c->s[c->len++] = ch;
  c->s[c->len] = '\0';
}

struct reader {
  const char *path;
  const char *p, *end; /* cursor in the file text; end of the text */
  long line;           /* line of the cursor, 1-based */
  char *err;
  size_t errlen;
  struct cell cell;
};

static int at_eol(const struct reader *r) {
  return r->p == r->end || *r->p == '\n' || *r->p == '\r';
}

/* Step over the line end at the cursor (LF, CRLF or a lone CR); nothing at the end of text. */
static void skip_eol(struct reader *r) {
  if (r->p == r->end) return;
  if (*r->p == '\r' && r->p + 1 < r->end && r->p[1] == '\n') ++r->p;
  ++r->p;
  ++r->line;
}

static void skip_blanks(struct reader *r) {
  while (r->p < r->end && (*r->p == ' ' || *r->p == '\t')) ++r->p;
}

/* Skip blank lines and comment lines. 1 if a record starts at the cursor, 0 at the end. */
static int next_record(struct reader *r) {
  for (;;) {
    skip_blanks(r);
    if (r->p == r->end) return 0;
    if (*r->p == '#')
      while (!at_eol(r)) ++r->p;
    if (!at_eol(r)) return 1;
    skip_eol(r);
  }
}

/* The cell at the cursor of the record starting on `line`, unquoted, into r->cell. Blanks around
 * a cell are dropped, blanks inside quotes kept. Leaves the cursor on the ',' or the line end
 * that follows the cell. */
static int read_cell(struct reader *r, long line, int col) {
  cell_clear(&r->cell);
  skip_blanks(r);
  if (r->p < r->end && *r->p == '"') {
    ++r->p;
    for (;;) {
      if (r->p == r->end)
        return fail(r->err, r->errlen, r->path, line, "column %d: the quote is never closed", col);
      char ch = *r->p++;
      if (ch == '"') {
        if (r->p == r->end || *r->p != '"') break;
        ++r->p; /* "" stands for one quote */
      }
      if (ch == '\n' || (ch == '\r' && (r->p == r->end || *r->p != '\n'))) ++r->line;
      cell_put(&r->cell, ch);
    }
    skip_blanks(r);
    if (!at_eol(r) && *r->p != ',')
      return fail(r->err, r->errlen, r->path, line,
                  "column %d: expected ',' or the end of the line after the closing quote", col);
    return 0;
  }
  while (!at_eol(r) && *r->p != ',') cell_put(&r->cell, *r->p++);
  while (r->cell.len > 0 &&
         (r->cell.s[r->cell.len - 1] == ' ' || r->cell.s[r->cell.len - 1] == '\t'))
    r->cell.s[--r->cell.len] = '\0';
  return 0;
}

/* After a cell: 1 if another cell of the same record follows (the ',' is consumed), 0 at the end
 * of the record (its line end is consumed). */
static int more_cells(struct reader *r) {
  if (r->p < r->end && *r->p == ',') {
    ++r->p;
    return 1;
  }
  skip_eol(r);
  return 0;
}

static int read_header(struct reader *r, struct cmn_table *t) {
  const long line = r->line;
  int cap = 0;
  t->header_line = line;
  for (int col = 1;; ++col) {
    if (read_cell(r, line, col) != 0) return -1;
    if (r->cell.len == 0)
      return fail(r->err, r->errlen, r->path, line, "column %d of the header: empty name", col);
    if (t->ncols == cap) {
      cap = cap > 0 ? 2 * cap : 8;
      t->names = cmn_realloc(t->names, (size_t)cap * sizeof *t->names);
    }
    t->names[t->ncols++] = copy_string(r->cell.s);
    if (!more_cells(r)) break;
  }
  /* A file without a header would otherwise lose its first row to column names like "0". */
  int numbers = 0;
  double x;
  for (int k = 0; k < t->ncols; ++k) numbers += cmn_parse_double(t->names[k], &x) == 0;
  if (numbers == t->ncols)
    return fail(r->err, r->errlen, r->path, line,
                "expected a header line of column names, got only numbers");
  for (int j = 1; j < t->ncols; ++j)
    for (int k = 0; k < j; ++k)
      if (strcmp(t->names[k], t->names[j]) == 0) {
        char buf[64];
        return fail(r->err, r->errlen, r->path, line,
                    "column %d of the header: duplicate name '%s' (also column %d)", j + 1,
                    shown(t->names[j], buf, sizeof buf), k + 1);
      }
  return 0;
}

/* 0: a finite number; -1: not a number; -2: a number that is not finite (nan, inf, 1e400). */
static int parse_cell(const char *text, double *x) {
  if (cmn_parse_double(text, x) == 0) return 0;
  if (text[0] == '\0' || text[0] == ' ' || text[0] == '\t') return -1;
  fenv_t env; /* 1e400 overflows inside strtod: keep that from callers that trap it */
  feholdexcept(&env);
  char *end = NULL;
  double v = strtod(text, &end);
  fesetenv(&env);
  (void)v;
  return end != text && *end == '\0' ? -2 : -1;
}

static int read_row(struct reader *r, const struct cmn_table *t, double *row) {
  const long line = r->line;
  int col = 0;
  do {
    if (read_cell(r, line, col + 1) != 0) return -1;
    if (col < t->ncols) {
      int status = parse_cell(r->cell.s, &row[col]);
      if (status != 0) {
        char buf[2][64];
        const char *name = shown(t->names[col], buf[0], sizeof buf[0]);
        if (r->cell.len == 0)
          return fail(r->err, r->errlen, r->path, line,
                      "column %d ('%s'): expected a number, got an empty cell", col + 1, name);
        return fail(r->err, r->errlen, r->path, line,
                    "column %d ('%s'): expected a %snumber, got '%s'", col + 1, name,
                    status == -2 ? "finite " : "", shown(r->cell.s, buf[1], sizeof buf[1]));
      }
    }
    ++col;
  } while (more_cells(r));
  if (col != t->ncols)
    return fail(r->err, r->errlen, r->path, line,
                "expected %d cell%s as in the header (line %ld), got %d", t->ncols,
                t->ncols == 1 ? "" : "s", t->header_line, col);
  return 0;
}

static int parse(struct reader *r, struct cmn_table *t) {
  const char *nul = memchr(r->p, '\0', (size_t)(r->end - r->p));
  if (nul != NULL) {
    long line = 1;
    for (const char *q = r->p; q < nul; ++q) line += *q == '\n';
    return fail(r->err, r->errlen, r->path, line, "NUL byte: this is not a text file");
  }
  if (r->end - r->p >= 3 && memcmp(r->p, "\xEF\xBB\xBF", 3) == 0) r->p += 3; /* UTF-8 BOM */
  if (!next_record(r))
    return fail(r->err, r->errlen, r->path, 0,
                "no header line (the file is empty or holds only comments and blank lines)");
  if (read_header(r, t) != 0) return -1;
  const size_t ncols = (size_t)t->ncols;
  size_t cap = 0;
  while (next_record(r)) {
    if (t->nrows == cap) {
      cap = cap > 0 ? 2 * cap : 64;
      t->data = cmn_realloc(t->data, cap * ncols * sizeof *t->data);
      t->lines = cmn_realloc(t->lines, cap * sizeof *t->lines);
    }
    t->lines[t->nrows] = r->line;
    if (read_row(r, t, t->data + t->nrows * ncols) != 0) return -1;
    ++t->nrows;
  }
  if (t->nrows == 0)
    return fail(r->err, r->errlen, r->path, 0, "no data rows after the header (line %ld)",
                t->header_line);
  return 0;
}

/* The whole file, NUL-terminated, length in *len; NULL with a message on failure. */
static char *read_file(const char *path, size_t *len, char *err, size_t errlen) {
  FILE *f = fopen(path, "rb");
  if (f == NULL) {
    fail(err, errlen, path, 0, "cannot open: %s", strerror(errno));
    return NULL;
  }
  size_t n = 0, cap = 4096;
  char *text = cmn_malloc(cap);
  for (;;) {
    n += fread(text + n, 1, cap - n - 1, f);
    if (n + 1 < cap) break;
    cap *= 2;
    text = cmn_realloc(text, cap);
  }
  int failed = ferror(f), saved = errno;
  fclose(f);
  if (failed) {
    fail(err, errlen, path, 0, "cannot read: %s", strerror(saved));
    free(text);
    return NULL;
  }
  text[n] = '\0';
  *len = n;
  return text;
}

int cmn_table_read(const char *path, struct cmn_table *t, char *err, size_t errlen) {
  memset(t, 0, sizeof *t);
  if (err != NULL && errlen > 0) err[0] = '\0';
  size_t len = 0;
  char *text = read_file(path, &len, err, errlen);
  if (text == NULL) return -1;
  struct reader r = {
      .path = path, .p = text, .end = text + len, .line = 1, .err = err, .errlen = errlen};
  int status = parse(&r, t);
  free(text);
  free(r.cell.s);
  if (status != 0) {
    cmn_table_free(t);
    return -1;
  }
  t->path = copy_string(path);
  return 0;
}

void cmn_table_free(struct cmn_table *t) {
  if (t == NULL) return;
  for (int k = 0; k < t->ncols && t->names != NULL; ++k) free(t->names[k]);
  free(t->names);
  free(t->data);
  free(t->lines);
  free(t->path);
  memset(t, 0, sizeof *t);
}

int cmn_table_column(const struct cmn_table *t, const char *name) {
  for (int k = 0; k < t->ncols; ++k)
    if (strcmp(t->names[k], name) == 0) return k;
  return -1;
}

/* Names joined by ',' into buf (truncated with "..." if too long). */
static void join_names(int n, const char *const *names, char *buf, size_t buflen) {
  size_t used = 0;
  buf[0] = '\0';
  for (int k = 0; k < n; ++k) {
    int w = snprintf(buf + used, buflen - used, "%s%s", k > 0 ? "," : "", names[k]);
    if (w < 0 || (size_t)w >= buflen - used) {
      if (buflen > 4) memcpy(buf + buflen - 4, "...", 4);
      return;
    }
    used += (size_t)w;
  }
}

int cmn_table_expect_columns(const struct cmn_table *t, int ncols, const char *const *names,
                             char *err, size_t errlen) {
  int same = t->ncols == ncols;
  for (int k = 0; same && k < ncols; ++k) same = strcmp(t->names[k], names[k]) == 0;
  if (same) return 0;
  char want[256], got[256];
  join_names(ncols, names, want, sizeof want);
  join_names(t->ncols, (const char *const *)t->names, got, sizeof got);
  return fail(err, errlen, t->path, t->header_line, "the header must be '%s', got '%s'", want, got);
}

int cmn_table_check_increasing(const struct cmn_table *t, int col, char *err, size_t errlen) {
  if (col < 0 || col >= t->ncols)
    return fail(err, errlen, t->path, 0, "no column %d (the table has %d)", col + 1, t->ncols);
  const size_t nc = (size_t)t->ncols;
  for (size_t i = 1; i < t->nrows; ++i) {
    double prev = t->data[(i - 1) * nc + (size_t)col], x = t->data[i * nc + (size_t)col];
    if (!(x > prev)) {
      char a[40], b[40], buf[64];
      format_exact(x, a, sizeof a);
      format_exact(prev, b, sizeof b);
      return fail(err, errlen, t->path, t->lines[i],
                  "column %d ('%s'): values must increase strictly, got %s after %s (line %ld)",
                  col + 1, shown(t->names[col], buf, sizeof buf), a, b, t->lines[i - 1]);
    }
  }
  return 0;
}

/* ---------------------------------------------------------------------------------------------
 * Interpolation
 * ------------------------------------------------------------------------------------------- */

double cmn_interp_linear(size_t n, const double *x, const double *y, size_t stride, double xq) {
  /* NaN first: the ordered comparisons below would raise FE_INVALID on it. */
  if (n == 0 || isnan(xq)) return NAN;
  const size_t last = (n - 1) * stride;
  if (xq <= x[0]) return y[0];
  if (xq >= x[last]) return y[last];
  size_t lo = 0, hi = n - 1; /* bisection on x[lo] ≤ xq < x[hi] */
  while (hi - lo > 1) {
    size_t mid = lo + (hi - lo) / 2;
    if (x[mid * stride] <= xq)
      lo = mid;
    else
      hi = mid;
  }
  const double x0 = x[lo * stride], x1 = x[hi * stride];
  const double y0 = y[lo * stride], y1 = y[hi * stride];
  const double w = (xq - x0) / (x1 - x0);
  return y0 + w * (y1 - y0);
}

double cmn_table_interp(const struct cmn_table *t, int xcol, int ycol, double x) {
  return cmn_interp_linear(t->nrows, t->data + xcol, t->data + ycol, (size_t)t->ncols, x);
}
