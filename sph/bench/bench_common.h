/* Shared by the solver benchmarks (bench_sph.c, bench_dambreak.c): a solver set up from an inline
 * case and the OpenMP thread count. Header-only: each benchmark is one program. */
#ifndef SABRE_SPH_BENCH_COMMON_H
#define SABRE_SPH_BENCH_COMMON_H

#include "sabre/common.h"
#include "sabre/sph.h"
#include "sabre/sph_solver.h"
#ifdef _OPENMP
#include <omp.h>
#endif

static inline void bench_set_threads(int n) {
#ifdef _OPENMP
  omp_set_num_threads(n);
#else
  (void)n;
#endif
}

/* The solver of a case given as YAML text, its force and open-boundary groups resolved against
 * the mesh as `sabre-sph run` does; name is the case file's path (file names in the case are
 * relative to its directory). Stops the program on a bad case. Free with sph_solver_free() and
 * free(). */
static inline struct sph_solver *bench_solver(const char *yaml, const char *name) {
  char err[1024];
  struct cmn_case *c = cmn_case_parse(yaml, name, err, sizeof err);
  if (!c) cmn_error("%s", err);
  struct sph_geometry g;
  sph_geometry_read(&g, c);
  struct sph_config cfg;
  sph_config_read(&cfg, c, g.dim);
  sph_open_check_mesh(&cfg.open, c, &g.walls);
  cmn_case_check_unused(c);
  struct sph_system s;
  sph_system_from_geometry(&s, &g);
  struct sph_solver *sv = cmn_calloc(1, sizeof *sv);
  /* segment j is mesh element j: the mesh's own wall index and element number of each */
  sph_solver_init(sv, &cfg, &s, g.walls.source, g.walls.source_index);
  sph_system_free(&s);
  sph_geometry_free(&g);
  cmn_case_free(c);
  return sv;
}

#endif
