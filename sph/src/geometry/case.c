/* The `geometry` section of a case file (reference: docs/sph-geometry.md). Reads the keys through
 * common/ (which reports file, line and expected type), builds the walls from generators and
 * files, refines them to ≈ Δr, joins them across periodic boundaries and checks them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geometry/geometry.h"
#include "sabre/common.h"
#include "sabre/sph.h"

#define PI 3.14159265358979323846

enum wall_type { W_INTERVAL, W_BOX, W_CHANNEL, W_STEP, W_WEDGE, W_POLYGON, W_POLYLINE_FILE, W_STL };
static const char *const wall_types[] = {"interval", "box",           "channel", "step", "wedge",
                                         "polygon",  "polyline_file", "stl",     NULL};
/* Dimensions each type exists in (bit d). */
static const unsigned wall_dims[] = {1u << 1, 0xEu,    0xCu,    1u << 2,
                                     1u << 2, 1u << 2, 1u << 2, 1u << 3};
static const char *const face_names[] = {"x-", "x+", "y-", "y+", "z-", "z+", NULL};
static const char *const axis_names[] = {"x", "y", "z", NULL};

/* Path of a key inside the current entry. */
static const char *key(char *buf, size_t len, const char *entry, const char *name) {
  snprintf(buf, len, "%s.%s", entry, name);
  return buf;
}

static void get_vector(struct cmn_case *c, const char *path, int dim, double *x) {
  x[0] = x[1] = x[2] = 0;
  cmn_case_get_doubles(c, path, dim, dim, x, NULL);
}

/* lo and hi of a box-like entry, with hi > lo in every direction. */
static void get_box(struct cmn_case *c, const char *entry, int dim, double *lo, double *hi) {
  char p[256];
  get_vector(c, key(p, sizeof p, entry, "lo"), dim, lo);
  get_vector(c, key(p, sizeof p, entry, "hi"), dim, hi);
  for (int a = 0; a < dim; a++)
    if (!(hi[a] > lo[a]))
      cmn_case_fail(c, p, "hi must exceed lo in every direction (%c: %g <= %g)", "xyz"[a], hi[a],
                    lo[a]);
}

/* `open: [x-, y+, ...]` as face bits. */
static unsigned get_faces(struct cmn_case *c, const char *entry, int dim, unsigned allowed) {
  char p[256], q[300];
  key(p, sizeof p, entry, "open");
  int n = cmn_case_seq_length(c, p);
  unsigned bits = 0;
  for (int i = 0; i < n; i++) {
    int f;
    snprintf(q, sizeof q, "%s[%d]", p, i);
    cmn_case_get_choice(c, q, face_names, &f);
    if (f >= 2 * dim || !(allowed >> f & 1u))
      cmn_case_fail(c, q, "no such face for this wall type in %dD", dim);
    bits |= 1u << f;
  }
  return bits;
}

/* Orientation of the triangle a, b, c: > 0 counter-clockwise, < 0 clockwise, 0 collinear. */
static double orient(const double *a, const double *b, const double *c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* Point c collinear with segment ab lies within its bounding box. */
static int on_segment(const double *a, const double *b, const double *c) {
  return fmin(a[0], b[0]) <= c[0] && c[0] <= fmax(a[0], b[0]) && fmin(a[1], b[1]) <= c[1] &&
         c[1] <= fmax(a[1], b[1]);
}

/* Segments pq and rs share at least one point. */
static int segments_meet(const double *p, const double *q, const double *r, const double *s) {
  double d1 = orient(r, s, p), d2 = orient(r, s, q), d3 = orient(p, q, r), d4 = orient(p, q, s);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return 1;
  return (d1 == 0 && on_segment(r, s, p)) || (d2 == 0 && on_segment(r, s, q)) ||
         (d3 == 0 && on_segment(p, q, r)) || (d4 == 0 && on_segment(p, q, s));
}

/* Points [[x, y], ...] of a polygon (closed: the last point joins the first). A polygon whose
 * edges cross or touch other than at their shared corners has no inside: an input error naming
 * the two edges. Adjacent edges folding back onto each other count as touching. */
static double (*get_points(struct cmn_case *c, const char *path, size_t min, int closed,
                           size_t *n))[2] {
  int len = cmn_case_seq_length(c, path);
  if (len < (int)min) cmn_case_fail(c, path, "expected a list of at least %zu points [x, y]", min);
  double(*pts)[2] = cmn_malloc((size_t)len * sizeof *pts);
  for (int i = 0; i < len; i++) {
    char q[300];
    snprintf(q, sizeof q, "%s[%d]", path, i);
    cmn_case_get_doubles(c, q, 2, 2, pts[i], NULL);
  }
  const int nedges = closed ? len : len - 1;
  for (int i = 0; i < nedges; i++) {
    const double *a = pts[i], *b = pts[(i + 1) % len];
    for (int j = i + 1; j < nedges; j++) {
      const double *p = pts[j], *q = pts[(j + 1) % len];
      const int next = j == i + 1, prev = closed && i == 0 && j == nedges - 1;
      int meet;
      if (next) /* shares b = p: folds back if q lies on ab beyond b's side, or b on pq */
        meet = orient(a, b, q) == 0 &&
               ((q[0] - b[0]) * (a[0] - b[0]) + (q[1] - b[1]) * (a[1] - b[1])) > 0;
      else if (prev) /* shares a = q */
        meet = orient(a, b, p) == 0 &&
               ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) > 0;
      else
        meet = segments_meet(a, b, p, q);
      if (meet)
        cmn_case_fail(c, path,
                      "the %s crosses itself: edge %d ([%g, %g] to [%g, %g]) meets edge %d ([%g, "
                      "%g] to [%g, %g]); give the points in order around the boundary",
                      closed ? "polygon" : "polyline", i, a[0], a[1], b[0], b[1], j, p[0], p[1],
                      q[0], q[1]);
    }
  }
  *n = (size_t)len;
  return pts;
}

/* File names are relative to the case file's directory. */
static char *resolve(const struct cmn_case *c, const char *file) {
  const char *name = cmn_case_name(c), *slash = strrchr(name, '/');
  size_t dir = file[0] == '/' || !slash ? 0 : (size_t)(slash - name) + 1;
  char *path = cmn_malloc(dir + strlen(file) + 1);
  memcpy(path, name, dir);
  strcpy(path + dir, file);
  return path;
}

static void read_wall(struct cmn_case *c, int i, int dim, double dr, const int *periodic,
                      struct sph_mesh *m) {
  char entry[64], p[256], src[128], msg[2048];
  snprintf(entry, sizeof entry, "geometry.walls[%d]", i);
  int type;
  cmn_case_get_choice(c, key(p, sizeof p, entry, "type"), wall_types, &type);
  if (!(wall_dims[type] >> dim & 1u))
    cmn_case_fail(c, p, "wall type '%s' does not exist in %dD", wall_types[type], dim);
  snprintf(src, sizeof src, "%s (%s)", entry, wall_types[type]);
  double lo[3], hi[3];
  switch (type) {
    case W_INTERVAL:
    case W_BOX: {
      get_box(c, entry, dim, lo, hi);
      unsigned open = get_faces(c, entry, dim, 0x3Fu);
      sph_mesh_box(m, lo, hi, dr, open, 0, sph_mesh_add_source(m, src));
      break;
    }
    case W_CHANNEL: {
      get_box(c, entry, dim, lo, hi);
      if (!periodic[0])
        cmn_case_fail(c, key(p, sizeof p, entry, "type"),
                      "a channel has no walls at its x ends: add x to geometry.periodic, or use a "
                      "box with open: [x-, x+]");
      /* In 3D a channel periodic in y as well has no walls at its y ends either: the floor and
       * lid of an infinite layer. */
      const unsigned skip = dim == 3 && periodic[1] ? 0xFu : 0x3u;
      unsigned open = get_faces(c, entry, dim, 0x3Fu & ~skip);
      sph_mesh_box(m, lo, hi, dr, open, skip, sph_mesh_add_source(m, src));
      break;
    }
    case W_STEP: {
      get_box(c, entry, dim, lo, hi);
      double sl, sh;
      cmn_case_get_positive(c, key(p, sizeof p, entry, "step_length"), &sl);
      if (!(sl < hi[0] - lo[0])) cmn_case_fail(c, p, "must be less than hi[0] - lo[0]");
      cmn_case_get_positive(c, key(p, sizeof p, entry, "step_height"), &sh);
      if (!(sh < hi[1] - lo[1])) cmn_case_fail(c, p, "must be less than hi[1] - lo[1]");
      unsigned open = get_faces(c, entry, dim, 0xFu);
      const double pts[6][2] = {{lo[0], lo[1] + sh}, {lo[0] + sl, lo[1] + sh}, {lo[0] + sl, lo[1]},
                                {hi[0], lo[1]},      {hi[0], hi[1]},           {lo[0], hi[1]}};
      /* Edges: step top, riser, floor, right end, top, left end. */
      uint8_t oe[6] = {open >> 2 & 1u, 0,        open >> 2 & 1u, open >> 1 & 1u,
                       open >> 3 & 1u, open & 1u};
      sph_mesh_polygon(m, 6, pts, 1, 1, oe, sph_mesh_add_source(m, src));
      break;
    }
    case W_WEDGE: {
      double apex[3], angle, len, dir;
      int lid;
      static const char *const lids[] = {"wall", "open", NULL};
      get_vector(c, key(p, sizeof p, entry, "apex"), 2, apex);
      cmn_case_get_double(c, key(p, sizeof p, entry, "angle"), 0, 180, &angle);
      if (!(angle > 0 && angle < 180)) cmn_case_fail(c, p, "expected an angle in (0, 180) degrees");
      cmn_case_get_positive(c, key(p, sizeof p, entry, "length"), &len);
      cmn_case_opt_double(c, key(p, sizeof p, entry, "direction"), 90, -360, 360, &dir);
      cmn_case_opt_choice(c, key(p, sizeof p, entry, "lid"), lids, 0, &lid);
      double a1 = (dir - angle / 2) * PI / 180, a2 = (dir + angle / 2) * PI / 180;
      const double pts[3][2] = {{apex[0], apex[1]},
                                {apex[0] + len * cos(a1), apex[1] + len * sin(a1)},
                                {apex[0] + len * cos(a2), apex[1] + len * sin(a2)}};
      uint8_t oe[3] = {0, (uint8_t)lid, 0};
      sph_mesh_polygon(m, 3, pts, 1, 1, oe, sph_mesh_add_source(m, src));
      break;
    }
    case W_POLYGON: {
      int closed, fluid;
      static const char *const sides[] = {"inside", "outside", "left", "right", NULL};
      cmn_case_opt_bool(c, key(p, sizeof p, entry, "closed"), 1, &closed);
      cmn_case_opt_choice(c, key(p, sizeof p, entry, "fluid"), sides, closed ? 0 : 2, &fluid);
      if ((fluid >= 2) == closed)
        cmn_case_fail(c, p, "%s",
                      closed ? "a closed polygon has the fluid inside or outside"
                             : "an open polyline has the fluid on its left or right");
      size_t n;
      double(*pts)[2] =
          get_points(c, key(p, sizeof p, entry, "points"), closed ? 3 : 2, closed, &n);
      size_t nedges = closed ? n : n - 1;
      uint8_t *oe = cmn_calloc(nedges, 1);
      key(p, sizeof p, entry, "open_edges");
      int no = cmn_case_seq_length(c, p);
      for (int k = 0; k < no; k++) {
        char q[300];
        long e;
        snprintf(q, sizeof q, "%s[%d]", p, k);
        cmn_case_get_long(c, q, 0, (long)nedges - 1, &e);
        oe[e] = 1;
      }
      sph_mesh_polygon(m, n, (const double(*)[2])pts, closed, fluid == 0 || fluid == 2, oe,
                       sph_mesh_add_source(m, src));
      free(oe);
      free(pts);
      break;
    }
    case W_POLYLINE_FILE:
    case W_STL: {
      const char *file;
      int fluid;
      double scale = 1;
      static const char *const sides[] = {"inside", "outside", NULL};
      cmn_case_get_string(c, key(p, sizeof p, entry, "file"), &file);
      char *path = resolve(c, file);
      cmn_case_opt_choice(c, key(p, sizeof p, entry, "fluid"), sides, 0, &fluid);
      int rc;
      if (type == W_STL) {
        cmn_case_opt_positive(c, key(p, sizeof p, entry, "scale"), 1.0, &scale);
        /* open boundaries: the whole file, or its ASCII solids by name */
        struct sph_stl_open op = {0, 0, NULL};
        cmn_case_opt_bool(c, key(p, sizeof p, entry, "open"), 0, &op.all);
        key(p, sizeof p, entry, "open_solids");
        const int nn = cmn_case_seq_length(c, p);
        const char **names = cmn_calloc((size_t)(nn > 0 ? nn : 0) + 1, sizeof *names);
        for (int k = 0; k < nn; k++) {
          char q[300];
          snprintf(q, sizeof q, "%s[%d]", p, k);
          cmn_case_get_string(c, q, &names[k]);
          for (int l = 0; l < k; l++)
            if (strcmp(names[l], names[k]) == 0)
              cmn_case_fail(c, q, "solid '%s' is named twice (entries %d and %d)", names[k], l, k);
        }
        if (op.all && nn > 0)
          cmn_case_fail(c, p,
                        "give 'open: true' (the whole file) or 'open_solids' (some of its "
                        "solids), not both");
        op.n = nn > 0 ? nn : 0;
        op.names = names;
        int s0 = m->nsources;
        rc = sph_mesh_read_stl_open(m, path, scale, fluid == 0, &op, msg, sizeof msg);
        free(names);
        int any_periodic = periodic[0] || periodic[1] || periodic[2];
        if (rc == 0 && !any_periodic) { /* orientation of a closed surface as a whole */
          double vol = sph_mesh_signed_volume(m, s0);
          if (sph_mesh_check(m, NULL, msg, sizeof msg) == 0 && (vol > 0) != (fluid == 0))
            cmn_input_error(
                "%s: %s: the surface encloses a negative volume with fluid: %s, so "
                "its facets are ordered clockwise seen from outside the solid "
                "(inside out); fix the file, or set fluid: %s if that was meant",
                cmn_case_name(c), path, sides[fluid], sides[!fluid]);
        }
      } else {
        rc = sph_mesh_read_polyline(m, path, fluid == 0, msg, sizeof msg);
      }
      if (rc) cmn_input_error("%s: %s: %s", cmn_case_name(c), entry, msg);
      free(path);
      break;
    }
  }
}

static void read_region(struct cmn_case *c, int i, int dim, struct sph_region *r) {
  char entry[64], p[256];
  static const char *const types[] = {"box", "polygon", NULL};
  snprintf(entry, sizeof entry, "geometry.fluid[%d]", i);
  memset(r, 0, sizeof *r);
  cmn_case_get_choice(c, key(p, sizeof p, entry, "type"), types, &r->type);
  if (r->type == 0) {
    get_box(c, entry, dim, r->lo, r->hi);
    return;
  }
  if (dim != 2) cmn_case_fail(c, p, "polygon regions exist in 2D only");
  r->pts = get_points(c, key(p, sizeof p, entry, "points"), 3, 1, &r->npts);
  r->lo[0] = r->lo[1] = INFINITY;
  r->hi[0] = r->hi[1] = -INFINITY;
  for (size_t k = 0; k < r->npts; k++)
    for (int a = 0; a < 2; a++) {
      r->lo[a] = fmin(r->lo[a], r->pts[k][a]);
      r->hi[a] = fmax(r->hi[a], r->pts[k][a]);
    }
}

/* ---------------------------------------------------------------------------------------------
 * Size of the run before building it: a tiny dr or a geometry in the wrong unit (a 10 km STL read
 * as metres) would otherwise sit silent for minutes growing memory. The estimate is an upper bound
 * (fluid regions are clipped by the walls) and counts, per particle, the fields and the neighbour
 * list entries of a support of radius 2h.
 * ------------------------------------------------------------------------------------------- */
static double neighbours_per_particle(int dim, double h_over_dr) {
  const double r = 2.0 * h_over_dr; /* support radius in units of dr */
  return dim == 1 ? 2.0 * r : dim == 2 ? PI * r * r : 4.0 / 3.0 * PI * r * r * r;
}

static double physical_memory(void) {
  long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? (double)pages * (double)size : INFINITY;
}

/* Volume (dim 2: area; 1: length) of the box lo..hi, or the bounding box of a polygon's points,
 * of entry `entry` when its keys are present and well formed (else 0: the getters report them
 * later, in order). */
static double entry_extent(struct cmn_case *c, const char *entry, int dim, double *surface) {
  char p[256];
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  *surface = 0.0;
  if (cmn_case_has(c, key(p, sizeof p, entry, "lo")) &&
      cmn_case_has(c, key(p, sizeof p, entry, "hi"))) {
    cmn_case_get_doubles(c, key(p, sizeof p, entry, "lo"), dim, dim, lo, NULL);
    cmn_case_get_doubles(c, key(p, sizeof p, entry, "hi"), dim, dim, hi, NULL);
  } else if (dim == 2 && cmn_case_seq_length(c, key(p, sizeof p, entry, "points")) > 0) {
    int n = cmn_case_seq_length(c, p);
    lo[0] = lo[1] = INFINITY;
    hi[0] = hi[1] = -INFINITY;
    for (int i = 0; i < n; i++) {
      char q[300];
      double x[2];
      snprintf(q, sizeof q, "%s[%d]", p, i);
      cmn_case_get_doubles(c, q, 2, 2, x, NULL);
      for (int a = 0; a < 2; a++) lo[a] = fmin(lo[a], x[a]), hi[a] = fmax(hi[a], x[a]);
    }
  } else {
    return 0.0;
  }
  double vol = 1.0, len[3];
  for (int a = 0; a < dim; a++) vol *= len[a] = fabs(hi[a] - lo[a]);
  *surface = dim == 1   ? 2.0
             : dim == 2 ? 2.0 * (len[0] + len[1])
                        : 2.0 * (len[0] * len[1] + len[1] * len[2] + len[2] * len[0]);
  return vol;
}

/* Estimate the particles and memory of g (walls: `wall_measure` of the unrefined mesh, or < 0 to
 * take the walls' boxes from the case) and stop if the run cannot fit in memory. */
static void size_check(struct cmn_case *c, struct sph_geometry *g, double wall_measure, int say) {
  const int dim = g->dim;
  const double dr = g->dr, cell = pow(dr, dim), face = dim == 1 ? 1.0 : pow(dr, dim - 1);
  double fluid = 0.0, walls = 0.0, surface;
  int nr = cmn_case_seq_length(c, "geometry.fluid"), nw = cmn_case_seq_length(c, "geometry.walls");
  for (int i = 0; i < nr; i++) {
    char entry[64];
    snprintf(entry, sizeof entry, "geometry.fluid[%d]", i);
    fluid += entry_extent(c, entry, dim, &surface) / cell;
  }
  if (wall_measure >= 0.0) {
    walls = dim == 1 ? wall_measure : wall_measure / face * (dim == 3 ? 2.0 : 1.0);
  } else {
    for (int i = 0; i < nw; i++) {
      char entry[64];
      snprintf(entry, sizeof entry, "geometry.walls[%d]", i);
      entry_extent(c, entry, dim, &surface);
      walls += surface / face * (dim == 3 ? 2.0 : 1.0);
    }
  }
  /* per fluid particle: ~60 doubles of fields and its fluid row of 4-byte entries (radius 2h +
   * skin: 1.33 nb entries, 1.125 of them allocated); per segment: its fields, its vertex's row and
   * the fluid–segment pair data (fitted to bench-dambreak's peak at 10^6 fluid particles, 3.1 GB,
   * to about 10 %) */
  const double nb = neighbours_per_particle(dim, g->h_over_dr);
  const double bytes = fluid * (480.0 + 6.0 * nb) + walls * (480.0 + 5.0 * nb);
  g->est_fluid = fluid;
  g->est_walls = walls;
  g->est_bytes = bytes;
  const double mem = physical_memory();
  if (!(bytes < 0.8 * mem) || !(fluid + 2.0 * walls < 2e9))
    cmn_case_fail(c, "geometry.dr",
                  "dr = %g m gives about %.3g fluid particles and %.3g wall segments, some %.3g "
                  "GB, beyond this machine's %.3g GB of memory: increase dr, or check the "
                  "geometry's unit (STL files are read in metres, geometry.walls[].scale)",
                  dr, fluid, walls, bytes / 1e9, mem / 1e9);
  if (say)
    cmn_message("%s: about %.3g fluid particles and %.3g wall segments (%.3g MB); meshing...",
                cmn_case_name(c), fluid, walls, bytes / 1e6);
}

void sph_geometry_read(struct sph_geometry *g, struct cmn_case *c) {
  memset(g, 0, sizeof *g);
  long dim;
  cmn_case_get_long(c, "geometry.dimension", 1, 3, &dim);
  g->dim = (int)dim;
  cmn_case_get_positive(c, "geometry.dr", &g->dr);
  /* h/dr in [1, 20]: below, too few neighbours for the kernel sums; above, neighbour counts (and
   * memory) grow as (h/dr)^d far beyond any convergence study. 1e6 is a typo, not a resolution. */
  cmn_case_opt_double(c, "geometry.h_over_dr", 2.0, SPH_H_OVER_DR_MIN, SPH_H_OVER_DR_MAX,
                      &g->h_over_dr);
  cmn_case_opt_double(c, "geometry.min_wall_distance", 0.5 * g->dr, 0, INFINITY,
                      &g->min_wall_distance);
  cmn_case_opt_double(c, "geometry.first_row", 0.5, 0.0, 1.0, &g->first_row);
  if (!(g->first_row > 0.0))
    cmn_case_fail(c, "geometry.first_row", "expected a number in (0, 1] (units of dr), got %g",
                  g->first_row);
  struct sph_domain *dom = &g->domain;
  dom->dim = g->dim;
  int np = cmn_case_seq_length(c, "geometry.periodic");
  for (int i = 0; i < np; i++) {
    char q[64];
    int a;
    snprintf(q, sizeof q, "geometry.periodic[%d]", i);
    cmn_case_get_choice(c, q, axis_names, &a);
    if (a >= g->dim) cmn_case_fail(c, q, "no direction %s in %ldD", axis_names[a], dim);
    dom->periodic[a] = 1;
  }
  size_check(c, g, -1.0, 0); /* before any generator meshes a box at spacing dr */
  sph_mesh_init(&g->walls, g->dim);
  int nw = cmn_case_seq_length(c, "geometry.walls");
  for (int i = 0; i < nw; i++) read_wall(c, i, g->dim, g->dr, dom->periodic, &g->walls);
  g->nregions = cmn_case_seq_length(c, "geometry.fluid");
  g->regions = cmn_calloc((size_t)g->nregions + 1, sizeof *g->regions);
  for (int i = 0; i < g->nregions; i++) read_region(c, i, g->dim, &g->regions[i]);

  /* Domain: given, or the bounding box of walls and fluid. */
  if (cmn_case_is_map(c, "geometry.domain") == 1) {
    get_box(c, "geometry.domain", g->dim, dom->lo, dom->hi);
  } else {
    for (int a = 0; a < g->dim; a++) {
      dom->lo[a] = INFINITY;
      dom->hi[a] = -INFINITY;
      for (size_t v = 0; v < g->walls.nvert; v++) {
        dom->lo[a] = fmin(dom->lo[a], g->walls.vert[v][a]);
        dom->hi[a] = fmax(dom->hi[a], g->walls.vert[v][a]);
      }
      for (int r = 0; r < g->nregions; r++) {
        dom->lo[a] = fmin(dom->lo[a], g->regions[r].lo[a]);
        dom->hi[a] = fmax(dom->hi[a], g->regions[r].hi[a]);
      }
      if (!(dom->hi[a] > dom->lo[a]))
        cmn_case_fail(c, "geometry",
                      "no walls or fluid regions to size the domain in %c: give "
                      "geometry.domain",
                      "xyz"[a]);
    }
  }

  double measure = 0.0; /* the walls as read, before refining (an STL's true size) */
  for (size_t e = 0; e < g->walls.nelem; e++) {
    double v[3][3];
    geom_element_vertices(&g->walls, e, v);
    measure += g->dim == 1 ? 1.0 : geom_element_measure(g->dim, v);
  }
  size_check(c, g, measure, 1);
  double tol = 1e-9 * g->dr;
  sph_mesh_merge_vertices(&g->walls, tol);
  char msg[2048];
  /* Check the walls as given first, so messages quote the user's own points and triangles; with
   * periodic directions the walls close only once joined across the boundary (after refining). */
  int any_periodic = dom->periodic[0] || dom->periodic[1] || dom->periodic[2];
  if (!any_periodic && sph_mesh_check(&g->walls, NULL, msg, sizeof msg))
    cmn_input_error("%s: geometry.walls: %s", cmn_case_name(c), msg);
  sph_mesh_refine(&g->walls, g->dr);
  geom_mesh_identify_periodic(&g->walls, dom, 1e-6 * g->dr);
  if (sph_mesh_check(&g->walls, dom, msg, sizeof msg))
    cmn_input_error("%s: geometry.walls: %s", cmn_case_name(c), msg);
  if (g->walls.nelem == 0 &&
      !(dom->periodic[0] && (g->dim < 2 || dom->periodic[1]) && (g->dim < 3 || dom->periodic[2])))
    cmn_warning(
        "%s: geometry: no walls and not periodic in every direction: the fluid is "
        "unbounded",
        cmn_case_name(c));
}

void sph_geometry_free(struct sph_geometry *g) {
  sph_mesh_free(&g->walls);
  for (int r = 0; r < g->nregions; r++) free(g->regions[r].pts);
  free(g->regions);
  memset(g, 0, sizeof *g);
}
