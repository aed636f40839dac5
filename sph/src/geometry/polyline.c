/* 2D polyline files (format: docs/sph-geometry.md):
 *
 *   # comment                 (anything after '#' is ignored; blank lines too)
 *   polygon                   starts a closed polyline ("polyline" starts an open one)
 *   0.0 0.0                   a point "x y" [m]
 *   1.0 0.0 open              "open": the edge from this point to the next is an open boundary
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geometry/geometry.h"
#include "sabre/common.h"
#include "sabre/sph.h"

struct polyline {
  int closed;
  long line; /* where it starts, for messages */
  size_t n, cap;
  double (*pts)[2];
  uint8_t *open;
  long *lines; /* line of each point */
};

/* Add the finished polyline to the mesh, or complain that it is too short. */
static int flush(struct sph_mesh *m, struct polyline *pl, const char *path, int fluid_inside,
                 int source, long *numbered, char *msg, size_t msglen) {
  if (pl->line == 0) return 0;
  size_t need = pl->closed ? 3 : 2;
  if (pl->n < need)
    return geom_fail(msg, msglen, "%s:%ld: %s with %zu point%s: it needs at least %zu", path,
                     pl->line, pl->closed ? "polygon" : "polyline", pl->n, pl->n == 1 ? "" : "s",
                     need);
  if (!pl->closed && pl->open[pl->n - 1])
    return geom_fail(
        msg, msglen,
        "%s:%ld: the last point of an open polyline starts no edge: 'open' not allowed "
        "there",
        path, pl->line);
  size_t e0 = m->nelem;
  sph_mesh_polygon(m, pl->n, (const double(*)[2])pl->pts, pl->closed, fluid_inside, pl->open,
                   source);
  /* Segments are numbered through the file (force groups select them by number); messages also
   * give the line of the segment's first point. */
  for (size_t e = e0; e < m->nelem; e++) {
    m->source_index[e] = ++*numbered;
    m->source_line[e] = pl->lines[e - e0];
  }
  pl->n = 0;
  pl->line = 0;
  return 0;
}

int sph_mesh_read_polyline(struct sph_mesh *m, const char *path, int fluid_inside, char *msg,
                           size_t msglen) {
  if (m->dim != 2) return geom_fail(msg, msglen, "%s: polyline files describe 2D walls", path);
  FILE *f = fopen(path, "r");
  if (!f) return geom_fail(msg, msglen, "%s: cannot open: %s", path, strerror(errno));
  int source = sph_mesh_add_source(m, path);
  struct polyline pl = {0};
  char buf[1024];
  long line = 0;
  int rc = 0, count = 0;
  long numbered = 0;
  while (rc == 0 && fgets(buf, sizeof buf, f)) {
    line++;
    if (!strchr(buf, '\n') && !feof(f)) {
      rc = geom_fail(msg, msglen, "%s:%ld: line longer than %zu characters", path, line,
                     sizeof buf - 2);
      break;
    }
    char *hash = strchr(buf, '#');
    if (hash) *hash = '\0';
    char *tok[4];
    int nt = 0;
    for (char *save = NULL, *t = strtok_r(buf, " \t\r\n", &save); t;
         t = strtok_r(NULL, " \t\r\n", &save))
      if (nt < 4)
        tok[nt++] = t;
      else
        nt = 5;
    if (nt == 0) continue;
    if (nt == 1 && (strcmp(tok[0], "polygon") == 0 || strcmp(tok[0], "polyline") == 0)) {
      rc = flush(m, &pl, path, fluid_inside, source, &numbered, msg, msglen);
      pl.closed = strcmp(tok[0], "polygon") == 0;
      pl.line = line;
      count++;
      continue;
    }
    double x, y;
    int ok = (nt == 2 || (nt == 3 && strcmp(tok[2], "open") == 0)) &&
             cmn_parse_double(tok[0], &x) == 0 && cmn_parse_double(tok[1], &y) == 0;
    if (!ok) {
      rc = geom_fail(msg, msglen,
                     "%s:%ld: expected 'polygon', 'polyline', or a point 'x y' optionally followed "
                     "by 'open'",
                     path, line);
      break;
    }
    if (pl.line == 0) {
      rc = geom_fail(msg, msglen, "%s:%ld: point before any 'polygon' or 'polyline' line", path,
                     line);
      break;
    }
    if (pl.n == pl.cap) {
      pl.cap = pl.cap ? 2 * pl.cap : 16;
      pl.pts = cmn_realloc(pl.pts, pl.cap * sizeof *pl.pts);
      pl.open = cmn_realloc(pl.open, pl.cap);
      pl.lines = cmn_realloc(pl.lines, pl.cap * sizeof *pl.lines);
    }
    pl.pts[pl.n][0] = x;
    pl.pts[pl.n][1] = y;
    pl.lines[pl.n] = line;
    pl.open[pl.n++] = nt == 3;
  }
  if (rc == 0 && ferror(f)) rc = geom_fail(msg, msglen, "%s: read error", path);
  if (rc == 0) rc = flush(m, &pl, path, fluid_inside, source, &numbered, msg, msglen);
  if (rc == 0 && count == 0)
    rc = geom_fail(msg, msglen, "%s:%ld: no 'polygon' or 'polyline' in the file", path, line);
  free(pl.pts);
  free(pl.open);
  free(pl.lines);
  fclose(f);
  return rc;
}
