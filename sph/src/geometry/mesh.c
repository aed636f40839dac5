/* Wall meshes: storage, vertex merging, refinement to elements of size ≈ Δr, consistency checks.
 *
 * Orientation convention (sph.h): 2D fluid to the left of v0 → v1; 3D right-hand normal of
 * (v0, v1, v2) into the fluid; 1D explicit normal ±1. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geometry/geometry.h"
#include "sabre/common.h"
#include "sabre/sph.h"

void sph_mesh_init(struct sph_mesh *m, int dim) {
  memset(m, 0, sizeof *m);
  m->dim = dim;
}

void sph_mesh_free(struct sph_mesh *m) {
  free(m->vert);
  free(m->elem);
  free(m->normal);
  free(m->flags);
  free(m->source);
  free(m->source_index);
  free(m->source_line);
  for (int i = 0; i < m->nsources; i++) free(m->sources[i]);
  free(m->sources);
  free(m->parts);
  sph_mesh_init(m, m->dim);
}

int sph_mesh_add_source(struct sph_mesh *m, const char *name) {
  m->sources = cmn_realloc(m->sources, (size_t)(m->nsources + 1) * sizeof *m->sources);
  size_t len = strlen(name) + 1;
  m->sources[m->nsources] = memcpy(cmn_malloc(len), name, len);
  return m->nsources++;
}

void sph_mesh_add_part(struct sph_mesh *m, int source, const char *name, long first, long last) {
  m->parts = cmn_realloc(m->parts, (size_t)(m->nparts + 1) * sizeof *m->parts);
  struct sph_mesh_part *pt = &m->parts[m->nparts++];
  pt->source = source;
  pt->first = first;
  pt->last = last;
  snprintf(pt->name, sizeof pt->name, "%s", name);
}

/* The sources and named parts of src into the empty mesh dst (refinement). */
static void copy_sources(struct sph_mesh *dst, const struct sph_mesh *src) {
  for (int i = 0; i < src->nsources; i++) sph_mesh_add_source(dst, src->sources[i]);
  for (int i = 0; i < src->nparts; i++)
    sph_mesh_add_part(dst, src->parts[i].source, src->parts[i].name, src->parts[i].first,
                      src->parts[i].last);
}

size_t sph_mesh_add_vertex(struct sph_mesh *m, const double *x) {
  if (m->nvert == m->cap_vert) {
    m->cap_vert = m->cap_vert ? 2 * m->cap_vert : 64;
    m->vert = cmn_realloc(m->vert, m->cap_vert * sizeof *m->vert);
  }
  double *v = m->vert[m->nvert];
  for (int a = 0; a < 3; a++) v[a] = a < m->dim ? x[a] : 0.0;
  return m->nvert++;
}

void geom_element_normal(int dim, const double v[3][3], double normal1d, double *n) {
  n[0] = n[1] = n[2] = 0;
  if (dim == 1) {
    n[0] = normal1d;
    return;
  }
  if (dim == 2) {
    double dx = v[1][0] - v[0][0], dy = v[1][1] - v[0][1], len = hypot(dx, dy);
    if (len > 0) {
      n[0] = -dy / len;
      n[1] = dx / len;
    }
    return;
  }
  double e1[3], e2[3];
  for (int a = 0; a < 3; a++) {
    e1[a] = v[1][a] - v[0][a];
    e2[a] = v[2][a] - v[0][a];
  }
  geom_cross(e1, e2, n);
  double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int a = 0; a < 3; a++) n[a] = len > 0 ? n[a] / len : 0.0;
}

double geom_element_measure(int dim, const double v[3][3]) {
  if (dim == 1) return 1.0;
  if (dim == 2) return hypot(v[1][0] - v[0][0], v[1][1] - v[0][1]);
  double e1[3], e2[3], c[3];
  for (int a = 0; a < 3; a++) {
    e1[a] = v[1][a] - v[0][a];
    e2[a] = v[2][a] - v[0][a];
  }
  geom_cross(e1, e2, c);
  return 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

void geom_element_vertices(const struct sph_mesh *m, size_t e, double v[3][3]) {
  for (int k = 0; k < 3; k++)
    for (int a = 0; a < 3; a++) v[k][a] = k < m->dim ? m->vert[m->elem[e][k]][a] : 0.0;
}

size_t sph_mesh_add_element(struct sph_mesh *m, const size_t *v, double normal1d, uint8_t flags,
                            int source, long source_index) {
  if (m->nelem == m->cap_elem) {
    m->cap_elem = m->cap_elem ? 2 * m->cap_elem : 64;
    m->elem = cmn_realloc(m->elem, m->cap_elem * sizeof *m->elem);
    m->normal = cmn_realloc(m->normal, m->cap_elem * sizeof *m->normal);
    m->flags = cmn_realloc(m->flags, m->cap_elem * sizeof *m->flags);
    m->source = cmn_realloc(m->source, m->cap_elem * sizeof *m->source);
    m->source_index = cmn_realloc(m->source_index, m->cap_elem * sizeof *m->source_index);
    m->source_line = cmn_realloc(m->source_line, m->cap_elem * sizeof *m->source_line);
  }
  size_t e = m->nelem++;
  for (int k = 0; k < 3; k++) m->elem[e][k] = k < m->dim ? v[k] : 0;
  double x[3][3];
  geom_element_vertices(m, e, x);
  geom_element_normal(m->dim, x, normal1d, m->normal[e]);
  m->flags[e] = flags;
  m->source[e] = source;
  m->source_index[e] = source_index;
  m->source_line[e] = 0;
  return e;
}

/* Copy element e of src (with its vertex indices replaced by v) to dst. */
static void copy_element(struct sph_mesh *dst, const struct sph_mesh *src, size_t e,
                         const size_t *v) {
  size_t f = sph_mesh_add_element(dst, v, src->normal[e][0], src->flags[e], src->source[e],
                                  src->source_index[e]);
  /* Children of a planar element keep the parent's exact normal. */
  memcpy(dst->normal[f], src->normal[e], sizeof dst->normal[f]);
  dst->source_line[f] = src->source_line[e];
}

/* --------------------------------------------------------------------------------------------
 * Vertex merging: sort by quantised coordinates, merge runs of equal keys, drop unused vertices.
 * ------------------------------------------------------------------------------------------ */
struct vertex_key {
  double k[3]; /* coordinates, or rounded multiples of the tolerance */
  size_t index;
};

static int key_equal(const struct vertex_key *a, const struct vertex_key *b) {
  return a->k[0] == b->k[0] && a->k[1] == b->k[1] && a->k[2] == b->k[2];
}

static int key_cmp(const void *pa, const void *pb) {
  const struct vertex_key *a = pa, *b = pb;
  for (int c = 0; c < 3; c++)
    if (a->k[c] != b->k[c]) return a->k[c] < b->k[c] ? -1 : 1;
  return (a->index > b->index) - (a->index < b->index);
}

void sph_mesh_merge_vertices(struct sph_mesh *m, double tol) {
  size_t n = m->nvert;
  if (n == 0) return;
  struct vertex_key *keys = cmn_malloc(n * sizeof *keys);
  size_t *map = cmn_malloc(n * sizeof *map);
  for (size_t i = 0; i < n; i++) {
    for (int c = 0; c < 3; c++) keys[i].k[c] = tol > 0 ? round(m->vert[i][c] / tol) : m->vert[i][c];
    keys[i].index = i;
  }
  qsort(keys, n, sizeof *keys, key_cmp);
  for (size_t r = 0; r < n;) {
    size_t s = r + 1;
    while (s < n && key_equal(&keys[r], &keys[s])) s++;
    for (size_t k = r; k < s; k++) map[keys[k].index] = keys[r].index;
    r = s;
  }
  free(keys);
  /* Renumber the vertices that elements use, in their original order. */
  size_t *newidx = cmn_malloc(n * sizeof *newidx);
  for (size_t i = 0; i < n; i++) newidx[i] = SIZE_MAX;
  for (size_t e = 0; e < m->nelem; e++)
    for (int k = 0; k < m->dim; k++) newidx[map[m->elem[e][k]]] = 0;
  size_t cnt = 0;
  for (size_t i = 0; i < n; i++)
    if (newidx[i] == 0) {
      newidx[i] = cnt;
      memmove(m->vert[cnt], m->vert[i], sizeof m->vert[0]);
      cnt++;
    }
  for (size_t e = 0; e < m->nelem; e++)
    for (int k = 0; k < m->dim; k++) m->elem[e][k] = newidx[map[m->elem[e][k]]];
  m->nvert = cnt;
  free(map);
  free(newidx);
}

void geom_mesh_identify_periodic(struct sph_mesh *m, const struct sph_domain *dom, double tol) {
  int any = 0;
  for (int a = 0; a < m->dim; a++) {
    if (!dom->periodic[a]) continue;
    any = 1;
    for (size_t i = 0; i < m->nvert; i++)
      if (fabs(m->vert[i][a] - dom->hi[a]) <= tol) m->vert[i][a] = dom->lo[a];
  }
  if (any) sph_mesh_merge_vertices(m, tol);
}

/* --------------------------------------------------------------------------------------------
 * Edge table: open addressing on (min, max) vertex pairs.
 * ------------------------------------------------------------------------------------------ */
struct edge_table {
  size_t cap, n;
  size_t *a, *b; /* a < b; SIZE_MAX marks an empty slot */
  size_t *value;
};

static void edges_init(struct edge_table *t, size_t expected) {
  t->cap = 16;
  while (t->cap < 2 * expected + 16) t->cap *= 2;
  t->n = 0;
  t->a = cmn_malloc(t->cap * sizeof *t->a);
  t->b = cmn_malloc(t->cap * sizeof *t->b);
  t->value = cmn_malloc(t->cap * sizeof *t->value);
  for (size_t i = 0; i < t->cap; i++) t->a[i] = SIZE_MAX;
}

static void edges_free(struct edge_table *t) {
  free(t->a);
  free(t->b);
  free(t->value);
}

/* Slot of edge {u, v}; inserted with value `fresh` if absent (the table never fills: its size is
 * at least twice the number of edges). */
static size_t edges_slot(struct edge_table *t, size_t u, size_t v, size_t fresh) {
  size_t a = u < v ? u : v, b = u < v ? v : u;
  size_t h = (a * 0x9E3779B97F4A7C15ULL) ^ (b * 0xC2B2AE3D27D4EB4FULL);
  for (size_t i = (h ^ (h >> 29)) & (t->cap - 1);; i = (i + 1) & (t->cap - 1)) {
    if (t->a[i] == SIZE_MAX) {
      t->a[i] = a;
      t->b[i] = b;
      t->value[i] = fresh;
      t->n++;
      return i;
    }
    if (t->a[i] == a && t->b[i] == b) return i;
  }
}

/* --------------------------------------------------------------------------------------------
 * Refinement
 * ------------------------------------------------------------------------------------------ */
static double dist3(const double *x, const double *y) {
  double d2 = 0;
  for (int a = 0; a < 3; a++) d2 += (x[a] - y[a]) * (x[a] - y[a]);
  return sqrt(d2);
}

static void refine_2d(struct sph_mesh *m, double dr) {
  struct sph_mesh out;
  sph_mesh_init(&out, 2);
  copy_sources(&out, m);
  for (size_t i = 0; i < m->nvert; i++) sph_mesh_add_vertex(&out, m->vert[i]);
  for (size_t e = 0; e < m->nelem; e++) {
    const double *x0 = m->vert[m->elem[e][0]], *x1 = m->vert[m->elem[e][1]];
    long n = lround(dist3(x0, x1) / dr);
    if (n < 1) n = 1;
    size_t prev = m->elem[e][0];
    for (long k = 1; k <= n; k++) {
      size_t next = m->elem[e][1];
      if (k < n) {
        double t = (double)k / (double)n, x[3];
        for (int a = 0; a < 3; a++) x[a] = x0[a] + t * (x1[a] - x0[a]);
        next = sph_mesh_add_vertex(&out, x);
      }
      copy_element(&out, m, e, (size_t[]){prev, next, 0});
      prev = next;
    }
  }
  sph_mesh_free(m);
  *m = out;
}

/* Index (0..2) of the longest edge of triangle e (edge k runs from vertex k to vertex k+1);
 * ties go to the lowest index, computed from the sorted pair so both triangles of an edge agree
 * on its length. */
static int longest_edge(const struct sph_mesh *m, size_t e, double *len) {
  int best = 0;
  double lbest = -1;
  for (int k = 0; k < 3; k++) {
    size_t u = m->elem[e][k], v = m->elem[e][(k + 1) % 3];
    double l = u < v ? dist3(m->vert[u], m->vert[v]) : dist3(m->vert[v], m->vert[u]);
    if (l > lbest) {
      lbest = l;
      best = k;
    }
  }
  if (len) *len = lbest;
  return best;
}

/* One pass of conforming refinement: mark the longest edge of every triangle longer than lmax,
 * close the marking (a triangle with a marked edge has its longest edge marked), then split each
 * triangle by its marked edges (bisection from the longest edge's midpoint). Returns the number of
 * split edges. */
static size_t refine_3d_pass(struct sph_mesh *m, double lmax) {
  struct edge_table t;
  edges_init(&t, 3 * m->nelem / 2 + 3);
  const size_t unmarked = SIZE_MAX, marked = SIZE_MAX - 1;
  for (size_t e = 0; e < m->nelem; e++)
    for (int k = 0; k < 3; k++) edges_slot(&t, m->elem[e][k], m->elem[e][(k + 1) % 3], unmarked);
  size_t nmarked = 0;
  for (size_t e = 0; e < m->nelem; e++) {
    double len;
    int k = longest_edge(m, e, &len);
    if (len <= lmax) continue;
    size_t s = edges_slot(&t, m->elem[e][k], m->elem[e][(k + 1) % 3], unmarked);
    if (t.value[s] == unmarked) {
      t.value[s] = marked;
      nmarked++;
    }
  }
  for (int changed = nmarked > 0; changed;) {
    changed = 0;
    for (size_t e = 0; e < m->nelem; e++) {
      int any = 0;
      for (int k = 0; k < 3; k++)
        any |= t.value[edges_slot(&t, m->elem[e][k], m->elem[e][(k + 1) % 3], 0)] != unmarked;
      if (!any) continue;
      int k = longest_edge(m, e, NULL);
      size_t s = edges_slot(&t, m->elem[e][k], m->elem[e][(k + 1) % 3], 0);
      if (t.value[s] == unmarked) {
        t.value[s] = marked;
        nmarked++;
        changed = 1;
      }
    }
  }
  if (nmarked == 0) {
    edges_free(&t);
    return 0;
  }
  for (size_t i = 0; i < t.cap; i++)
    if (t.a[i] != SIZE_MAX && t.value[i] == marked) {
      double x[3];
      for (int a = 0; a < 3; a++) x[a] = 0.5 * (m->vert[t.a[i]][a] + m->vert[t.b[i]][a]);
      t.value[i] = sph_mesh_add_vertex(m, x);
    }
  struct sph_mesh out;
  sph_mesh_init(&out, 3);
  copy_sources(&out, m);
  for (size_t i = 0; i < m->nvert; i++) sph_mesh_add_vertex(&out, m->vert[i]);
  for (size_t e = 0; e < m->nelem; e++) {
    int k = longest_edge(m, e, NULL);
    size_t A = m->elem[e][k], B = m->elem[e][(k + 1) % 3], C = m->elem[e][(k + 2) % 3];
    size_t M = t.value[edges_slot(&t, A, B, 0)];
    size_t N = t.value[edges_slot(&t, B, C, 0)];
    size_t P = t.value[edges_slot(&t, C, A, 0)];
    if (M == unmarked) { /* closure: then no edge of e is marked */
      copy_element(&out, m, e, m->elem[e]);
    } else if (N == unmarked && P == unmarked) {
      copy_element(&out, m, e, (size_t[]){A, M, C});
      copy_element(&out, m, e, (size_t[]){M, B, C});
    } else if (P == unmarked) {
      copy_element(&out, m, e, (size_t[]){A, M, C});
      copy_element(&out, m, e, (size_t[]){M, B, N});
      copy_element(&out, m, e, (size_t[]){M, N, C});
    } else if (N == unmarked) {
      copy_element(&out, m, e, (size_t[]){A, M, P});
      copy_element(&out, m, e, (size_t[]){P, M, C});
      copy_element(&out, m, e, (size_t[]){M, B, C});
    } else {
      copy_element(&out, m, e, (size_t[]){A, M, P});
      copy_element(&out, m, e, (size_t[]){M, B, N});
      copy_element(&out, m, e, (size_t[]){P, N, C});
      copy_element(&out, m, e, (size_t[]){M, N, P});
    }
  }
  edges_free(&t);
  sph_mesh_free(m);
  *m = out;
  return nmarked;
}

void sph_mesh_refine(struct sph_mesh *m, double dr) {
  if (m->dim == 2) refine_2d(m, dr);
  if (m->dim == 3)
    while (refine_3d_pass(m, GEOM_EDGE_MAX * dr) > 0) {
    }
}

/* --------------------------------------------------------------------------------------------
 * Checks
 * ------------------------------------------------------------------------------------------ */
static void describe(const struct sph_mesh *m, size_t e, char *buf, size_t len) {
  const char *what = m->dim == 1 ? "point" : m->dim == 2 ? "segment" : "triangle";
  const char *src =
      m->source[e] >= 0 && m->source[e] < m->nsources ? m->sources[m->source[e]] : "walls";
  long idx = m->source_index[e] ? m->source_index[e] : (long)e + 1;
  if (m->source_line[e] > 0)
    snprintf(buf, len, "%s:%ld: %s %ld", src, m->source_line[e], what, idx);
  else
    snprintf(buf, len, "%s: %s %ld", src, what, idx);
}

static void fmt_point(int dim, const double *x, char *buf, size_t len) {
  if (dim == 1) snprintf(buf, len, "(%.9g)", x[0]);
  if (dim == 2) snprintf(buf, len, "(%.9g, %.9g)", x[0], x[1]);
  if (dim == 3) snprintf(buf, len, "(%.9g, %.9g, %.9g)", x[0], x[1], x[2]);
}

int geom_fail(char *msg, size_t msglen, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, msglen, fmt, ap);
  va_end(ap);
  return -1;
}

/* Element vertices with periodic minimum image relative to the first vertex. */
static void element_unwrapped(const struct sph_mesh *m, const struct sph_domain *dom, size_t e,
                              double v[3][3]) {
  geom_element_vertices(m, e, v);
  if (!dom) return;
  for (int k = 1; k < m->dim; k++) {
    double d[3];
    sph_domain_delta(dom, v[0], v[k], d);
    for (int a = 0; a < 3; a++) v[k][a] = v[0][a] + d[a];
  }
}

int sph_mesh_check(const struct sph_mesh *m, const struct sph_domain *dom, char *msg,
                   size_t msglen) {
  char what[512], p0[128], p1[128];
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < m->nvert; i++)
    for (int a = 0; a < 3; a++) {
      lo[a] = fmin(lo[a], m->vert[i][a]);
      hi[a] = fmax(hi[a], m->vert[i][a]);
    }
  double scale = m->nvert ? dist3(lo, hi) : 1.0;
  if (!(scale > 0)) scale = 1.0;
  for (size_t e = 0; e < m->nelem; e++) {
    double v[3][3];
    element_unwrapped(m, dom, e, v);
    double meas = geom_element_measure(m->dim, v);
    double tiny = m->dim == 3 ? 1e-24 * scale * scale : 1e-12 * scale;
    if (!(meas > tiny) || !isfinite(meas)) {
      describe(m, e, what, sizeof what);
      fmt_point(m->dim, v[0], p0, sizeof p0);
      return geom_fail(msg, msglen, "%s: degenerate (zero %s) at %s", what,
                       m->dim == 2 ? "length" : "area", p0);
    }
    if (m->dim == 1 && fabs(fabs(m->normal[e][0]) - 1) > 1e-12) {
      describe(m, e, what, sizeof what);
      return geom_fail(msg, msglen, "%s: normal must be +1 or -1", what);
    }
  }
  if (m->dim == 2) {
    size_t *out = cmn_calloc(m->nvert + 1, sizeof *out), *in = cmn_calloc(m->nvert + 1, sizeof *in);
    size_t *by = cmn_malloc((m->nvert + 1) * sizeof *by);
    int rc = 0;
    for (size_t e = 0; e < m->nelem && rc == 0; e++) {
      size_t a = m->elem[e][0], b = m->elem[e][1];
      if (out[a]++ == 0) by[a] = e;
      if (in[b]++ == 0) continue;
      describe(m, e, what, sizeof what);
      fmt_point(2, m->vert[b], p0, sizeof p0);
      rc = geom_fail(msg, msglen,
                     "%s ends at %s where another segment already ends: inconsistent orientation "
                     "(each wall must run with the fluid on its left)",
                     what, p0);
    }
    for (size_t v = 0; v < m->nvert && rc == 0; v++) {
      if (out[v] > 1) {
        describe(m, by[v], what, sizeof what);
        fmt_point(2, m->vert[v], p0, sizeof p0);
        rc = geom_fail(msg, msglen,
                       "%s starts at %s where another segment already starts: inconsistent "
                       "orientation (each wall must run with the fluid on its left)",
                       what, p0);
      } else if (out[v] + in[v] == 1) {
        size_t e = 0;
        while (m->elem[e][0] != v && m->elem[e][1] != v) e++;
        describe(m, e, what, sizeof what);
        fmt_point(2, m->vert[v], p0, sizeof p0);
        rc = geom_fail(msg, msglen,
                       "%s: the wall is open at %s (no segment %s there): close it, or make the "
                       "domain periodic across this end",
                       what, p0, out[v] ? "ends" : "starts");
      }
    }
    free(out);
    free(in);
    free(by);
    return rc;
  }
  if (m->dim == 3) {
    struct edge_table t;
    edges_init(&t, 3 * m->nelem / 2 + 3);
    /* Per undirected edge: how many triangles run through it low→high index (fwd) and back. */
    size_t *fwd = cmn_calloc(3 * m->nelem + 1, sizeof *fwd);
    size_t *bwd = cmn_calloc(3 * m->nelem + 1, sizeof *bwd);
    size_t *first = cmn_malloc((3 * m->nelem + 1) * sizeof *first);
    size_t next = 0;
    int rc = 0;
    for (size_t e = 0; e < m->nelem && rc == 0; e++)
      for (int k = 0; k < 3 && rc == 0; k++) {
        size_t u = m->elem[e][k], v = m->elem[e][(k + 1) % 3];
        size_t s = edges_slot(&t, u, v, next);
        if (t.value[s] == next) first[next++] = e;
        size_t id = t.value[s];
        size_t *count = u < v ? &fwd[id] : &bwd[id];
        if (++*count > 1) {
          describe(m, e, what, sizeof what);
          char other[512];
          describe(m, first[id], other, sizeof other);
          fmt_point(3, m->vert[u], p0, sizeof p0);
          fmt_point(3, m->vert[v], p1, sizeof p1);
          rc = geom_fail(msg, msglen,
                         "%s runs through its edge %s-%s in the same direction as %s: "
                         "inconsistent orientation (normals must all point into the fluid)",
                         what, p0, p1, other);
        }
      }
    for (size_t i = 0; i < t.cap && rc == 0; i++) {
      if (t.a[i] == SIZE_MAX) continue;
      size_t id = t.value[i];
      if (fwd[id] + bwd[id] == 2) continue;
      describe(m, first[id], what, sizeof what);
      fmt_point(3, m->vert[t.a[i]], p0, sizeof p0);
      fmt_point(3, m->vert[t.b[i]], p1, sizeof p1);
      rc = geom_fail(msg, msglen,
                     "%s: its edge %s-%s belongs to no other triangle: the surface is open (close "
                     "it, or make the domain periodic across it)",
                     what, p0, p1);
    }
    free(fwd);
    free(bwd);
    free(first);
    edges_free(&t);
    return rc;
  }
  return 0;
}

double sph_mesh_signed_volume(const struct sph_mesh *m, int source) {
  double vol = 0;
  for (size_t e = 0; e < m->nelem; e++) {
    if (m->source[e] != source) continue;
    double v[3][3];
    geom_element_vertices(m, e, v);
    if (m->dim == 2) {
      vol += 0.5 * (v[0][0] * v[1][1] - v[1][0] * v[0][1]);
    } else if (m->dim == 3) {
      double c[3];
      geom_cross(v[1], v[2], c);
      vol -= (v[0][0] * c[0] + v[0][1] * c[1] + v[0][2] * c[2]) / 6.0;
    }
  }
  return vol;
}
