/* Particle store: one structure of arrays per kind, driven by a field table so that resizing,
 * removal, permutation and output never forget a field. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph.h"

#define F (1u << SPH_KIND_FLUID)
#define V (1u << SPH_KIND_VERTEX)
#define S (1u << SPH_KIND_SEGMENT)
#define FIELD(nm, type, ncomp, member, kinds) \
  { nm, type, ncomp, offsetof(struct sph_parts, member), kinds }

static const struct sph_field fields[] = {
    FIELD("id", SPH_FIELD_INT64, 1, id, F | V | S),
    FIELD("flags", SPH_FIELD_UINT8, 1, flags, F | V | S),
    FIELD("position", SPH_FIELD_DOUBLE, 3, x, F | V | S),
    FIELD("velocity", SPH_FIELD_DOUBLE, 3, v, F | V | S),
    FIELD("mass", SPH_FIELD_DOUBLE, 1, mass, F | V),
    FIELD("density", SPH_FIELD_DOUBLE, 1, rho, F | V | S),
    FIELD("pressure", SPH_FIELD_DOUBLE, 1, p, F | V | S),
    FIELD("gamma", SPH_FIELD_DOUBLE, 1, gamma, F | V),
    FIELD("grad_gamma", SPH_FIELD_DOUBLE, 3, grad_gamma, F | V),
    FIELD("normal", SPH_FIELD_DOUBLE, 3, normal, V | S),
    FIELD("measure", SPH_FIELD_DOUBLE, 1, measure, S),
    FIELD("volume", SPH_FIELD_DOUBLE, 1, volume, V),
    FIELD("wall_mass", SPH_FIELD_DOUBLE, 1, wall_mass, V),
    FIELD("vertex", SPH_FIELD_SIZE, 3, vertex, S),
};
#undef FIELD
#undef F
#undef V
#undef S

enum { NFIELDS = sizeof fields / sizeof fields[0] };

const struct sph_field *sph_parts_fields(int *n) {
  *n = NFIELDS;
  return fields;
}

size_t sph_field_type_size(enum sph_field_type type) {
  switch (type) {
    case SPH_FIELD_DOUBLE:
      return sizeof(double);
    case SPH_FIELD_INT64:
      return sizeof(int64_t);
    case SPH_FIELD_UINT8:
      return sizeof(uint8_t);
    case SPH_FIELD_SIZE:
      return sizeof(size_t);
  }
  return 0;
}

/* Address of the pointer to component c of field f (all component pointers of one field are
 * consecutive members of struct sph_parts, all of the same pointer type). */
static void **field_slot(const struct sph_parts *p, const struct sph_field *f, int c) {
  return (void **)((char *)p + f->offset) + c;
}

static int carries(const struct sph_parts *p, const struct sph_field *f) {
  return (f->kinds >> p->kind) & 1u;
}

void *sph_parts_field_data(const struct sph_parts *p, const struct sph_field *f, int c) {
  return carries(p, f) ? *field_slot(p, f, c) : NULL;
}

void sph_parts_init(struct sph_parts *p, enum sph_kind kind) {
  memset(p, 0, sizeof *p);
  p->kind = kind;
}

void sph_parts_free(struct sph_parts *p) {
  for (int i = 0; i < NFIELDS; i++)
    for (int c = 0; c < fields[i].ncomp; c++) free(*field_slot(p, &fields[i], c));
  sph_parts_init(p, p->kind);
}

void sph_parts_reserve(struct sph_parts *p, size_t capacity) {
  if (capacity <= p->capacity) return;
  size_t cap = p->capacity ? p->capacity : 64;
  while (cap < capacity) cap += cap / 2;
  for (int i = 0; i < NFIELDS; i++) {
    if (!carries(p, &fields[i])) continue;
    size_t sz = sph_field_type_size(fields[i].type);
    for (int c = 0; c < fields[i].ncomp; c++) {
      void **slot = field_slot(p, &fields[i], c);
      *slot = cmn_realloc(*slot, cap * sz);
    }
  }
  p->capacity = cap;
}

size_t sph_parts_append(struct sph_parts *p, size_t count) {
  size_t first = p->n;
  if (count == 0) return first;
  sph_parts_reserve(p, p->n + count);
  for (int i = 0; i < NFIELDS; i++) {
    if (!carries(p, &fields[i])) continue;
    size_t sz = sph_field_type_size(fields[i].type);
    for (int c = 0; c < fields[i].ncomp; c++)
      memset((char *)*field_slot(p, &fields[i], c) + first * sz, 0, count * sz);
  }
  p->n += count;
  return first;
}

size_t sph_parts_remove(struct sph_parts *p, const uint8_t *remove) {
  size_t kept = 0;
  for (size_t i = 0; i < p->n; i++) {
    if (remove[i]) continue;
    if (kept != i) {
      for (int f = 0; f < NFIELDS; f++) {
        if (!carries(p, &fields[f])) continue;
        size_t sz = sph_field_type_size(fields[f].type);
        for (int c = 0; c < fields[f].ncomp; c++) {
          char *a = *field_slot(p, &fields[f], c);
          memcpy(a + kept * sz, a + i * sz, sz);
        }
      }
    }
    kept++;
  }
  size_t removed = p->n - kept;
  p->n = kept;
  return removed;
}

void sph_parts_permute(struct sph_parts *p, const size_t *order) {
  if (p->n == 0) return;
  size_t maxsz = sizeof(double) > sizeof(size_t) ? sizeof(double) : sizeof(size_t);
  char *tmp = cmn_malloc(p->n * maxsz);
  for (int f = 0; f < NFIELDS; f++) {
    if (!carries(p, &fields[f])) continue;
    size_t sz = sph_field_type_size(fields[f].type);
    for (int c = 0; c < fields[f].ncomp; c++) {
      char *a = *field_slot(p, &fields[f], c);
      for (size_t i = 0; i < p->n; i++) memcpy(tmp + i * sz, a + order[i] * sz, sz);
      memcpy(a, tmp, p->n * sz);
    }
  }
  free(tmp);
}

void sph_system_init(struct sph_system *s, int dim) {
  memset(s, 0, sizeof *s);
  s->dim = dim;
  s->domain.dim = dim;
  for (int k = 0; k < SPH_NKINDS; k++) sph_parts_init(&s->part[k], (enum sph_kind)k);
}

void sph_system_free(struct sph_system *s) {
  for (int k = 0; k < SPH_NKINDS; k++) sph_parts_free(&s->part[k]);
}

size_t sph_system_append(struct sph_system *s, enum sph_kind kind, size_t count) {
  struct sph_parts *p = &s->part[kind];
  size_t first = sph_parts_append(p, count);
  for (size_t i = first; i < p->n; i++) p->id[i] = s->next_id++;
  return first;
}
