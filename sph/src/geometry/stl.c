/* STL import and export, ASCII and binary.
 *
 * An STL surface bounds a solid; each facet's vertices run counter-clockwise seen from outside
 * that solid (right-hand normal pointing out of it), and the facet normal, when not zero, says
 * the same. With the fluid inside the surface (a tank) the walls' normals are the opposite of the
 * facets'; with the fluid outside (an obstacle) they are the facets'. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geometry/geometry.h"
#include "sabre/common.h"
#include "sabre/sph.h"

/* Add one facet read from the file; checks the facet normal against the vertex order. */
static int add_facet(struct sph_mesh *m, const double fn[3], double v[3][3], double scale,
                     int fluid_inside, uint8_t flags, int source, long tri, const char *where,
                     char *msg, size_t msglen) {
  double e1[3], e2[3], rh[3];
  for (int a = 0; a < 3; a++) {
    e1[a] = v[1][a] - v[0][a];
    e2[a] = v[2][a] - v[0][a];
  }
  geom_cross(e1, e2, rh);
  double nf = sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
  double nr = sqrt(rh[0] * rh[0] + rh[1] * rh[1] + rh[2] * rh[2]);
  if (nf > 0 && nr > 0 && (fn[0] * rh[0] + fn[1] * rh[1] + fn[2] * rh[2]) < -0.5 * nf * nr)
    return geom_fail(msg, msglen,
                     "%s: triangle %ld: its facet normal (%g, %g, %g) points against the vertex "
                     "order (right-hand rule: (%g, %g, %g)): inconsistent orientation",
                     where, tri, fn[0], fn[1], fn[2], rh[0] / nr, rh[1] / nr, rh[2] / nr);
  size_t idx[3];
  for (int k = 0; k < 3; k++) {
    double x[3] = {scale * v[k][0], scale * v[k][1], scale * v[k][2]};
    idx[k] = sph_mesh_add_vertex(m, x);
  }
  if (fluid_inside) {
    size_t t = idx[1];
    idx[1] = idx[2];
    idx[2] = t;
  }
  sph_mesh_add_element(m, idx, 0, flags, source, tri);
  return 0;
}

/* ASCII tokens with their line numbers. */
struct lexer {
  const char *p, *end;
  long line;
  char tok[256];
};

static int next_token(struct lexer *lx) {
  while (lx->p < lx->end && (*lx->p == ' ' || *lx->p == '\t' || *lx->p == '\r' || *lx->p == '\n')) {
    if (*lx->p == '\n') lx->line++;
    lx->p++;
  }
  size_t n = 0;
  while (lx->p < lx->end &&
         !(*lx->p == ' ' || *lx->p == '\t' || *lx->p == '\r' || *lx->p == '\n')) {
    if (n + 1 < sizeof lx->tok) lx->tok[n++] = *lx->p;
    lx->p++;
  }
  lx->tok[n] = '\0';
  return n > 0;
}

static void skip_line(struct lexer *lx) {
  while (lx->p < lx->end && *lx->p != '\n') lx->p++;
}

static int expect(struct lexer *lx, const char *word, const char *path, char *msg, size_t msglen) {
  if (next_token(lx) && strcmp(lx->tok, word) == 0) return 0;
  return geom_fail(msg, msglen, "%s:%ld: expected '%s', got '%s'", path, lx->line, word,
                   lx->p < lx->end || lx->tok[0] ? lx->tok : "end of file");
}

static int read_numbers(struct lexer *lx, double *x, const char *what, const char *path, char *msg,
                        size_t msglen) {
  for (int a = 0; a < 3; a++)
    if (!next_token(lx) || cmn_parse_double(lx->tok, &x[a]) != 0)
      return geom_fail(msg, msglen, "%s:%ld: expected three numbers after '%s', got '%s'", path,
                       lx->line, what, lx->tok[0] ? lx->tok : "end of file");
  return 0;
}

/* The rest of the current line, blanks trimmed at both ends (a solid's name; may be empty). */
static void rest_of_line(struct lexer *lx, char *out, size_t len) {
  while (lx->p < lx->end && (*lx->p == ' ' || *lx->p == '\t')) lx->p++;
  const char *b = lx->p;
  while (lx->p < lx->end && *lx->p != '\n') lx->p++;
  const char *e = lx->p;
  while (e > b && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r')) e--;
  size_t n = (size_t)(e - b) < len - 1 ? (size_t)(e - b) : len - 1;
  memcpy(out, b, n);
  out[n] = '\0';
}

static int read_ascii(struct sph_mesh *m, const char *buf, size_t len, const char *path,
                      double scale, int fluid_inside, const struct sph_stl_open *open,
                      unsigned char *found, int source, char *msg, size_t msglen) {
  struct lexer lx = {buf, buf + len, 1, ""};
  long tri = 0;
  int solids = 0;
  while (next_token(&lx)) {
    if (strcmp(lx.tok, "solid") != 0)
      return geom_fail(msg, msglen, "%s:%ld: expected 'solid', got '%s'", path, lx.line, lx.tok);
    char name[256];
    rest_of_line(&lx, name, sizeof name);
    uint8_t flags = open && open->all ? SPH_FLAG_OPEN : 0;
    for (int k = 0; open && k < open->n; k++)
      if (strcmp(open->names[k], name) == 0) {
        flags = SPH_FLAG_OPEN;
        found[k] = 1;
      }
    solids++;
    const long first = tri + 1;
    for (;;) {
      if (!next_token(&lx))
        return geom_fail(msg, msglen, "%s:%ld: expected 'facet' or 'endsolid', got end of file",
                         path, lx.line);
      if (strcmp(lx.tok, "endsolid") == 0) {
        skip_line(&lx);
        if (tri >= first) sph_mesh_add_part(m, source, name, first, tri);
        break;
      }
      if (strcmp(lx.tok, "facet") != 0)
        return geom_fail(msg, msglen, "%s:%ld: expected 'facet' or 'endsolid', got '%s'", path,
                         lx.line, lx.tok);
      double fn[3], v[3][3];
      long line = lx.line;
      if (expect(&lx, "normal", path, msg, msglen) ||
          read_numbers(&lx, fn, "normal", path, msg, msglen) ||
          expect(&lx, "outer", path, msg, msglen) || expect(&lx, "loop", path, msg, msglen))
        return -1;
      for (int k = 0; k < 3; k++)
        if (expect(&lx, "vertex", path, msg, msglen) ||
            read_numbers(&lx, v[k], "vertex", path, msg, msglen))
          return -1;
      if (expect(&lx, "endloop", path, msg, msglen) || expect(&lx, "endfacet", path, msg, msglen))
        return -1;
      char where[1100];
      snprintf(where, sizeof where, "%s:%ld", path, line);
      if (add_facet(m, fn, v, scale, fluid_inside, flags, source, ++tri, where, msg, msglen))
        return -1;
    }
  }
  if (solids == 0 || tri == 0) return geom_fail(msg, msglen, "%s: no facets", path);
  return 0;
}

static float get_f32(const unsigned char *p) {
  uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
  float f;
  memcpy(&f, &u, sizeof f);
  return f;
}

static void put_f32(unsigned char *p, float f) {
  uint32_t u;
  memcpy(&u, &f, sizeof u);
  for (int i = 0; i < 4; i++) p[i] = (unsigned char)(u >> (8 * i));
}

int sph_mesh_read_stl(struct sph_mesh *m, const char *path, double scale, int fluid_inside,
                      char *msg, size_t msglen) {
  return sph_mesh_read_stl_open(m, path, scale, fluid_inside, NULL, msg, msglen);
}

int sph_mesh_read_stl_open(struct sph_mesh *m, const char *path, double scale, int fluid_inside,
                           const struct sph_stl_open *open, char *msg, size_t msglen) {
  if (m->dim != 3) return geom_fail(msg, msglen, "%s: STL files describe 3D walls", path);
  FILE *f = fopen(path, "rb");
  if (!f) return geom_fail(msg, msglen, "%s: cannot open: %s", path, strerror(errno));
  size_t cap = 1 << 16, len = 0;
  unsigned char *buf = cmn_malloc(cap);
  for (size_t got; (got = fread(buf + len, 1, cap - len, f)) > 0;) {
    len += got;
    if (len == cap) buf = cmn_realloc(buf, cap *= 2);
  }
  int err = ferror(f);
  fclose(f);
  if (err) {
    free(buf);
    return geom_fail(msg, msglen, "%s: read error", path);
  }
  int source = sph_mesh_add_source(m, path);
  size_t v0 = m->nvert;
  int rc = 0;
  uint32_t count = 0;
  if (len >= 84)
    count = (uint32_t)buf[80] | (uint32_t)buf[81] << 8 | (uint32_t)buf[82] << 16 |
            (uint32_t)buf[83] << 24;
  const int nnames = open ? open->n : 0;
  unsigned char *found = cmn_calloc((size_t)nnames + 1, 1);
  if (len >= 84 && len == 84 + 50 * (size_t)count) {
    if (count == 0) rc = geom_fail(msg, msglen, "%s: binary STL with no triangles", path);
    if (nnames > 0 && rc == 0)
      rc = geom_fail(msg, msglen,
                     "%s: a binary STL file has no solid names: open solids by name need an "
                     "ASCII file ('solid NAME' ... 'endsolid'); or open the whole file",
                     path);
    const uint8_t flags = open && open->all ? SPH_FLAG_OPEN : 0;
    for (uint32_t t = 0; t < count && rc == 0; t++) {
      const unsigned char *r = buf + 84 + 50 * (size_t)t;
      double fn[3], v[3][3];
      for (int a = 0; a < 3; a++) fn[a] = get_f32(r + 4 * a);
      for (int k = 0; k < 3; k++)
        for (int a = 0; a < 3; a++) v[k][a] = get_f32(r + 12 + 12 * k + 4 * a);
      for (int k = 0; k < 3 && rc == 0; k++)
        if (!isfinite(v[k][0]) || !isfinite(v[k][1]) || !isfinite(v[k][2]))
          rc = geom_fail(msg, msglen, "%s: triangle %lu: non-finite vertex coordinate", path,
                         (unsigned long)t + 1);
      if (rc == 0)
        rc =
            add_facet(m, fn, v, scale, fluid_inside, flags, source, (long)t + 1, path, msg, msglen);
    }
  } else {
    size_t i = 0;
    while (i < len && (buf[i] == ' ' || buf[i] == '\t' || buf[i] == '\r' || buf[i] == '\n')) i++;
    if (len - i >= 5 && memcmp(buf + i, "solid", 5) == 0)
      rc = read_ascii(m, (const char *)buf, len, path, scale, fluid_inside, open, found, source,
                      msg, msglen);
    else if (len >= 84)
      rc = geom_fail(msg, msglen,
                     "%s: not an STL file: neither ASCII (starting with 'solid') nor binary "
                     "(84 + 50 n bytes for n triangles; this file has %zu bytes and says n = %lu)",
                     path, len, (unsigned long)count);
    else
      rc = geom_fail(msg, msglen,
                     "%s: not an STL file: neither ASCII (starting with 'solid') nor binary "
                     "(at least 84 bytes; this file has %zu)",
                     path, len);
  }
  free(buf);
  for (int k = 0; k < nnames && rc == 0; k++)
    if (!found[k])
      rc = geom_fail(msg, msglen, "%s: no solid named '%s' (the name after 'solid')", path,
                     open->names[k]);
  free(found);
  if (rc == 0 && m->nvert > v0) sph_mesh_merge_vertices(m, 0.0);
  return rc;
}

int sph_mesh_write_stl(const struct sph_mesh *m, const char *path, int binary) {
  if (m->dim != 3) {
    errno = EINVAL;
    return -1;
  }
  FILE *f = fopen(path, binary ? "wb" : "w");
  if (!f) return -1;
  if (binary) {
    unsigned char head[84] = "SABRE binary STL: normals point out of the fluid";
    uint32_t n = (uint32_t)m->nelem;
    for (int i = 0; i < 4; i++) head[80 + i] = (unsigned char)(n >> (8 * i));
    fwrite(head, 1, sizeof head, f);
  } else {
    fprintf(f, "solid sabre\n");
  }
  for (size_t e = 0; e < m->nelem; e++) {
    /* Out of the fluid: reverse the order, negate the normal. */
    const size_t order[3] = {m->elem[e][0], m->elem[e][2], m->elem[e][1]};
    double n[3] = {-m->normal[e][0], -m->normal[e][1], -m->normal[e][2]};
    if (binary) {
      unsigned char rec[50] = {0};
      for (int a = 0; a < 3; a++) put_f32(rec + 4 * a, (float)n[a]);
      for (int k = 0; k < 3; k++)
        for (int a = 0; a < 3; a++) put_f32(rec + 12 + 12 * k + 4 * a, (float)m->vert[order[k]][a]);
      fwrite(rec, 1, sizeof rec, f);
    } else {
      fprintf(f, "  facet normal %.17g %.17g %.17g\n    outer loop\n", n[0], n[1], n[2]);
      for (int k = 0; k < 3; k++)
        fprintf(f, "      vertex %.17g %.17g %.17g\n", m->vert[order[k]][0], m->vert[order[k]][1],
                m->vert[order[k]][2]);
      fprintf(f, "    endloop\n  endfacet\n");
    }
  }
  if (!binary) fprintf(f, "endsolid sabre\n");
  int bad = ferror(f);
  if (fclose(f) != 0 || bad) return -1;
  return 0;
}
