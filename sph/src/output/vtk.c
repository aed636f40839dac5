/* VTK XML output: one UnstructuredGrid file per piece (fluid, boundary) and output time, with
 * every particle field of the store's field table, plus a .pvd collection for the series.
 * Data are appended raw binary (UInt64 block headers) to keep files small and exact. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph.h"

enum vtk_source { SRC_FIELD, SRC_POINTS, SRC_CONN, SRC_OFFSETS, SRC_TYPES };
enum vtk_section { SEC_POINTDATA, SEC_CELLDATA, SEC_POINTS, SEC_CELLS };

struct vtk_array {
  enum vtk_section section;
  const char *name;
  enum sph_field_type type;
  int ncomp;
  size_t n; /* tuples */
  enum vtk_source src;
  const struct sph_parts *p; /* SRC_FIELD */
  const struct sph_field *f; /* SRC_FIELD */
  const size_t *map;         /* SRC_FIELD: tuple i is particle map[i] (NULL: i) */
  const double (*pos)[3];    /* SRC_POINTS */
  const size_t *conn;        /* SRC_CONN (NULL: 0, 1, 2, ...) */
  int per_cell;              /* SRC_OFFSETS */
  uint8_t cell_type;         /* SRC_TYPES */
};

static size_t elem_size(enum sph_field_type t) { return t == SPH_FIELD_UINT8 ? 1 : 8; }

static const char *vtk_type(enum sph_field_type t) {
  return t == SPH_FIELD_DOUBLE ? "Float64" : t == SPH_FIELD_UINT8 ? "UInt8" : "Int64";
}

static void fill(const struct vtk_array *a, void *out) {
  double *d = out;
  int64_t *l = out;
  uint8_t *u = out;
  switch (a->src) {
    case SRC_FIELD:
      for (int c = 0; c < a->ncomp; c++) {
        const void *src = sph_parts_field_data(a->p, a->f, c);
        for (size_t i = 0; i < a->n; i++) {
          size_t j = a->map ? a->map[i] : i, k = i * (size_t)a->ncomp + (size_t)c;
          if (a->type == SPH_FIELD_DOUBLE) d[k] = ((const double *)src)[j];
          if (a->type == SPH_FIELD_INT64) l[k] = ((const int64_t *)src)[j];
          if (a->type == SPH_FIELD_UINT8) u[k] = ((const uint8_t *)src)[j];
        }
      }
      break;
    case SRC_POINTS:
      memcpy(d, a->pos, a->n * 3 * sizeof(double));
      break;
    case SRC_CONN:
      for (size_t i = 0; i < a->n; i++) l[i] = (int64_t)(a->conn ? a->conn[i] : i);
      break;
    case SRC_OFFSETS:
      for (size_t i = 0; i < a->n; i++) l[i] = (int64_t)((i + 1) * (size_t)a->per_cell);
      break;
    case SRC_TYPES:
      memset(u, a->cell_type, a->n);
      break;
  }
}

static int write_vtu(const char *path, size_t npoints, size_t ncells, const struct vtk_array *arr,
                     int narr) {
  FILE *f = fopen(path, "wb");
  if (!f) return -1;
  fprintf(f,
          "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
          "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n"
          "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n",
          npoints, ncells);
  static const char *const tags[] = {"PointData", "CellData", "Points", "Cells"};
  uint64_t offset = 0;
  for (int s = 0; s < 4; s++) {
    fprintf(f, "      <%s>\n", tags[s]);
    for (int i = 0; i < narr; i++) {
      if (arr[i].section != (enum vtk_section)s) continue;
      fprintf(f, "        <DataArray type=\"%s\"", vtk_type(arr[i].type));
      if (arr[i].name) fprintf(f, " Name=\"%s\"", arr[i].name);
      fprintf(f, " NumberOfComponents=\"%d\" format=\"appended\" offset=\"%llu\"/>\n", arr[i].ncomp,
              (unsigned long long)offset);
      offset += 8 + arr[i].n * (uint64_t)arr[i].ncomp * elem_size(arr[i].type);
    }
    fprintf(f, "      </%s>\n", tags[s]);
  }
  fprintf(f, "    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n_");
  for (int s = 0; s < 4; s++)
    for (int i = 0; i < narr; i++) {
      if (arr[i].section != (enum vtk_section)s) continue;
      uint64_t bytes = arr[i].n * (uint64_t)arr[i].ncomp * elem_size(arr[i].type);
      void *buf = cmn_malloc(bytes ? bytes : 1);
      fill(&arr[i], buf);
      fwrite(&bytes, sizeof bytes, 1, f); /* the file says LittleEndian: so is every target */
      fwrite(buf, 1, bytes, f);
      free(buf);
    }
  fprintf(f, "\n  </AppendedData>\n</VTKFile>\n");
  int bad = ferror(f);
  if (fclose(f) != 0 || bad) return -1;
  return 0;
}

/* Every field a kind carries, except positions (the points) and vertex indices (the cells). */
static int add_fields(struct vtk_array *arr, int narr, enum vtk_section sec,
                      const struct sph_parts *p, size_t n, const size_t *map) {
  int nf;
  const struct sph_field *fields = sph_parts_fields(&nf);
  for (int k = 0; k < nf; k++) {
    const struct sph_field *f = &fields[k];
    if (!sph_parts_field_data(p, f, 0) || f->type == SPH_FIELD_SIZE) continue;
    if (strcmp(f->name, "position") == 0) continue;
    arr[narr++] = (struct vtk_array){.section = sec,
                                     .name = f->name,
                                     .type = f->type,
                                     .ncomp = f->ncomp,
                                     .n = n,
                                     .src = SRC_FIELD,
                                     .p = p,
                                     .f = f,
                                     .map = map};
  }
  return narr;
}

static int write_fluid(const char *path, const struct sph_system *s) {
  const struct sph_parts *p = &s->part[SPH_KIND_FLUID];
  int nf;
  const struct sph_field *fields = sph_parts_fields(&nf), *pos = NULL;
  for (int k = 0; k < nf; k++)
    if (strcmp(fields[k].name, "position") == 0) pos = &fields[k];
  struct vtk_array arr[32];
  int narr = add_fields(arr, 0, SEC_POINTDATA, p, p->n, NULL);
  arr[narr++] = (struct vtk_array){.section = SEC_POINTS,
                                   .type = SPH_FIELD_DOUBLE,
                                   .ncomp = 3,
                                   .n = p->n,
                                   .src = SRC_FIELD,
                                   .p = p,
                                   .f = pos};
  arr[narr++] = (struct vtk_array){.section = SEC_CELLS,
                                   .name = "connectivity",
                                   .type = SPH_FIELD_INT64,
                                   .ncomp = 1,
                                   .n = p->n,
                                   .src = SRC_CONN};
  arr[narr++] = (struct vtk_array){.section = SEC_CELLS,
                                   .name = "offsets",
                                   .type = SPH_FIELD_INT64,
                                   .ncomp = 1,
                                   .n = p->n,
                                   .src = SRC_OFFSETS,
                                   .per_cell = 1};
  arr[narr++] = (struct vtk_array){.section = SEC_CELLS,
                                   .name = "types",
                                   .type = SPH_FIELD_UINT8,
                                   .ncomp = 1,
                                   .n = p->n,
                                   .src = SRC_TYPES,
                                   .cell_type = 1};
  return write_vtu(path, p->n, p->n, arr, narr);
}

/*
 * Boundary piece: vertex particles are the points, segments the cells. A segment that crosses a
 * periodic boundary uses copies of its far vertices at their minimum-image positions (one copy per
 * vertex and image), so that ParaView draws it where it is rather than across the domain.
 */
static int write_boundary(const char *path, const struct sph_system *s) {
  const struct sph_parts *pv = &s->part[SPH_KIND_VERTEX], *ps = &s->part[SPH_KIND_SEGMENT];
  int dim = s->dim;
  size_t cap = pv->n + 16, np = pv->n;
  double(*pos)[3] = cmn_malloc(cap * sizeof *pos);
  size_t *map = cmn_malloc(cap * sizeof *map);
  for (size_t i = 0; i < pv->n; i++) {
    map[i] = i;
    for (int a = 0; a < 3; a++) pos[i][a] = pv->x[a][i];
  }
  size_t *conn = cmn_malloc((ps->n * (size_t)dim + 1) * sizeof *conn);
  /* Images of a vertex, chained from first_image[vertex] through next_image[point]. */
  size_t *first_image = cmn_malloc((pv->n + 1) * sizeof *first_image);
  size_t *next_image = cmn_malloc(cap * sizeof *next_image);
  for (size_t i = 0; i < pv->n; i++) first_image[i] = SIZE_MAX;
  for (size_t j = 0; j < ps->n; j++) {
    double c[3] = {ps->x[0][j], ps->x[1][j], ps->x[2][j]}, v[3][3];
    sph_segment_vertices(s, j, c, v);
    for (int k = 0; k < dim; k++) {
      size_t iv = ps->vertex[k][j], at = iv;
      if (v[k][0] != pv->x[0][iv] || v[k][1] != pv->x[1][iv] || v[k][2] != pv->x[2][iv]) {
        at = first_image[iv];
        while (at != SIZE_MAX && memcmp(pos[at], v[k], sizeof pos[at]) != 0) at = next_image[at];
        if (at == SIZE_MAX) {
          if (np == cap) {
            cap *= 2;
            pos = cmn_realloc(pos, cap * sizeof *pos);
            map = cmn_realloc(map, cap * sizeof *map);
            next_image = cmn_realloc(next_image, cap * sizeof *next_image);
          }
          memcpy(pos[np], v[k], sizeof pos[np]);
          map[np] = iv;
          next_image[np] = first_image[iv];
          first_image[iv] = np;
          at = np++;
        }
      }
      conn[j * (size_t)dim + (size_t)k] = at;
    }
  }
  free(first_image);
  free(next_image);
  static const uint8_t cell_types[4] = {0, 1, 3, 5}; /* VTK_VERTEX, VTK_LINE, VTK_TRIANGLE */
  struct vtk_array arr[48];
  int narr = add_fields(arr, 0, SEC_POINTDATA, pv, np, map);
  narr = add_fields(arr, narr, SEC_CELLDATA, ps, ps->n, NULL);
  arr[narr++] = (struct vtk_array){.section = SEC_POINTS,
                                   .type = SPH_FIELD_DOUBLE,
                                   .ncomp = 3,
                                   .n = np,
                                   .src = SRC_POINTS,
                                   .pos = (const double(*)[3])pos};
  arr[narr++] = (struct vtk_array){.section = SEC_CELLS,
                                   .name = "connectivity",
                                   .type = SPH_FIELD_INT64,
                                   .ncomp = 1,
                                   .n = ps->n * (size_t)dim,
                                   .src = SRC_CONN,
                                   .conn = conn};
  arr[narr++] = (struct vtk_array){.section = SEC_CELLS,
                                   .name = "offsets",
                                   .type = SPH_FIELD_INT64,
                                   .ncomp = 1,
                                   .n = ps->n,
                                   .src = SRC_OFFSETS,
                                   .per_cell = dim};
  arr[narr++] = (struct vtk_array){.section = SEC_CELLS,
                                   .name = "types",
                                   .type = SPH_FIELD_UINT8,
                                   .ncomp = 1,
                                   .n = ps->n,
                                   .src = SRC_TYPES,
                                   .cell_type = cell_types[dim]};
  int rc = write_vtu(path, np, ps->n, arr, narr);
  free(pos);
  free(map);
  free(conn);
  return rc;
}

static char *dup_string(const char *s) {
  size_t n = strlen(s) + 1;
  return memcpy(cmn_malloc(n), s, n);
}

int sph_output_open(struct sph_output *o, const char *dir, const char *name) {
  memset(o, 0, sizeof *o);
  if (cmn_mkdir_p(dir) != 0) return -1;
  o->dir = dup_string(dir);
  o->name = dup_string(name);
  return 0;
}

static int write_pvd(const struct sph_output *o) {
  size_t len = strlen(o->dir) + strlen(o->name) + 16;
  char *path = cmn_malloc(len), *tmp = cmn_malloc(len + 4);
  snprintf(path, len, "%s/%s.pvd", o->dir, o->name);
  snprintf(tmp, len + 4, "%s.tmp", path);
  FILE *f = fopen(tmp, "w");
  int rc = -1;
  if (f) {
    fprintf(f,
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
            "byte_order=\"LittleEndian\">\n  <Collection>\n");
    for (int i = 0; i < o->count; i++)
      for (int part = 0; part < 2; part++)
        fprintf(f,
                "    <DataSet timestep=\"%.17g\" group=\"\" part=\"%d\" "
                "file=\"%s_%06d.vtu\"/>\n",
                o->times[i], part, part ? "boundary" : "fluid", i);
    fprintf(f, "  </Collection>\n</VTKFile>\n");
    int bad = ferror(f);
    rc = fclose(f) != 0 || bad ? -1 : rename(tmp, path);
  }
  free(path);
  free(tmp);
  return rc;
}

int sph_output_write(struct sph_output *o, const struct sph_system *s, double time) {
  size_t len = strlen(o->dir) + 32;
  char *path = cmn_malloc(len);
  snprintf(path, len, "%s/fluid_%06d.vtu", o->dir, o->count);
  int rc = write_fluid(path, s);
  snprintf(path, len, "%s/boundary_%06d.vtu", o->dir, o->count);
  if (rc == 0) rc = write_boundary(path, s);
  free(path);
  if (rc) return -1;
  if (o->count == o->cap) {
    o->cap = o->cap ? 2 * o->cap : 16;
    o->times = cmn_realloc(o->times, (size_t)o->cap * sizeof *o->times);
  }
  o->times[o->count++] = time;
  return write_pvd(o);
}

void sph_output_close(struct sph_output *o) {
  free(o->dir);
  free(o->name);
  free(o->times);
  memset(o, 0, sizeof *o);
}
