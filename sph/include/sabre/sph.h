/*
 * SABRE sph/ — public API of the SPH solver library: particle store, cell lists and neighbour
 * lists, wall geometry (generators, polyline and STL import, meshing, checks, fluid filling) and
 * VTK XML output. Kernel and γ integrals: sabre/sph_walls.h.
 *
 * Units are SI throughout (m, s, kg). Dimension d ∈ {1, 2, 3} is a run-time choice; vectors are
 * always stored with three components, the unused ones being 0.
 *
 * Like the rest of sph/, these functions stop the program on errors they cannot report
 * (out of memory: cmn_error()). Functions that read user input (case files, polyline and STL files)
 * report bad input through cmn_case_fail()/cmn_input_error() (exit code 2) or, where stated, return
 * -1 with a message in a caller-provided buffer so tests can check the message.
 */
#ifndef SABRE_SPH_H
#define SABRE_SPH_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

struct cmn_case;

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * Particle store
 *
 * One struct sph_parts holds the particles of one kind as a structure of arrays, so a neighbour
 * loop streams through the few arrays it reads. Kinds follow the unified semi-analytical wall
 * model (docs/theory.md §3): fluid particles, vertex particles (mesh nodes of the walls, their
 * masses vary on open boundaries) and segment particles (1D: a boundary point; 2D: a line segment
 * between two vertices; 3D: a triangle between three vertices). The fluid count varies at run time
 * (particles are created and removed at open boundaries); ids are stable and unique over all kinds.
 * ------------------------------------------------------------------------------------------- */

enum sph_kind { SPH_KIND_FLUID = 0, SPH_KIND_VERTEX = 1, SPH_KIND_SEGMENT = 2 };
#define SPH_NKINDS 3

/** Bits of sph_parts.flags. */
enum sph_flag {
  SPH_FLAG_OPEN = 1u << 0,   /**< vertex/segment on an open (inlet/outlet) boundary, else wall */
  SPH_FLAG_CORNER = 1u << 1, /**< vertex shared by a wall segment and an open segment */
  SPH_FLAG_WET = 1u << 2,    /**< open segment or vertex whose boundary Riemann problem was solved
                                  at the last evaluation (dry ones keep wall values) */
};

struct sph_parts {
  enum sph_kind kind;
  size_t n;              /**< number of particles */
  size_t capacity;       /**< allocated length of every array */
  double *x[3];          /**< position [m]; a segment's position is its centroid */
  double *v[3];          /**< velocity [m/s] */
  double *mass;          /**< mass [kg] (fluid, vertex; set by the solver, 0 after meshing) */
  double *rho;           /**< density [kg/m^3] (set by the solver, 0 after meshing) */
  double *p;             /**< pressure [Pa] (set by the solver, 0 after meshing) */
  double *gamma;         /**< γ, J(2) (fluid, vertex) [-] */
  double *grad_gamma[3]; /**< ∇γ, J(4) (fluid, vertex) [1/m] */
  double *normal[3];     /**< unit normal into the fluid (segment; vertex: mean of its segments) */
  double *measure;       /**< segment length (2D) or area (3D) [m^(d-1)]; 1 in 1D */
  double *volume;        /**< vertex: V_v, the volume of the wall layer it stands for, m_v/ρ_v
                              once the set-up has fixed the masses [m^d] (set by the solver) */
  double *wall_mass;     /**< vertex: its mass once the set-up has fixed the masses [kg] (set by
                              the solver; an open vertex's creation threshold and outflow floor
                              follow from it) */
  size_t *vertex[3];     /**< segment: indices of its d vertices in the vertex store */
  int64_t *id;           /**< stable id, unique over all kinds */
  uint8_t *flags;        /**< enum sph_flag bits */
};

/** Empty store of one kind (no allocation). Fields a kind does not use stay NULL. */
void sph_parts_init(struct sph_parts *p, enum sph_kind kind);
void sph_parts_free(struct sph_parts *p);
/** Grow the arrays to hold at least `capacity` particles (never shrinks). */
void sph_parts_reserve(struct sph_parts *p, size_t capacity);
/** Append `count` zero-filled particles; returns the index of the first one. */
size_t sph_parts_append(struct sph_parts *p, size_t count);
/** Remove the particles with remove[i] != 0, keeping the order of the others. Returns how many
 *  were removed. Segments refer to vertices by index: do not remove vertices. */
size_t sph_parts_remove(struct sph_parts *p, const uint8_t *remove);
/** Reorder: particle i becomes old particle order[i] (order is a permutation of 0..n-1). */
void sph_parts_permute(struct sph_parts *p, const size_t *order);

/**
 * Description of one per-particle field, for generic code (output, resize, permute).
 * `offset` is the offset of the first component pointer within struct sph_parts.
 */
enum sph_field_type { SPH_FIELD_DOUBLE, SPH_FIELD_INT64, SPH_FIELD_UINT8, SPH_FIELD_SIZE };
struct sph_field {
  const char *name;
  enum sph_field_type type;
  int ncomp;      /**< 1 or 3 */
  size_t offset;  /**< offsetof(struct sph_parts, <field>) */
  unsigned kinds; /**< bit (1 << kind) set when the kind carries the field */
};
/** Bytes per particle of one component of a field of this type (0 for an unknown type). */
size_t sph_field_type_size(enum sph_field_type type);
/** The field table (count in *n). */
const struct sph_field *sph_parts_fields(int *n);
/** Pointer to component c of field f of p (NULL if the kind does not carry it). */
void *sph_parts_field_data(const struct sph_parts *p, const struct sph_field *f, int c);

/** Simulation domain: bounding box [m], and which directions are periodic (period hi − lo). */
struct sph_domain {
  int dim;
  double lo[3], hi[3];
  int periodic[3];
};
/** Minimum-image separation dx = b − a (periodic directions wrapped into [−L/2, L/2]). */
static inline void sph_domain_delta(const struct sph_domain *dom, const double *a, const double *b,
                                    double *dx) {
  for (int k = 0; k < 3; k++) {
    dx[k] = b[k] - a[k];
    if (k < dom->dim && dom->periodic[k]) {
      double len = dom->hi[k] - dom->lo[k];
      if (dx[k] > 0.5 * len)
        dx[k] -= len;
      else if (dx[k] < -0.5 * len)
        dx[k] += len;
    }
  }
}

/** All particles of a run: one store per kind, the domain and the id counter. */
struct sph_system {
  int dim;
  double dr; /**< initial particle spacing Δr [m] */
  double h;  /**< smoothing length [m] */
  struct sph_domain domain;
  struct sph_parts part[SPH_NKINDS]; /**< indexed by enum sph_kind */
  int64_t next_id;
};
void sph_system_init(struct sph_system *s, int dim);
void sph_system_free(struct sph_system *s);
/** Append count particles of a kind and give them fresh ids; returns the first index. */
size_t sph_system_append(struct sph_system *s, enum sph_kind kind, size_t count);

/* ---------------------------------------------------------------------------------------------
 * Cell lists and neighbour lists
 *
 * Cells are at least `cell_min` wide (pass the kernel support 2h). Particles of each kind are
 * binned by a counting sort and their positions copied in cell order (the hot data of the
 * neighbour loops). A segment is a neighbour of a point when the distance from the point to the
 * segment (the whole element, not its centroid) is below the radius; the stencil is widened by the
 * largest centroid-to-vertex distance so that no such segment is missed.
 * Periodic directions need hi − lo ≥ 2 (radius + that reach), so a pair meets once.
 * ------------------------------------------------------------------------------------------- */

struct sph_cells {
  int dim;
  struct sph_domain domain; /**< periodic box; non-periodic directions: bounding box of particles */
  int ncell[3];             /**< cells per direction (1 for unused directions) */
  double width[3];          /**< cell width per direction [m], ≥ cell_min */
  size_t ncells;
  size_t *start[SPH_NKINDS]; /**< particles of cell c: index[k][start[k][c] .. start[k][c+1]) */
  size_t *index[SPH_NKINDS]; /**< particle indices in cell order */
  double *xs[SPH_NKINDS][3]; /**< positions in cell order */
  double segment_reach;      /**< max centroid-to-vertex distance of the segments [m] */
  size_t alloc[SPH_NKINDS];
};

/**
 * Bin every particle of s into cells at least cell_min wide (> 0; sparse sets get wider cells so
 * that there are at most about 4 cells per particle). Reuses c's arrays when called again
 * (initialise c to zero first). Stops (cmn_error) on a non-finite position.
 */
void sph_cells_build(struct sph_cells *c, const struct sph_system *s, double cell_min);
void sph_cells_free(struct sph_cells *c);

/** Neighbour lists in compressed rows: neighbours of query particle i of kind `query` are the
 *  particles index[offset[i] .. offset[i+1]) of kind `other`. Neighbour indices are 32-bit
 *  (sph_nbr_t): the lists are most of a run's memory, and a kind never holds 2^32 particles in
 *  the memory of one machine (sph_nlist_build stops if it does). */
typedef uint32_t sph_nbr_t;
#define SPH_NBR_MAX UINT32_MAX
struct sph_nlist_scratch;

struct sph_nlist {
  enum sph_kind query, other;
  size_t n;       /**< number of query particles (rows) */
  size_t *offset; /**< n + 1 entries */
  sph_nbr_t *index;
  size_t capacity;                   /**< allocated length of index */
  struct sph_nlist_scratch *scratch; /**< work buffers kept between builds (owned; NULL at first) */
};

/**
 * Build the list of particles of kind `other` within `radius` of each particle of kind `query`
 * (strictly closer; a particle is not its own neighbour). Segment–segment lists are not supported.
 * OpenMP-parallel gather over cells; the result does not depend on the thread count. Each row is
 * sorted by neighbour index (as the naive search gives it), so that sums over a row run in the
 * same order whatever the radius and the positions at the build. `c` must have been built from
 * `s` as it is now; the radius may span up to 16 cells. Stops with an input error
 * (exit 2) if a periodic direction is shorter than 2 (radius + segment reach).
 */
void sph_nlist_build(struct sph_nlist *nl, const struct sph_cells *c, const struct sph_system *s,
                     enum sph_kind query, enum sph_kind other, double radius);
/** The same list by the naive O(N^2) search (tests and checks). Neighbours in index order. */
void sph_nlist_build_naive(struct sph_nlist *nl, const struct sph_system *s, enum sph_kind query,
                           enum sph_kind other, double radius);
void sph_nlist_free(struct sph_nlist *nl);

/**
 * Vertices of segment j of s, as positions shifted by whole periods so that they lie next to the
 * point `near` (minimum image); v[k][0..2] for k < dim.
 */
void sph_segment_vertices(const struct sph_system *s, size_t j, const double *near, double v[3][3]);
/**
 * Distance from point a to the element with vertices v (1D: point; 2D: segment; 3D: triangle),
 * and the closest point q. Returns the distance [m].
 */
double sph_element_distance(int dim, const double v[3][3], const double *a, double *q);

/* ---------------------------------------------------------------------------------------------
 * Wall meshes
 *
 * A mesh is the walls as elements (1D points, 2D segments, 3D triangles) on shared vertices.
 * Orientation: in 2D the fluid lies to the left of the segment v0 → v1; in 3D the normal
 * (v1 − v0) × (v2 − v0) (right-hand rule) points into the fluid; in 1D each element carries its
 * normal ±1. Each element remembers where it came from (a source string and an index, e.g. the
 * triangle number in an STL file) so that checks can name it.
 * ------------------------------------------------------------------------------------------- */

/** A named part of a source: the elements numbered first..last of that source (an ASCII STL
 *  file's `solid NAME` ... `endsolid` block). */
struct sph_mesh_part {
  int source;       /**< index into sources[] */
  long first, last; /**< element numbers (source_index) of the part, inclusive */
  char name[256];   /**< the solid's name (the reader keeps 255 bytes: no longer name can match a
                         shorter one by its prefix) */
};

struct sph_mesh {
  int dim;
  size_t nvert, nelem;
  double (*vert)[3];
  size_t (*elem)[3];
  double (*normal)[3]; /**< unit normal into the fluid per element */
  uint8_t *flags;      /**< SPH_FLAG_OPEN for open-boundary elements */
  int *source;         /**< index into sources[] */
  long *source_index;  /**< element number within its source (from 1; 0 if none) */
  long *source_line;   /**< line of a text file where the element is written (0 if none) */
  char **sources;      /**< e.g. "geometry.walls[1] (box)" or "tank.stl" */
  int nsources;
  struct sph_mesh_part *parts; /**< named parts of sources (STL solids) */
  int nparts;
  size_t cap_vert, cap_elem;
};

void sph_mesh_init(struct sph_mesh *m, int dim);
void sph_mesh_free(struct sph_mesh *m);
/** Register a source name for messages; returns its index. */
int sph_mesh_add_source(struct sph_mesh *m, const char *name);
/** Record that elements first..last of source are the part called name (copied, truncated). */
void sph_mesh_add_part(struct sph_mesh *m, int source, const char *name, long first, long last);
size_t sph_mesh_add_vertex(struct sph_mesh *m, const double *x);
/**
 * Add an element on vertices v[0..dim-1]. In 2D/3D the normal follows from the orientation;
 * in 1D pass normal1d = ±1. Degenerate elements (zero length/area) are kept here and rejected by
 * sph_mesh_check().
 */
size_t sph_mesh_add_element(struct sph_mesh *m, const size_t *v, double normal1d, uint8_t flags,
                            int source, long source_index);
/** Merge vertices closer than tol in every coordinate (exact duplicates when tol = 0) and drop
 *  vertices no element uses. */
void sph_mesh_merge_vertices(struct sph_mesh *m, double tol);
/**
 * Split the elements so that they are about dr in size: 2D segments into round(L/dr) equal parts;
 * 3D triangles by conforming longest-edge bisection until no edge exceeds 1.5 dr (a conforming
 * mesh stays conforming). 1D: nothing to do.
 */
void sph_mesh_refine(struct sph_mesh *m, double dr);
/**
 * Check that the mesh is a consistent closed wall: no degenerate element; 2D: every vertex ends
 * exactly one segment and starts exactly one; 3D: every edge is shared by exactly two triangles
 * that run through it in opposite directions. Ends and edges lying on a periodic boundary of dom
 * (dom may be NULL) are allowed to be open. Returns 0, or -1 with a message naming the source,
 * element and position in msg.
 */
int sph_mesh_check(const struct sph_mesh *m, const struct sph_domain *dom, char *msg,
                   size_t msglen);
/** Signed volume (3D) or area (2D) enclosed by the elements of one source [m^d]: positive when
 *  the normals point into the enclosed region (fluid inside a closed wall), negative when they
 *  point out of it (fluid around an obstacle). */
double sph_mesh_signed_volume(const struct sph_mesh *m, int source);

/* Generators. All return elements oriented with normals into the fluid, one source each. */
/**
 * Closed polygon (2D) through pts[0..n-1]; fluid inside for a counter-clockwise polygon when
 * fluid_inside, else outside. Edge i (pts[i] → pts[i+1]) is open when open_edges[i] != 0
 * (open_edges may be NULL). closed = 0 gives the polyline without its closing edge.
 */
void sph_mesh_polygon(struct sph_mesh *m, size_t n, const double (*pts)[2], int closed,
                      int fluid_inside, const uint8_t *open_edges, int source);
/**
 * Axis-aligned box [lo, hi] with the fluid inside, in dimension m->dim: 1D interval, 2D rectangle,
 * 3D six faces meshed at spacing ≈ dr. open: bit 2a = face at lo of axis a, bit 2a+1 = face at hi.
 * skip: same bits, faces left out (channels).
 */
void sph_mesh_box(struct sph_mesh *m, const double *lo, const double *hi, double dr, unsigned open,
                  unsigned skip, int source);

/**
 * Read a 2D polyline file (format in docs/sph-geometry.md). Returns 0, or -1 with
 * "<path>:<line>: <what was expected>" in msg.
 */
int sph_mesh_read_polyline(struct sph_mesh *m, const char *path, int fluid_inside, char *msg,
                           size_t msglen);
/**
 * Read an STL file (ASCII or binary, detected), multiply coordinates by scale, merge identical
 * vertices. fluid_inside: the fluid is inside the closed surface (the facets' right-hand normals,
 * which point out of the solid the STL bounds, are turned inwards). Returns 0, or -1 with a message
 * naming the file and the line (ASCII) or triangle (binary). Facet normals that disagree with the
 * vertex order are an error.
 */
int sph_mesh_read_stl(struct sph_mesh *m, const char *path, double scale, int fluid_inside,
                      char *msg, size_t msglen);
/** Which facets of an STL file are open boundaries (SPH_FLAG_OPEN): all of them, or those of the
 *  ASCII file's solids with the given names (`solid NAME` ... `endsolid`). */
struct sph_stl_open {
  int all;                  /**< 1: every facet of the file */
  int n;                    /**< number of names */
  const char *const *names; /**< solid names (case-sensitive), each must be in the file */
};
/** sph_mesh_read_stl() with open facets: open == NULL or {0, 0, NULL} flags none. Errors (−1 with a
 *  message naming the file): a listed name that no solid of the file has, or names with a binary
 *  file (which has no solid names). */
int sph_mesh_read_stl_open(struct sph_mesh *m, const char *path, double scale, int fluid_inside,
                           const struct sph_stl_open *open, char *msg, size_t msglen);
/** Write the elements of a 3D mesh as STL (binary or ASCII), normals out of the fluid, so that
 *  reading the file back with fluid_inside = 1 returns the same mesh. Returns 0 or -1 (errno). */
int sph_mesh_write_stl(const struct sph_mesh *m, const char *path, int binary);

/* ---------------------------------------------------------------------------------------------
 * Geometry: case-file section, walls to particles, fluid filling
 * ------------------------------------------------------------------------------------------- */

/** Range of geometry.h_over_dr (docs/sph-geometry.md). */
#define SPH_H_OVER_DR_MIN 1.0
#define SPH_H_OVER_DR_MAX 20.0

/** Resolved `geometry` section of a case file (docs/sph-geometry.md). */
struct sph_geometry {
  int dim;
  double dr;                /**< particle spacing Δr [m] */
  double h_over_dr;         /**< h / Δr [-] */
  double min_wall_distance; /**< fluid particles closer to a wall are not created [m] */
  double first_row;         /**< lattice offset: points at lo + (i + first_row) Δr [Δr] */
  double est_fluid; /**< fluid particles expected (regions' volume / Δr^d, an upper bound) */
  double est_walls; /**< wall segments expected after refining to Δr */
  double est_bytes; /**< memory expected for the run [bytes] */
  struct sph_domain domain;
  struct sph_mesh walls; /**< refined, merged, checked */
  /** Fluid regions, in case order. */
  int nregions;
  struct sph_region {
    int type;            /**< 0 box, 1 polygon (2D) */
    double lo[3], hi[3]; /**< box, or bounding box of the polygon */
    size_t npts;
    double (*pts)[2];
  } * regions;
};

/**
 * Read the `geometry` section of a case file (fatal mode: bad input stops the program naming the
 * file, line and key), build, refine, merge and check the wall mesh. Relative file names are
 * relative to the case file's directory.
 */
void sph_geometry_read(struct sph_geometry *g, struct cmn_case *c);
void sph_geometry_free(struct sph_geometry *g);

/** Turn a checked mesh into vertex and segment particles of s (appended). Vertex normals are the
 *  measure-weighted mean of their segments'; flags as described for enum sph_flag. */
void sph_system_add_walls(struct sph_system *s, const struct sph_mesh *m);
/**
 * Fill the fluid regions of g on a lattice of spacing dr (points lo + (i + first_row) dr, i = 0 ..
 * n − 1 with n = ⌊(hi − lo)/dr⌋ per direction; first_row = 1 puts the first row dr from walls on
 * the region's faces, the last point then lying on the hi face), keeping the
 * points inside the walls (side of the nearest element, with pseudo-normals at edges and
 * vertices; points far from every wall take the side of their lattice neighbours) and at least
 * min_wall_distance from them. The walls must already be in s. Returns the count added.
 */
size_t sph_system_fill(struct sph_system *s, const struct sph_geometry *g);
/**
 * Side of the walls of s on which point x lies, from the nearest wall element (pseudo-normals at
 * edges and vertices; O(segments), for checks, not for loops): 1 the fluid side, 0 the other side,
 * −1 if s has no walls. *dist receives the distance to the nearest element [m].
 */
int sph_system_wall_side(const struct sph_system *s, const double *x, double *dist);
/** sph_system_init + walls + fluid for a geometry; s->h = h_over_dr · dr. */
void sph_system_from_geometry(struct sph_system *s, const struct sph_geometry *g);

/* ---------------------------------------------------------------------------------------------
 * VTK XML output
 *
 * Per output time: <dir>/fluid_<step>.vtu (fluid particles as vertex cells) and
 * <dir>/boundary_<step>.vtu (vertex particles as points, segments as cells: lines in 2D,
 * triangles in 3D, vertex cells in 1D; segment fields as cell data). <dir>/<name>.pvd lists them
 * (part 0 = fluid, part 1 = boundary) and is rewritten after each output, so a run can be opened
 * in ParaView while it goes. Data are raw binary appended (little-endian, UInt64 headers).
 * ------------------------------------------------------------------------------------------- */

struct sph_output {
  char *dir;
  char *name; /**< series name, e.g. "particles" */
  int count;
  double *times;
  int cap;
};
/** Start a series in dir (created if needed). Returns 0 or -1 (errno). */
int sph_output_open(struct sph_output *o, const char *dir, const char *name);
/** Write one output time (the index is the number of previous outputs). Returns 0 or -1. */
int sph_output_write(struct sph_output *o, const struct sph_system *s, double time);
void sph_output_close(struct sph_output *o);

/* ---------------------------------------------------------------------------------------------
 * Commands of the sabre-sph program (docs/sph-geometry.md §6). argv[0] is the command's name.
 * They return the exit code; bad input stops the program with CMN_EXIT_INPUT and a message.
 * ------------------------------------------------------------------------------------------- */

/** `gamma --dim D --dr DR --h-over-dr K [--box LO:HI] [--stl FILE [--stl-fluid inside|outside]]
 *  --at X[,Y[,Z]] ...`: one JSON object {"at", "gamma", "grad_gamma"} per point on stdout. */
int sph_cmd_gamma(int argc, char **argv);
/** `mesh CASE.yaml --output DIR [--set key=value ...]`: walls, fluid and γ as VTU files. */
int sph_cmd_mesh(int argc, char **argv);
/** The program's usage text. */
void sph_cmd_usage(FILE *out);

#ifdef __cplusplus
}
#endif
#endif /* SABRE_SPH_H */
