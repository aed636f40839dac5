/* VTK XML output: the appended binary arrays read back equal the store's fields bit for bit
 * (every field of the field table is present), cells reference the right vertices, segments across
 * a periodic boundary are drawn with an image of their far vertex (one per vertex), and the .pvd
 * lists every output time with both pieces. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sabre/common.h"
#include "sabre/sph.h"
#include "testutil.h"
/* testutil.h first */
#include "sph_testfiles.h"

static void *copies[32];
static size_t ncopies;

struct vtu {
  char *buf;
  size_t len;
  const char *appended; /* first byte after '_' */
};

static void vtu_read(struct vtu *v, const char *name) {
  FILE *f = fopen(test_path(name), "rb");
  assert_non_null(f);
  fseek(f, 0, SEEK_END);
  v->len = (size_t)ftell(f);
  fseek(f, 0, SEEK_SET);
  v->buf = malloc(v->len + 1);
  assert_int_equal(fread(v->buf, 1, v->len, f), v->len);
  v->buf[v->len] = '\0';
  fclose(f);
  const char *a = strstr(v->buf, "<AppendedData encoding=\"raw\">");
  assert_non_null(a);
  v->appended = strchr(a, '_') + 1;
}

/* Data of the array named `name` in section `sec` (NULL name: the Points array); byte count in
 * *bytes. */
static const void *vtu_array(const struct vtu *v, const char *sec, const char *name,
                             size_t *bytes) {
  char open_tag[64], close_tag[64], key[128];
  snprintf(open_tag, sizeof open_tag, "<%s>", sec);
  snprintf(close_tag, sizeof close_tag, "</%s>", sec);
  const char *s = strstr(v->buf, open_tag), *e = strstr(v->buf, close_tag);
  assert_non_null(s);
  const char *at = s;
  if (name) {
    snprintf(key, sizeof key, "Name=\"%s\"", name);
    at = strstr(s, key);
  } else {
    at = strstr(s, "<DataArray");
  }
  assert_non_null(at);
  assert_true(at < e);
  const char *off = strstr(at, "offset=\"");
  unsigned long long offset = strtoull(off + 8, NULL, 10);
  uint64_t n;
  memcpy(&n, v->appended + offset, sizeof n);
  *bytes = (size_t)n;
  /* The appended data are not aligned: hand out an aligned copy (freed by free_copies()). */
  assert_true(ncopies < sizeof copies / sizeof copies[0]);
  copies[ncopies] = malloc(n + 8);
  memcpy(copies[ncopies], v->appended + offset + 8, n);
  return copies[ncopies++];
}

static void free_copies(void) {
  while (ncopies > 0) free(copies[--ncopies]);
}

static void test_roundtrip(void **state) {
  (void)state;
  /* A 2D channel periodic in x: bottom wall of 5 segments, fluid with stamped fields. */
  struct sph_system s;
  sph_system_init(&s, 2);
  s.domain.lo[0] = 0;
  s.domain.hi[0] = 1;
  s.domain.hi[1] = 1;
  s.domain.periodic[0] = 1;
  struct sph_mesh m;
  sph_mesh_init(&m, 2);
  size_t v[5];
  int src = sph_mesh_add_source(&m, "floor");
  for (int i = 0; i < 5; i++) v[i] = sph_mesh_add_vertex(&m, (double[]){0.2 * i, 0, 0});
  for (int i = 0; i < 5; i++)
    sph_mesh_add_element(&m, (size_t[]){v[i], v[(i + 1) % 5], 0}, 0, i == 2 ? SPH_FLAG_OPEN : 0,
                         src, i + 1);
  sph_system_add_walls(&s, &m);
  sph_mesh_free(&m);
  size_t f0 = sph_system_append(&s, SPH_KIND_FLUID, 7);
  struct sph_parts *pf = &s.part[SPH_KIND_FLUID];
  for (size_t i = f0; i < pf->n; i++) {
    pf->x[0][i] = 0.1 + 0.137 * (double)i;
    pf->x[1][i] = 0.3 / (double)(i + 1);
    pf->v[1][i] = -2.5e-3 * (double)i;
    pf->gamma[i] = 1.0 - 0.01 * (double)i;
    pf->grad_gamma[1][i] = 1.0 / 3.0;
    pf->mass[i] = 0.1 + (double)i;
  }
  struct sph_output out;
  assert_int_equal(sph_output_open(&out, test_dir, "series"), 0);
  assert_int_equal(sph_output_write(&out, &s, 0.0), 0);
  pf->x[0][0] = 0.999;
  assert_int_equal(sph_output_write(&out, &s, 0.125), 0);
  sph_output_close(&out);

  struct vtu f;
  vtu_read(&f, "fluid_000001.vtu");
  assert_non_null(strstr(f.buf, "NumberOfPoints=\"7\" NumberOfCells=\"7\""));
  size_t bytes;
  const double *x = vtu_array(&f, "Points", NULL, &bytes);
  assert_int_equal(bytes, 7 * 3 * sizeof(double));
  for (size_t i = 0; i < 7; i++)
    for (int a = 0; a < 3; a++) assert_true(x[3 * i + (size_t)a] == pf->x[a][i]);
  const double *g = vtu_array(&f, "PointData", "gamma", &bytes);
  assert_int_equal(bytes, 7 * sizeof(double));
  assert_memory_equal(g, pf->gamma, bytes);
  const double *gg = vtu_array(&f, "PointData", "grad_gamma", &bytes);
  for (size_t i = 0; i < 7; i++) assert_true(gg[3 * i + 1] == 1.0 / 3.0);
  const double *vel = vtu_array(&f, "PointData", "velocity", &bytes);
  for (size_t i = 0; i < 7; i++) assert_true(vel[3 * i + 1] == pf->v[1][i]);
  const int64_t *id = vtu_array(&f, "PointData", "id", &bytes);
  for (size_t i = 0; i < 7; i++) assert_int_equal(id[i], pf->id[i]);
  /* Every field the kind carries is written (positions as Points). */
  int nf;
  const struct sph_field *fields = sph_parts_fields(&nf);
  for (int k = 0; k < nf; k++) {
    if (!sph_parts_field_data(pf, &fields[k], 0) || fields[k].type == SPH_FIELD_SIZE ||
        strcmp(fields[k].name, "position") == 0)
      continue;
    char key[64];
    snprintf(key, sizeof key, "Name=\"%s\"", fields[k].name);
    assert_non_null(strstr(f.buf, key));
  }
  free(f.buf);

  /* Boundary: 5 vertices + 1 image of vertex 0 at x = 1 for the segment crossing x = 1. */
  struct vtu b;
  vtu_read(&b, "boundary_000000.vtu");
  assert_non_null(strstr(b.buf, "NumberOfPoints=\"6\" NumberOfCells=\"5\""));
  const double *p = vtu_array(&b, "Points", NULL, &bytes);
  assert_true(p[3 * 5] == 1.0);
  const int64_t *conn = vtu_array(&b, "Cells", "connectivity", &bytes);
  assert_int_equal(bytes, 10 * sizeof(int64_t));
  for (int j = 0; j < 5; j++) {
    double len = p[3 * conn[2 * j + 1]] - p[3 * conn[2 * j]];
    assert_rel(len, 0.2, 1e-12); /* every segment drawn where it is */
  }
  const int64_t *vid = vtu_array(&b, "PointData", "id", &bytes);
  assert_int_equal(vid[5], vid[0]); /* the image carries its vertex's data */
  const uint8_t *flags = vtu_array(&b, "CellData", "flags", &bytes);
  assert_int_equal(bytes, 5);
  assert_int_equal(flags[2], SPH_FLAG_OPEN);
  const uint8_t *types = vtu_array(&b, "Cells", "types", &bytes);
  assert_int_equal(types[4], 3); /* VTK_LINE */
  free(b.buf);

  char text[2048];
  test_read("series.pvd", text, sizeof text);
  assert_non_null(
      strstr(text, "timestep=\"0.125\" group=\"\" part=\"1\" file=\"boundary_000001.vtu\""));
  assert_non_null(strstr(text, "timestep=\"0\" group=\"\" part=\"0\" file=\"fluid_000000.vtu\""));
  free_copies();
  sph_system_free(&s);
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_roundtrip)};
  return cmocka_run_group_tests(tests, test_dir_setup, test_dir_teardown);
}
