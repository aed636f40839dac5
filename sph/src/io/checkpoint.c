/*
 * Checkpoints: the whole particle store through its field table (so a field added to the store is
 * saved without touching this file), the run's time, step, last Δt and output counters, and the
 * imposed-flux controller's history (M 62–63 depend on the last two measured velocities) and the
 * open boundaries' counts of created and deleted particles and their released mass, and the
 * fitted wall layer's thickness (the set-up, which a restart does not repeat, fitted it). Raw
 * native-endian binary: a checkpoint restarts a run on the machine that wrote it, bit-identically
 * for the same thread count (the step depends only on this state).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph_solver.h"

static const char magic[16] = "SABRE-SPH-CKPTB"; /* versions 1-9, A, B (vertex volume, wall mass) */

void sph_run_counters_digest(struct sph_run_counters *rc, const struct cmn_case *c) {
  rc->ndigest = 0;
  for (int i = 0; i < cmn_case_top_count(c) && rc->ndigest < SPH_MAX_DIGESTS; i++) {
    const char *name = cmn_case_top_key(c, i);
    /* `time` only says how far and how often: a restart may change it (a later time.end) */
    if (strcmp(name, "time") == 0) continue;
    snprintf(rc->digest_name[rc->ndigest], sizeof rc->digest_name[0], "%s", name);
    rc->digest[rc->ndigest++] = cmn_case_digest(c, name);
  }
}

#define W(ptr, size, count)                                                      \
  do {                                                                           \
    if ((count) > 0 && fwrite((ptr), (size), (count), fp) != (count)) goto fail; \
  } while (0)

int sph_checkpoint_write(const struct sph_solver *sv, const struct sph_run_counters *rc,
                         const char *path) {
  size_t len = strlen(path) + 8;
  char *tmp = cmn_malloc(len);
  snprintf(tmp, len, "%s.tmp", path);
  FILE *fp = fopen(tmp, "wb");
  if (!fp) {
    free(tmp);
    return -1;
  }
  const struct sph_system *s = &sv->sys;
  int32_t dim = s->dim;
  uint64_t nout = (uint64_t)rc->outputs;
  W(magic, 1, sizeof magic);
  int32_t nd = rc->ndigest;
  W(&nd, sizeof nd, 1);
  for (int i = 0; i < rc->ndigest; i++) {
    W(rc->digest_name[i], 1, sizeof rc->digest_name[i]);
    W(&rc->digest[i], sizeof rc->digest[i], 1);
  }
  W(&dim, sizeof dim, 1);
  W(&s->dr, sizeof(double), 1);
  W(&s->h, sizeof(double), 1);
  /* the domain member by member: no struct padding in the file */
  int32_t ddim = s->domain.dim,
          per[3] = {s->domain.periodic[0], s->domain.periodic[1], s->domain.periodic[2]};
  W(&ddim, sizeof ddim, 1);
  W(s->domain.lo, sizeof(double), 3);
  W(s->domain.hi, sizeof(double), 3);
  W(per, sizeof per[0], 3);
  W(&s->next_id, sizeof s->next_id, 1);
  W(&sv->time, sizeof(double), 1);
  W(&sv->step, sizeof(long), 1);
  W(&sv->dt, sizeof(double), 1);
  W(&sv->vertex_phi, sizeof(double), 1); /* the set-up's (fitted after the repacking) */
  W(&rc->next_output, sizeof(double), 1);
  W(&nout, sizeof nout, 1);
  W(rc->output_times, sizeof(double), (size_t)nout);
  /* imposed-flux controller, member by member */
  const struct sph_flux_ctrl *fc = &sv->flux_ctrl;
  int32_t fmethod = (int32_t)fc->method;
  int64_t fsteps = fc->steps;
  W(&fmethod, sizeof fmethod, 1);
  W(&fc->v_target, sizeof(double), 1);
  W(&fc->vt1, sizeof(double), 1);
  W(&fc->vt2, sizeof(double), 1);
  W(&fc->dt1, sizeof(double), 1);
  W(&fc->force, sizeof(double), 1);
  W(&fsteps, sizeof fsteps, 1);
  W(&sv->flux_v, sizeof(double), 1);
  W(&sv->flux_force, sizeof(double), 1);
  /* open boundaries: particles created and deleted per group since the run began */
  int64_t ocount[2][SPH_MAX_OPEN_GROUPS] = {{0}};
  for (int g = 0; sv->open && g < sv->open->ngroups; g++) {
    ocount[0][g] = sv->open->created[g];
    ocount[1][g] = sv->open->deleted[g];
  }
  W(ocount, sizeof ocount[0][0], 2 * SPH_MAX_OPEN_GROUPS);
  double omass[6][SPH_MAX_OPEN_GROUPS] = {{0.0}};
  for (int g = 0; sv->open && g < sv->open->ngroups; g++) {
    omass[0][g] = sv->open->mass_entered[g];
    omass[1][g] = sv->open->mass_released[g];
    omass[2][g] = sv->open->mass_withheld[g];
    for (int k = 0; k < 3; k++) omass[3 + k][g] = sv->open->mass_comp[k][g];
  }
  W(omass, sizeof omass[0][0], 6 * SPH_MAX_OPEN_GROUPS);
  int nf;
  const struct sph_field *fields = sph_parts_fields(&nf);
  for (int k = 0; k < SPH_NKINDS; k++) {
    const struct sph_parts *p = &s->part[k];
    uint64_t n = p->n;
    W(&n, sizeof n, 1);
    for (int i = 0; i < nf; i++)
      for (int c = 0; c < fields[i].ncomp; c++) {
        const void *data = sph_parts_field_data(p, &fields[i], c);
        if (data) W(data, sph_field_type_size(fields[i].type), (size_t)n);
      }
  }
  if (fclose(fp) != 0) {
    fp = NULL;
    goto fail;
  }
  if (rename(tmp, path) != 0) {
    int e = errno;
    remove(tmp);
    free(tmp);
    errno = e;
    return -1;
  }
  free(tmp);
  return 0;
fail : {
  int e = errno;
  if (fp) fclose(fp);
  remove(tmp);
  free(tmp);
  errno = e ? e : EIO;
  return -1;
}
}
#undef W

#define R(ptr, size, count)                                                           \
  do {                                                                                \
    if ((count) > 0 && fread((ptr), (size), (count), fp) != (count)) goto short_read; \
  } while (0)

int sph_checkpoint_read(struct sph_solver *sv, struct sph_run_counters *rc, const char *path,
                        char *msg, size_t msglen) {
  FILE *fp = fopen(path, "rb");
  if (!fp) {
    snprintf(msg, msglen, "%s: cannot open: %s", path, strerror(errno));
    return -1;
  }
  struct sph_system *s = &sv->sys;
  char m[16];
  int32_t dim;
  uint64_t nout;
  double dr, h;
  struct sph_domain dom;
  R(m, 1, sizeof m);
  if (memcmp(m, magic, sizeof m) != 0) {
    snprintf(msg, msglen,
             memcmp(m, magic, 14) == 0
                 ? "%s: a checkpoint of another version of sabre-sph: restart with that version"
                 : "%s: not a SABRE SPH checkpoint (bad magic)",
             path);
    fclose(fp);
    return -1;
  }
  {
    int32_t nd;
    char name[32];
    unsigned long long d;
    R(&nd, sizeof nd, 1);
    if (nd < 0 || nd > SPH_MAX_DIGESTS) goto short_read;
    int seen[SPH_MAX_DIGESTS] = {0};
    for (int i = 0; i < nd; i++) {
      R(name, 1, sizeof name);
      R(&d, sizeof d, 1);
      name[sizeof name - 1] = '\0';
      if (rc->ndigest == 0) continue; /* no case to compare with (library use) */
      int j = 0;
      while (j < rc->ndigest && strcmp(rc->digest_name[j], name) != 0) j++;
      const char *what = j == rc->ndigest     ? "is absent from this case"
                         : rc->digest[j] != d ? "differs in this case"
                                              : NULL;
      if (j < rc->ndigest) seen[j] = 1;
      if (what) {
        snprintf(msg, msglen,
                 "%s: section '%s' of the run that wrote this checkpoint %s: a restart must use "
                 "the same case and --set options (only the time section may change); start a "
                 "new run without --restart to use the new parameters",
                 path, name, what);
        fclose(fp);
        return -1;
      }
    }
    for (int j = 0; j < rc->ndigest && nd > 0; j++)
      if (!seen[j]) {
        snprintf(msg, msglen,
                 "%s: section '%s' of this case was not in the run that wrote this checkpoint: a "
                 "restart must use the same case and --set options (only the time section may "
                 "change); start a new run without --restart to use the new parameters",
                 path, rc->digest_name[j]);
        fclose(fp);
        return -1;
      }
  }
  R(&dim, sizeof dim, 1);
  R(&dr, sizeof dr, 1);
  R(&h, sizeof h, 1);
  int32_t ddim, per[3];
  memset(&dom, 0, sizeof dom);
  R(&ddim, sizeof ddim, 1);
  R(dom.lo, sizeof(double), 3);
  R(dom.hi, sizeof(double), 3);
  R(per, sizeof per[0], 3);
  dom.dim = ddim;
  for (int i = 0; i < 3; i++) dom.periodic[i] = per[i];
  if (dim != s->dim || dr != s->dr || h != s->h) {
    snprintf(msg, msglen,
             "%s: written for dimension %d, dr = %g m, h = %g m; the case has %d, %g m, %g m", path,
             (int)dim, dr, h, s->dim, s->dr, s->h);
    fclose(fp);
    return -1;
  }
  s->domain = dom;
  R(&s->next_id, sizeof s->next_id, 1);
  R(&sv->time, sizeof(double), 1);
  R(&sv->step, sizeof(long), 1);
  R(&sv->dt, sizeof(double), 1);
  R(&sv->vertex_phi, sizeof(double), 1);
  R(&rc->next_output, sizeof(double), 1);
  R(&nout, sizeof nout, 1);
  if (nout > 100000000u) goto short_read;
  free(rc->output_times);
  rc->output_times = cmn_malloc((size_t)(nout + 1) * sizeof(double));
  rc->outputs = (long)nout;
  R(rc->output_times, sizeof(double), (size_t)nout);
  {
    struct sph_flux_ctrl *fc = &sv->flux_ctrl;
    int32_t fmethod;
    int64_t fsteps;
    R(&fmethod, sizeof fmethod, 1);
    R(&fc->v_target, sizeof(double), 1);
    R(&fc->vt1, sizeof(double), 1);
    R(&fc->vt2, sizeof(double), 1);
    R(&fc->dt1, sizeof(double), 1);
    R(&fc->force, sizeof(double), 1);
    R(&fsteps, sizeof fsteps, 1);
    R(&sv->flux_v, sizeof(double), 1);
    R(&sv->flux_force, sizeof(double), 1);
    fc->method = (enum sph_flux_method)fmethod;
    fc->steps = (long)fsteps;
  }
  {
    int64_t ocount[2][SPH_MAX_OPEN_GROUPS];
    R(ocount, sizeof ocount[0][0], 2 * SPH_MAX_OPEN_GROUPS);
    double omass[6][SPH_MAX_OPEN_GROUPS];
    R(omass, sizeof omass[0][0], 6 * SPH_MAX_OPEN_GROUPS);
    for (int g = 0; sv->open && g < sv->open->ngroups; g++) {
      sv->open->created[g] = (long)ocount[0][g];
      sv->open->deleted[g] = (long)ocount[1][g];
      sv->open->mass_entered[g] = omass[0][g];
      sv->open->mass_released[g] = omass[1][g];
      sv->open->mass_withheld[g] = omass[2][g];
      for (int k = 0; k < 3; k++) sv->open->mass_comp[k][g] = omass[3 + k][g];
    }
  }
  int nf;
  const struct sph_field *fields = sph_parts_fields(&nf);
  for (int k = 0; k < SPH_NKINDS; k++) {
    struct sph_parts *p = &s->part[k];
    uint64_t n;
    R(&n, sizeof n, 1);
    if (k != SPH_KIND_FLUID && n != p->n) {
      snprintf(msg, msglen, "%s: %llu %s particles, the case has %zu: not this case's checkpoint",
               path, (unsigned long long)n, k == SPH_KIND_VERTEX ? "vertex" : "segment", p->n);
      fclose(fp);
      return -1;
    }
    if (n > ((uint64_t)1 << 40)) goto short_read;
    sph_parts_reserve(p, (size_t)n);
    p->n = (size_t)n;
    for (int i = 0; i < nf; i++)
      for (int c = 0; c < fields[i].ncomp; c++) {
        void *data = sph_parts_field_data(p, &fields[i], c);
        if (data) R(data, sph_field_type_size(fields[i].type), (size_t)n);
      }
  }
  fclose(fp);
  sph_solver_sync(sv);
  return 0;
short_read:
  snprintf(msg, msglen, "%s: truncated or corrupt checkpoint", path);
  fclose(fp);
  return -1;
}
