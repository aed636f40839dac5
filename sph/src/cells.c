/* Cell lists and neighbour lists (fluid–fluid, fluid–vertex, fluid–segment, ...).
 *
 * Cells are at least one kernel support wide; each query cell gathers from the cells within the
 * search reach (one layer for points, more only if a segment's extent requires it). Lists are
 * written by the thread that owns its query particle's cell: no atomics, and the result is
 * independent of the thread count. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph.h"
#ifdef _OPENMP
#include <omp.h>
#endif

/* Cap on the number of cells relative to the particle count, for sparse sets. */
#define CELLS_PER_PARTICLE_MAX 4
/* Widest stencil, in cells each side (the reach is one or two cells in practice). */
#define STENCIL_REACH_MAX 16
/* Query particles per slice of sph_nlist_build(): the rows of one slice are gathered, then copied
 * into place, so that the work buffers hold one slice's rows (a few tens of MB) rather than a
 * second copy of the whole list, which would double the peak memory of a large run. */
#define NLIST_SLICE 32768

static const char *const axis_name = "xyz";
static const char *const kind_name[SPH_NKINDS] = {"fluid", "vertex", "segment"};

void sph_cells_free(struct sph_cells *c) {
  for (int k = 0; k < SPH_NKINDS; k++) {
    free(c->start[k]);
    free(c->index[k]);
    for (int a = 0; a < 3; a++) free(c->xs[k][a]);
  }
  memset(c, 0, sizeof *c);
}

static size_t cell_coord(const struct sph_cells *c, int a, double x) {
  double t = floor((x - c->domain.lo[a]) / c->width[a]);
  long n = c->ncell[a];
  if (c->domain.periodic[a]) {
    long i = (long)fmod(t, (double)n);
    return (size_t)(i < 0 ? i + n : i);
  }
  if (t < 0) return 0;
  if (t >= (double)n) return (size_t)(n - 1);
  return (size_t)t;
}

static size_t cell_of(const struct sph_cells *c, const double *x) {
  size_t id = 0;
  for (int a = c->dim - 1; a >= 0; a--) id = id * (size_t)c->ncell[a] + cell_coord(c, a, x[a]);
  return id;
}

/* Largest distance from a segment's centroid to its vertices (minimum image). */
static double segment_reach(const struct sph_system *s) {
  const struct sph_parts *seg = &s->part[SPH_KIND_SEGMENT];
  double reach = 0;
  for (size_t j = 0; j < seg->n; j++) {
    double c[3] = {seg->x[0][j], seg->x[1][j], seg->x[2][j]}, v[3][3];
    sph_segment_vertices(s, j, c, v);
    for (int k = 0; k < s->dim; k++) {
      double r2 = 0;
      for (int a = 0; a < 3; a++) r2 += (v[k][a] - c[a]) * (v[k][a] - c[a]);
      reach = fmax(reach, sqrt(r2));
    }
  }
  return reach;
}

void sph_cells_build(struct sph_cells *c, const struct sph_system *s, double cell_min) {
  if (!(cell_min > 0)) cmn_error("cell width %g must be positive", cell_min);
  int dim = s->dim;
  c->dim = dim;
  c->domain = s->domain;
  c->domain.dim = dim;
  size_t ntot = 0;
  for (int a = 0; a < dim; a++) {
    if (c->domain.periodic[a]) continue;
    c->domain.lo[a] = INFINITY;
    c->domain.hi[a] = -INFINITY;
  }
  for (int k = 0; k < SPH_NKINDS; k++) {
    const struct sph_parts *p = &s->part[k];
    ntot += p->n;
    for (int a = 0; a < dim; a++) {
      if (c->domain.periodic[a]) continue;
      for (size_t i = 0; i < p->n; i++) {
        double x = p->x[a][i];
        if (!isfinite(x))
          cmn_error("%s particle %zu (id %lld) has a non-finite position", kind_name[k], i,
                    (long long)p->id[i]);
        if (x < c->domain.lo[a]) c->domain.lo[a] = x;
        if (x > c->domain.hi[a]) c->domain.hi[a] = x;
      }
    }
  }
  for (int a = 0; a < 3; a++) {
    c->ncell[a] = 1;
    c->width[a] = cell_min;
    if (a >= dim) {
      c->domain.lo[a] = c->domain.hi[a] = 0;
      c->domain.periodic[a] = 0;
    } else if (!(c->domain.lo[a] <= c->domain.hi[a])) { /* no particles */
      c->domain.lo[a] = c->domain.hi[a] = 0;
    }
  }
  /* Widen the cells of sparse sets so memory stays proportional to the particle count. */
  double width = cell_min;
  size_t cap = CELLS_PER_PARTICLE_MAX * ntot + 64;
  for (;;) {
    size_t total = 1;
    for (int a = 0; a < dim; a++) {
      double len = c->domain.hi[a] - c->domain.lo[a];
      double n = floor(len / width);
      if (n < 1) n = 1;
      if (n > 1e7) n = 1e7;
      c->ncell[a] = (int)n;
      c->width[a] = c->domain.periodic[a] || len > 0 ? len / n : width;
      if (c->width[a] < width) c->width[a] = width; /* non-periodic: a point at hi is clamped */
      total *= (size_t)n;
    }
    c->ncells = total;
    if (total <= cap) break;
    width *= 1.5;
  }
  c->segment_reach = segment_reach(s);

  for (int k = 0; k < SPH_NKINDS; k++) {
    const struct sph_parts *p = &s->part[k];
    free(c->start[k]);
    c->start[k] = cmn_calloc(c->ncells + 1, sizeof(size_t));
    if (c->alloc[k] < p->n || !c->index[k]) {
      size_t len = p->n ? p->n : 1;
      c->index[k] = cmn_realloc(c->index[k], len * sizeof(size_t));
      for (int a = 0; a < 3; a++) c->xs[k][a] = cmn_realloc(c->xs[k][a], len * sizeof(double));
      c->alloc[k] = len;
    }
    size_t *cell = cmn_malloc((p->n ? p->n : 1) * sizeof(size_t));
#ifdef _OPENMP
#pragma omp parallel for schedule(static)
#endif
    for (size_t i = 0; i < p->n; i++) {
      double x[3] = {p->x[0][i], p->x[1][i], p->x[2][i]};
      cell[i] = cell_of(c, x);
    }
    size_t *start = c->start[k];
    for (size_t i = 0; i < p->n; i++) start[cell[i] + 1]++;
    for (size_t ci = 0; ci < c->ncells; ci++) start[ci + 1] += start[ci];
    size_t *fill = cmn_malloc((c->ncells + 1) * sizeof(size_t));
    memcpy(fill, start, (c->ncells + 1) * sizeof(size_t));
    for (size_t i = 0; i < p->n; i++) {
      size_t at = fill[cell[i]]++;
      c->index[k][at] = i;
      for (int a = 0; a < 3; a++) c->xs[k][a][at] = p->x[a][i];
    }
    free(fill);
    free(cell);
  }
}

/* Whole periods to add to b so that it lies within half a period of a (0 in other directions). */
static void image_shift(const struct sph_domain *dom, const double *a, const double *b,
                        double *shift) {
  double d[3];
  sph_domain_delta(dom, a, b, d);
  for (int k = 0; k < 3; k++) {
    double len = dom->hi[k] - dom->lo[k];
    shift[k] = d[k] == b[k] - a[k] ? 0.0 : d[k] < b[k] - a[k] ? -len : len;
  }
}

void sph_segment_vertices(const struct sph_system *s, size_t j, const double *near,
                          double v[3][3]) {
  const struct sph_parts *seg = &s->part[SPH_KIND_SEGMENT];
  const struct sph_parts *vert = &s->part[SPH_KIND_VERTEX];
  int periodic = 0;
  for (int k = 0; k < s->domain.dim; k++) periodic |= s->domain.periodic[k];
  if (!periodic) { /* every image_shift() below would be 0: the same bits (+ 0.0) without them */
    for (int k = 0; k < 3; k++) {
      const size_t iv = k < s->dim ? seg->vertex[k][j] : 0;
      for (int a = 0; a < 3; a++) v[k][a] = k < s->dim ? vert->x[a][iv] + 0.0 : 0;
    }
    return;
  }
  double c[3] = {seg->x[0][j], seg->x[1][j], seg->x[2][j]}, sc[3], sv[3];
  image_shift(&s->domain, near, c, sc);
  for (int k = 0; k < 3; k++) {
    if (k >= s->dim) {
      v[k][0] = v[k][1] = v[k][2] = 0;
      continue;
    }
    size_t iv = seg->vertex[k][j];
    double xv[3] = {vert->x[0][iv], vert->x[1][iv], vert->x[2][iv]};
    image_shift(&s->domain, c, xv, sv);
    /* Without periodic images the coordinates are the vertices' own, bit for bit. */
    for (int a = 0; a < 3; a++) v[k][a] = xv[a] + (sv[a] + sc[a]);
  }
}

static double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double sph_element_distance(int dim, const double v[3][3], const double *p, double *q) {
  if (dim == 1) {
    q[0] = v[0][0];
    q[1] = q[2] = 0;
  } else if (dim == 2) {
    double ab[3], ap[3];
    for (int a = 0; a < 3; a++) {
      ab[a] = v[1][a] - v[0][a];
      ap[a] = p[a] - v[0][a];
    }
    double len2 = dot3(ab, ab), t = len2 > 0 ? dot3(ap, ab) / len2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (int a = 0; a < 3; a++) q[a] = v[0][a] + t * ab[a];
  } else {
    /* Closest point on a triangle by Voronoi regions of its vertices, edges and face. */
    const double *A = v[0], *B = v[1], *C = v[2];
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int a = 0; a < 3; a++) {
      ab[a] = B[a] - A[a];
      ac[a] = C[a] - A[a];
      ap[a] = p[a] - A[a];
      bp[a] = p[a] - B[a];
      cp[a] = p[a] - C[a];
    }
    double d1 = dot3(ab, ap), d2 = dot3(ac, ap), d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
    double s = 0, t = 0; /* q = A + s ab + t ac */
    if (d1 <= 0 && d2 <= 0) {
    } else if (d3 >= 0 && d4 <= d3) {
      s = 1;
    } else if (d6 >= 0 && d5 <= d6) {
      t = 1;
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      s = d1 / (d1 - d3);
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      t = d2 / (d2 - d6);
    } else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
      double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      s = 1 - w;
      t = w;
    } else {
      double denom = 1 / (va + vb + vc);
      s = vb * denom;
      t = vc * denom;
    }
    for (int a = 0; a < 3; a++) q[a] = A[a] + s * ab[a] + t * ac[a];
  }
  double d2 = 0;
  for (int a = 0; a < 3; a++) d2 += (p[a] - q[a]) * (p[a] - q[a]);
  return sqrt(d2);
}

/* The neighbour test shared by the cell and naive searches, so both decide borderline pairs
 * identically. xa is the query particle, j the candidate of kind `other`. */
static int is_neighbour(const struct sph_system *s, enum sph_kind query, enum sph_kind other,
                        const double *xa, size_t i, const double *xb, size_t j, double radius,
                        double reach) {
  if (query == other && i == j) return 0;
  double d[3];
  sph_domain_delta(&s->domain, xa, xb, d);
  double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  if (query != SPH_KIND_SEGMENT && other != SPH_KIND_SEGMENT) return r2 < radius * radius;
  double lim = radius + reach;
  if (r2 >= lim * lim) return 0;
  const double *x = other == SPH_KIND_SEGMENT ? xa : xb;
  const size_t e = other == SPH_KIND_SEGMENT ? j : i;
  const struct sph_parts *seg = &s->part[SPH_KIND_SEGMENT];
  double v[3][3], q[3];
  sph_segment_vertices(s, e, x, v);
  /* Decided without the exact distance when a bound settles it with room to spare (1e-12, far
   * above round-off), so the list is the one the exact test gives: the element is no farther than
   * its first vertex and no nearer than its plane (line, point) of unit normal n. */
  double dv[3], dn = 0.0;
  for (int a = 0; a < 3; a++) {
    dv[a] = x[a] - v[0][a];
    dn += dv[a] * seg->normal[a][e];
  }
  const double r2min = radius * radius;
  if (dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2] < r2min * (1.0 - 1e-12)) return 1;
  if (dn * dn > r2min * (1.0 + 1e-12)) return 0;
  return sph_element_distance(s->dim, v, x, q) < radius;
}

static void check_kinds(const struct sph_system *s, enum sph_kind query, enum sph_kind other) {
  if (query == SPH_KIND_SEGMENT && other == SPH_KIND_SEGMENT)
    cmn_error("segment-segment neighbour lists are not supported");
  if (s->part[other].n > (size_t)SPH_NBR_MAX)
    cmn_error("%zu particles of one kind: neighbour lists hold 32-bit indices (at most %zu)",
              s->part[other].n, (size_t)SPH_NBR_MAX);
}

static void nlist_alloc(struct sph_nlist *nl, enum sph_kind query, enum sph_kind other, size_t n) {
  nl->query = query;
  nl->other = other;
  nl->n = n;
  free(nl->offset);
  nl->offset = cmn_calloc(n + 1, sizeof(size_t));
}

/* Room for `need` entries in nl->index, keeping the entries already there. */
static void nlist_reserve(struct sph_nlist *nl, size_t need) {
  if (need > nl->capacity || !nl->index) {
    nl->capacity = need > 0 ? need + need / 8 : 1;
    nl->index = cmn_realloc(nl->index, nl->capacity * sizeof *nl->index);
  }
}

/* The work buffers of sph_nlist_build(), kept with the list so that a list rebuilt every step
 * does not allocate (and fault in) its per-thread row buffers again. */
struct sph_nlist_scratch {
  int nthreads;
  struct row_buffer {
    sph_nbr_t *data;
    size_t n, cap;
    double *r2; /* squared distances to one cell's candidates (point pairs) */
    size_t r2cap;
  } * buf;
  int *cell_thread;
  size_t *cell_at, ncells; /* cell arrays of ncells + 1 entries */
};

static void scratch_free(struct sph_nlist_scratch *sc) {
  if (!sc) return;
  for (int t = 0; t < sc->nthreads; t++) {
    free(sc->buf[t].data);
    free(sc->buf[t].r2);
  }
  free(sc->buf);
  free(sc->cell_thread);
  free(sc->cell_at);
  free(sc);
}

/* The list's scratch, sized for nthreads threads and ncells cells. */
static struct sph_nlist_scratch *scratch_get(struct sph_nlist *nl, int nthreads, size_t ncells) {
  struct sph_nlist_scratch *sc = nl->scratch;
  if (sc && sc->nthreads != nthreads) {
    scratch_free(sc);
    sc = NULL;
  }
  if (!sc) {
    sc = cmn_calloc(1, sizeof *sc);
    sc->nthreads = nthreads;
    sc->buf = cmn_calloc((size_t)nthreads, sizeof *sc->buf);
    /* Every buffer is allocated, even for a thread that will find no pair: the copy into place
     * then always reads from a valid pointer (memcpy from NULL is undefined even for 0 bytes). */
    for (int t = 0; t < nthreads; t++) {
      sc->buf[t].cap = 1024;
      sc->buf[t].data = cmn_malloc(sc->buf[t].cap * sizeof *sc->buf[t].data);
    }
    nl->scratch = sc;
  }
  if (!sc->cell_at || ncells > sc->ncells) {
    free(sc->cell_thread);
    free(sc->cell_at);
    sc->cell_thread = cmn_malloc((ncells + 1) * sizeof *sc->cell_thread);
    sc->cell_at = cmn_malloc((ncells + 1) * sizeof *sc->cell_at);
    sc->ncells = ncells;
  }
  for (int t = 0; t < nthreads; t++) sc->buf[t].n = 0;
  return sc;
}

void sph_nlist_free(struct sph_nlist *nl) {
  free(nl->offset);
  free(nl->index);
  scratch_free(nl->scratch);
  memset(nl, 0, sizeof *nl);
}

/* Rows are sorted by ascending neighbour index: sorted rows make every sum over a row run in
 * neighbour-index order, whatever the list radius or the positions at the build, so that a list
 * kept over several steps and a fresh one give the same bits. */

/* Merge the ascending runs a[0..m) and a[m..n) into out. */
static void merge_runs(const sph_nbr_t *a, size_t m, size_t n, sph_nbr_t *out) {
  size_t i = 0, j = m, k = 0;
  while (i < m && j < n) out[k++] = a[i] < a[j] ? a[i++] : a[j++];
  while (i < m) out[k++] = a[i++];
  while (j < n) out[k++] = a[j++];
}

/* The n distinct indices of src in ascending order into dst (src is used as scratch): bottom-up
 * merges of the ascending runs the traversal leaves (one per stencil cell, the cells' contents
 * being in index order), between the two arrays. */
static void sort_row(sph_nbr_t *src, size_t n, sph_nbr_t *dst) {
  if (n == 0) return;
  sph_nbr_t *from = src, *to = dst;
  for (;;) {
    size_t i = 0, runs = 0;
    while (i < n) {
      size_t m = i + 1;
      while (m < n && from[m - 1] < from[m]) m++;
      size_t e = m;
      if (m < n)
        for (e = m + 1; e < n && from[e - 1] < from[e];) e++;
      merge_runs(from + i, m - i, e - i, to + i);
      runs++;
      i = e;
    }
    if (runs == 1) {
      if (to != dst) memcpy(dst, to, n * sizeof *dst);
      return;
    }
    sph_nbr_t *t = from;
    from = to;
    to = t;
  }
}

/* The naive search visits the candidates in index order: its rows are sorted as built. */
void sph_nlist_build_naive(struct sph_nlist *nl, const struct sph_system *s, enum sph_kind query,
                           enum sph_kind other, double radius) {
  check_kinds(s, query, other);
  const struct sph_parts *pq = &s->part[query], *po = &s->part[other];
  double reach = query == SPH_KIND_SEGMENT || other == SPH_KIND_SEGMENT ? INFINITY : 0;
  nlist_alloc(nl, query, other, pq->n);
  for (int pass = 0; pass < 2; pass++) {
    for (size_t i = 0; i < pq->n; i++) {
      double xa[3] = {pq->x[0][i], pq->x[1][i], pq->x[2][i]};
      size_t cnt = 0;
      sph_nbr_t *row = pass ? nl->index + nl->offset[i] : NULL;
      for (size_t j = 0; j < po->n; j++) {
        double xb[3] = {po->x[0][j], po->x[1][j], po->x[2][j]};
        if (!is_neighbour(s, query, other, xa, i, xb, j, radius, reach)) continue;
        if (pass) row[cnt] = (sph_nbr_t)j;
        cnt++;
      }
      if (!pass) nl->offset[i + 1] = nl->offset[i] + cnt;
    }
    if (!pass) nlist_reserve(nl, nl->offset[nl->n]);
  }
}

/* Cells along one axis within `reach` cells of cell i, each listed once (a short periodic axis
 * would otherwise list a cell twice). Returns the count. */
static int axis_stencil(const struct sph_cells *c, int a, int i, int reach, int *out) {
  int n = c->ncell[a], cnt = 0;
  if (a >= c->dim) {
    out[0] = 0;
    return 1;
  }
  if (c->domain.periodic[a]) {
    if (2 * reach + 1 >= n) {
      for (int j = 0; j < n; j++) out[cnt++] = j;
      return cnt;
    }
    for (int d = -reach; d <= reach; d++) out[cnt++] = ((i + d) % n + n) % n;
    return cnt;
  }
  for (int d = -reach; d <= reach; d++)
    if (i + d >= 0 && i + d < n) out[cnt++] = i + d;
  return cnt;
}

void sph_nlist_build(struct sph_nlist *nl, const struct sph_cells *c, const struct sph_system *s,
                     enum sph_kind query, enum sph_kind other, double radius) {
  check_kinds(s, query, other);
  const struct sph_parts *pq = &s->part[query];
  if (c->dim != s->dim) cmn_error("cells built for dimension %d, system has %d", c->dim, s->dim);
  double reach = query == SPH_KIND_SEGMENT || other == SPH_KIND_SEGMENT ? c->segment_reach : 0;
  double lim = radius + reach;
  int sreach[3] = {0, 0, 0};
  for (int a = 0; a < s->dim; a++) {
    sreach[a] = (int)ceil(lim / c->width[a]);
    if (sreach[a] < 1) sreach[a] = 1;
    if (sreach[a] > STENCIL_REACH_MAX)
      cmn_error("search radius %g m spans more than %d cells of %g m: build the cells wider",
                radius, STENCIL_REACH_MAX, c->width[a]);
    double len = c->domain.hi[a] - c->domain.lo[a];
    if (c->domain.periodic[a] && len < 2 * lim)
      cmn_input_error(
          "periodic direction %c is %g m long, shorter than twice the search reach %g m "
          "(support plus segment size): enlarge the domain or refine dr",
          axis_name[a], len, lim);
  }
  nlist_alloc(nl, query, other, pq->n);
  const int points = query != SPH_KIND_SEGMENT && other != SPH_KIND_SEGMENT, same = query == other;
  const double r2max = radius * radius, lim2 = lim * lim;
  /* Round-off in the cell binning, with a wide margin. */
  double slack[3];
  for (int a = 0; a < 3; a++)
    slack[a] = 1e-9 * (fabs(c->domain.lo[a]) + fabs(c->domain.hi[a]) + c->width[a]);
  double period[3], half[3];
  for (int a = 0; a < 3; a++) {
    int per = a < s->dim && s->domain.periodic[a];
    period[a] = per ? s->domain.hi[a] - s->domain.lo[a] : 0.0;
    half[a] = per ? 0.5 * period[a] : INFINITY;
  }
  const size_t *startq = c->start[query], *starto = c->start[other];
  const size_t *idxq = c->index[query], *idxo = c->index[other];
  /* Per slice of query indices [lo, hi): each thread appends the rows of the cells it handles to
   * its own buffer (row order fixed by the traversal, so independent of the thread count); then
   * the slice's offsets are known and its rows are copied into place. Every candidate is tested
   * once whatever the number of slices. */
  int nthreads = 1;
#ifdef _OPENMP
  nthreads = omp_get_max_threads();
#endif
  struct sph_nlist_scratch *sc = scratch_get(nl, nthreads, c->ncells);
  struct row_buffer *buf = sc->buf;
  int *cell_thread = sc->cell_thread;
  size_t *cell_at = sc->cell_at;
  for (size_t lo = 0; lo < pq->n || lo == 0; lo += NLIST_SLICE) {
    const size_t hi = pq->n - lo > NLIST_SLICE ? lo + NLIST_SLICE : pq->n;
    for (int t = 0; t < nthreads; t++) buf[t].n = 0;
#ifdef _OPENMP
#pragma omp parallel
#endif
    {
      int tid = 0;
#ifdef _OPENMP
      tid = omp_get_thread_num();
#endif
      struct row_buffer *b = &buf[tid];
#ifdef _OPENMP
#pragma omp for schedule(dynamic, 8)
#endif
      for (size_t ci = 0; ci < c->ncells; ci++) {
        cell_thread[ci] = -1;
        size_t q0 = startq[ci];
        while (q0 < startq[ci + 1] && (idxq[q0] < lo || idxq[q0] >= hi)) q0++;
        if (q0 == startq[ci + 1]) continue; /* no query particle of the slice here */
        cell_thread[ci] = tid;
        cell_at[ci] = b->n;
        int ic[3] = {0, 0, 0}, st[3][2 * STENCIL_REACH_MAX + 1], nst[3];
        size_t rest = ci;
        for (int a = 0; a < 3; a++) {
          if (a < c->dim) {
            ic[a] = (int)(rest % (size_t)c->ncell[a]);
            rest /= (size_t)c->ncell[a];
          }
          nst[a] = axis_stencil(c, a, ic[a], sreach[a], st[a]);
        }
        for (size_t qa = q0; qa < startq[ci + 1]; qa++) {
          size_t i = idxq[qa], first = b->n;
          if (i < lo || i >= hi) continue;
          double xa[3] = {c->xs[query][0][qa], c->xs[query][1][qa], c->xs[query][2][qa]};
          /* Squared gap from xa to each stencil slab along the non-periodic axes (0 along
           * periodic ones): a cell whose box is lim + slack away holds no candidate that passes
           * the tests below, so skipping it leaves the list unchanged. */
          double gap2[3][2 * STENCIL_REACH_MAX + 1];
          for (int a = 0; a < 3; a++)
            for (int k = 0; k < nst[a]; k++) {
              double g = 0.0;
              if (a < c->dim && !c->domain.periodic[a]) {
                const double clo = c->domain.lo[a] + c->width[a] * st[a][k];
                g = st[a][k] > ic[a]   ? clo - xa[a] - slack[a]
                    : st[a][k] < ic[a] ? xa[a] - (clo + c->width[a]) - slack[a]
                                       : 0.0;
                g = g > 0.0 ? g : 0.0;
              }
              gap2[a][k] = g * g;
            }
          for (int s2 = 0; s2 < nst[2]; s2++)
            for (int s1 = 0; s1 < nst[1]; s1++)
              for (int s0 = 0; s0 < nst[0]; s0++) {
                if (gap2[0][s0] + gap2[1][s1] + gap2[2][s2] >= lim2) continue;
                size_t cj = ((size_t)st[2][s2] * (size_t)c->ncell[1] + (size_t)st[1][s1]) *
                                (size_t)c->ncell[0] +
                            (size_t)st[0][s0];
                size_t o0 = starto[cj], o1 = starto[cj + 1];
                if (b->n + (o1 - o0) > b->cap) {
                  const size_t need = b->n + (o1 - o0);
                  b->cap = need + need / 4 + 1024;
                  b->data = cmn_realloc(b->data, b->cap * sizeof *b->data);
                }
                if (points) {
                  /* Point pairs: the test of is_neighbour() with the same arithmetic (the
                   * minimum image written without branches): the squared distances of the
                   * cell's candidates first, in a loop the compiler vectorises (the cell's
                   * coordinates are contiguous), then appended without a branch. */
                  const size_t m = o1 - o0;
                  if (m > b->r2cap) {
                    b->r2cap = m + m / 2 + 64;
                    b->r2 = cmn_realloc(b->r2, b->r2cap * sizeof *b->r2);
                  }
                  double *restrict r2v = b->r2;
                  const double *restrict y0 = c->xs[other][0] + o0;
                  const double *restrict y1 = c->xs[other][1] + o0;
                  const double *restrict y2 = c->xs[other][2] + o0;
                  const double p0 = period[0], p1 = period[1], p2 = period[2];
                  const double h0 = half[0], h1 = half[1], h2 = half[2];
                  for (size_t t = 0; t < m; t++) {
                    double d0 = y0[t] - xa[0], d1 = y1[t] - xa[1], d2 = y2[t] - xa[2];
                    d0 = d0 - (d0 > h0 ? p0 : 0.0) + (d0 < -h0 ? p0 : 0.0);
                    d1 = d1 - (d1 > h1 ? p1 : 0.0) + (d1 < -h1 ? p1 : 0.0);
                    d2 = d2 - (d2 > h2 ? p2 : 0.0) + (d2 < -h2 ? p2 : 0.0);
                    r2v[t] = d0 * d0 + d1 * d1 + d2 * d2;
                  }
                  for (size_t t = 0; t < m; t++) {
                    const size_t j = idxo[o0 + t];
                    b->data[b->n] = (sph_nbr_t)j;
                    b->n += (r2v[t] < r2max) & !(same & (j == i));
                  }
                  continue;
                }
                for (size_t ob = o0; ob < o1; ob++) {
                  double xb[3] = {c->xs[other][0][ob], c->xs[other][1][ob], c->xs[other][2][ob]};
                  size_t j = idxo[ob];
                  if (is_neighbour(s, query, other, xa, i, xb, j, radius, reach))
                    b->data[b->n++] = (sph_nbr_t)j;
                }
              }
          nl->offset[i + 1] = b->n - first;
        }
      }
    }
    for (size_t i = lo; i < hi; i++) nl->offset[i + 1] += nl->offset[i];
    nlist_reserve(nl, nl->offset[hi]);
    /* The slice's rows into place, each sorted by neighbour index (sort_row). */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 64)
#endif
    for (size_t ci = 0; ci < c->ncells; ci++) {
      if (cell_thread[ci] < 0) continue;
      sph_nbr_t *from = buf[cell_thread[ci]].data + cell_at[ci];
      for (size_t qa = startq[ci]; qa < startq[ci + 1]; qa++) {
        size_t i = idxq[qa];
        if (i < lo || i >= hi) continue;
        size_t len = nl->offset[i + 1] - nl->offset[i];
        sort_row(from, len, nl->index + nl->offset[i]);
        from += len;
      }
    }
    if (hi == pq->n) break;
  }
}
