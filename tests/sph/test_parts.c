/* Particle store: append with fresh ids, removal keeps order and every field, permutation moves
 * every field, kinds carry exactly their fields. */
#include <stdlib.h>

#include "sabre/sph.h"
#include "testutil.h"

/* Fill every double field of particle i with a value derived from its id, so a field that a
 * store operation forgot to move shows up as a mismatch. */
static void stamp(struct sph_parts *p, size_t i) {
  int nf;
  const struct sph_field *f = sph_parts_fields(&nf);
  for (int k = 0; k < nf; k++)
    for (int c = 0; c < f[k].ncomp; c++) {
      void *d = sph_parts_field_data(p, &f[k], c);
      if (!d || f[k].type != SPH_FIELD_DOUBLE) continue;
      ((double *)d)[i] = 1000.0 * (double)p->id[i] + 10.0 * k + c + 0.125;
    }
  p->flags[i] = (uint8_t)(p->id[i] % 3);
  if (p->vertex[0]) p->vertex[2][i] = (size_t)p->id[i] + 7;
}

static void check_stamp(const struct sph_parts *p, size_t i) {
  int nf;
  const struct sph_field *f = sph_parts_fields(&nf);
  for (int k = 0; k < nf; k++)
    for (int c = 0; c < f[k].ncomp; c++) {
      void *d = sph_parts_field_data(p, &f[k], c);
      if (!d || f[k].type != SPH_FIELD_DOUBLE) continue;
      assert_true(((double *)d)[i] == 1000.0 * (double)p->id[i] + 10.0 * k + c + 0.125);
    }
  assert_int_equal(p->flags[i], p->id[i] % 3);
  if (p->vertex[0]) assert_int_equal(p->vertex[2][i], (size_t)p->id[i] + 7);
}

static void test_parts_store(void **state) {
  (void)state;
  struct sph_system s;
  sph_system_init(&s, 3);
  /* Grow past the initial capacity several times, interleaving kinds. */
  for (int round = 0; round < 5; round++) {
    for (int k = 0; k < SPH_NKINDS; k++) {
      size_t first = sph_system_append(&s, (enum sph_kind)k, 37 + 11 * (size_t)round);
      for (size_t i = first; i < s.part[k].n; i++) stamp(&s.part[k], i);
    }
  }
  /* Ids unique over all kinds. */
  size_t total = 0;
  for (int k = 0; k < SPH_NKINDS; k++) total += s.part[k].n;
  assert_int_equal(total, (size_t)s.next_id);
  char *seen = calloc(total, 1);
  for (int k = 0; k < SPH_NKINDS; k++)
    for (size_t i = 0; i < s.part[k].n; i++) {
      assert_false(seen[s.part[k].id[i]]);
      seen[s.part[k].id[i]] = 1;
    }
  free(seen);
  /* Kinds carry their fields only. */
  assert_null(s.part[SPH_KIND_FLUID].normal[0]);
  assert_null(s.part[SPH_KIND_FLUID].vertex[0]);
  assert_null(s.part[SPH_KIND_SEGMENT].gamma);
  assert_non_null(s.part[SPH_KIND_VERTEX].mass);

  /* Remove every third fluid particle: order kept, fields follow. */
  struct sph_parts *f = &s.part[SPH_KIND_FLUID];
  size_t n0 = f->n;
  uint8_t *rm = calloc(n0, 1);
  for (size_t i = 0; i < n0; i += 3) rm[i] = 1;
  size_t removed = sph_parts_remove(f, rm);
  assert_int_equal(removed, (n0 + 2) / 3);
  assert_int_equal(f->n, n0 - removed);
  for (size_t i = 0; i < f->n; i++) {
    check_stamp(f, i);
    if (i) assert_true(f->id[i] > f->id[i - 1]);
  }
  free(rm);

  /* Reverse the segments. */
  struct sph_parts *sg = &s.part[SPH_KIND_SEGMENT];
  size_t *order = malloc(sg->n * sizeof *order);
  int64_t *ids = malloc(sg->n * sizeof *ids);
  for (size_t i = 0; i < sg->n; i++) {
    order[i] = sg->n - 1 - i;
    ids[i] = sg->id[i];
  }
  sph_parts_permute(sg, order);
  for (size_t i = 0; i < sg->n; i++) {
    assert_int_equal(sg->id[i], ids[sg->n - 1 - i]);
    check_stamp(sg, i);
  }
  free(order);
  free(ids);

  /* New particles after removals still get fresh ids, and zeroed fields. */
  size_t first = sph_system_append(&s, SPH_KIND_FLUID, 5);
  assert_int_equal(f->id[first], (int64_t)total);
  assert_true(f->x[1][first + 4] == 0.0 && f->gamma[first + 4] == 0.0);
  sph_system_free(&s);
}

int main(void) {
  sabre_fp_traps_on();
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_parts_store)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
