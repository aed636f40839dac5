/* The subcommands of sabre-sph that inspect a geometry (`gamma`, `mesh`); see sph/main.c and
 * docs/sph-geometry.md §6. argv[0] is the command's name; bad input exits with CMN_EXIT_INPUT. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"
#include "sabre/sph.h"
#include "sabre/sph_solver.h"
#include "sabre/sph_walls.h"

void sph_cmd_usage(FILE *out) {
  fprintf(
      out,
      "usage: sabre-sph <command> [options]     (sabre-sph <command> --help for one command)\n"
      "       sabre-sph --version\n"
      "\n"
      "commands:\n"
      "  run CASE.yaml [--output DIR] [--set key=value ...] [--restart FILE] [--threads N]\n"
      "      Run the simulation of a case (sabre-sph run --help for details). One thread unless\n"
      "      --threads N (or OMP_NUM_THREADS) asks for more.\n"
      "  gamma --dim D --dr DR --h-over-dr K [--box LO:HI] [--stl FILE [--stl-fluid inside|"
      "outside]]\n"
      "        --at X[,Y[,Z]] [--at ...]\n"
      "      Print {\"at\": [...], \"gamma\": g, \"grad_gamma\": [...]} (one line per point) for\n"
      "      walls meshed at spacing DR: the closed box with corners LO and HI (comma-separated,\n"
      "      fluid inside), and/or the STL surface (3D; fluid inside it by default, outside it\n"
      "      when a box is given too). h = K * DR.\n"
      "  mesh CASE.yaml --output DIR [--set key=value ...]\n"
      "      Mesh the walls and fill the fluid of the case's geometry section, compute gamma,\n"
      "      and write DIR/mesh.pvd (fluid and boundary VTU files) and DIR/used_case.yaml.\n"
      "  scalar CASE.yaml [--output DIR] [--set key=value ...]\n"
      "      Solve u_tt = c^2 Lap u on fixed particles with Robin/Neumann/Dirichlet walls\n"
      "      (docs/sph-scalar.md).\n"
      "  stability CASE.yaml [--output DIR] [--set key=value ...] [--modes N] [--eps E]\n"
      "      The linearised dynamics of a closed case's fluid about its start: the growth rates\n"
      "      of its modes (static instabilities, flutter) and where each lives (sabre-sph\n"
      "      stability --help; docs/sph-solver.md section 7.1).\n"
      "  wave stokes5 --depth D --height H (--length L | --period T) [--current U] --at X,Z,T ...\n"
      "  wave solitary --depth D --amplitude A [--angle DEG] [--x0 X0] --at X,Y,Z,T ...\n"
      "      Print the surface elevation, velocity and pressure of a fifth-order Stokes wave\n"
      "      (Fenton 1985) or of the solitary wave of Joly et al. (2016) at each point, one JSON\n"
      "      object per line (sabre-sph wave --help; docs/sph-waves.md).\n"
      "\n"
      "See docs/sph-geometry.md, docs/sph-case-file.md, docs/sph-scalar.md and "
      "docs/sph-waves.md.\n");
}

/* ------------------------------------------------------------------------------------------ */
/* γ over a set of wall elements                                                               */
/* ------------------------------------------------------------------------------------------ */

static void element_from_mesh(const struct sph_mesh *m, size_t e, struct sph_wall_element *w) {
  memset(w, 0, sizeof *w);
  for (int k = 0; k < m->dim; k++)
    for (int a = 0; a < 3; a++) w->x[k][a] = m->vert[m->elem[e][k]][a];
  memcpy(w->normal, m->normal[e], sizeof w->normal);
}

/* γ and ∇γ of every fluid and vertex particle of s from its segment neighbours. */
static void compute_gamma(struct sph_system *s, const struct sph_kernel *kern) {
  double support = sph_kernel_support(kern);
  struct sph_cells cells = {0};
  sph_cells_build(&cells, s, support);
  const struct sph_parts *ps = &s->part[SPH_KIND_SEGMENT];
  for (int kind = SPH_KIND_FLUID; kind <= SPH_KIND_VERTEX; kind++) {
    struct sph_parts *p = &s->part[kind];
    struct sph_nlist nl = {0};
    sph_nlist_build(&nl, &cells, s, (enum sph_kind)kind, SPH_KIND_SEGMENT, support);
    size_t maxrow = 1;
    for (size_t i = 0; i < p->n; i++)
      if (nl.offset[i + 1] - nl.offset[i] > maxrow) maxrow = nl.offset[i + 1] - nl.offset[i];
    long failed = -1;
#ifdef _OPENMP
#pragma omp parallel
#endif
    {
      struct sph_wall_element *el = cmn_malloc(maxrow * sizeof *el);
#ifdef _OPENMP
#pragma omp for schedule(dynamic, 64)
#endif
      for (size_t i = 0; i < p->n; i++) {
        double a[3] = {p->x[0][i], p->x[1][i], p->x[2][i]}, grad[3];
        size_t n = 0;
        for (size_t k = nl.offset[i]; k < nl.offset[i + 1]; k++, n++) {
          size_t j = nl.index[k];
          memset(&el[n], 0, sizeof el[n]);
          sph_segment_vertices(s, j, a, el[n].x);
          for (int c = 0; c < 3; c++) el[n].normal[c] = ps->normal[c][j];
        }
        if (sph_gamma_eval(kern, a, n, el, &p->gamma[i], grad) != 0) {
#ifdef _OPENMP
#pragma omp critical
#endif
          failed = (long)i;
        }
        for (int c = 0; c < 3; c++) p->grad_gamma[c][i] = grad[c];
      }
      free(el);
    }
    if (failed >= 0)
      cmn_input_error(
          "gamma undefined at %s particle id %lld (%g, %g, %g): is it on a wall with "
          "no fluid side?",
          kind == SPH_KIND_FLUID ? "fluid" : "vertex", (long long)p->id[failed], p->x[0][failed],
          p->x[1][failed], p->x[2][failed]);
    sph_nlist_free(&nl);
  }
  sph_cells_free(&cells);
}

/* ------------------------------------------------------------------------------------------ */
/* sabre-sph gamma                                                                             */
/* ------------------------------------------------------------------------------------------ */

static const char *need_value(int argc, char **argv, int i) {
  if (i + 1 >= argc) cmn_input_error("%s needs a value (see sabre-sph --help)", argv[i]);
  return argv[i + 1];
}

static void parse_point(const char *opt, const char *text, int dim, double *x) {
  x[0] = x[1] = x[2] = 0;
  if (cmn_parse_doubles(text, x, 3) != dim)
    cmn_input_error("%s '%s': expected %d comma-separated number%s", opt, text, dim,
                    dim > 1 ? "s" : "");
}

int sph_cmd_gamma(int argc, char **argv) {
  long dim = 0;
  double dr = 0, k = 0, lo[3], hi[3], (*at)[3] = NULL;
  const char *stl = NULL, *box = NULL;
  int nat = 0, stl_fluid = -1;
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    if (strcmp(o, "--help") == 0 || strcmp(o, "-h") == 0) {
      sph_cmd_usage(stdout);
      return 0;
    }
    const char *v = need_value(argc, argv, i);
    if (strcmp(o, "--dim") == 0) {
      if (cmn_parse_long(v, 1, 3, &dim)) cmn_input_error("--dim '%s': expected 1, 2 or 3", v);
    } else if (strcmp(o, "--dr") == 0) {
      if (cmn_parse_double(v, &dr) || !(dr > 0))
        cmn_input_error("--dr '%s': expected a positive number [m]", v);
    } else if (strcmp(o, "--h-over-dr") == 0) {
      if (cmn_parse_double(v, &k) || !(k > 0))
        cmn_input_error("--h-over-dr '%s': expected a positive number", v);
    } else if (strcmp(o, "--box") == 0) {
      box = v;
    } else if (strcmp(o, "--stl") == 0) {
      stl = v;
    } else if (strcmp(o, "--stl-fluid") == 0) {
      if (strcmp(v, "inside") && strcmp(v, "outside"))
        cmn_input_error("--stl-fluid '%s': expected inside or outside", v);
      stl_fluid = strcmp(v, "inside") == 0;
    } else if (strcmp(o, "--at") == 0) {
      at = cmn_realloc(at, (size_t)(nat + 1) * sizeof *at);
      if (dim == 0) cmn_input_error("--at: give --dim first");
      parse_point("--at", v, (int)dim, at[nat++]);
    } else {
      cmn_input_error("gamma: unknown option '%s' (see sabre-sph --help)", o);
    }
    i++;
  }
  if (dim == 0 || dr == 0 || k == 0)
    cmn_input_error("gamma needs --dim, --dr and --h-over-dr (see sabre-sph --help)");
  if (!box && !stl) cmn_input_error("gamma needs walls: --box LO:HI and/or --stl FILE");
  if (nat == 0) cmn_input_error("gamma needs at least one --at point");
  if (stl && dim != 3) cmn_input_error("--stl: STL walls exist in 3D only (--dim 3)");

  struct sph_mesh m;
  sph_mesh_init(&m, (int)dim);
  if (box) {
    const char *colon = strchr(box, ':');
    if (!colon) cmn_input_error("--box '%s': expected LO:HI, e.g. 0,0:1,0.5", box);
    char *los = strndup(box, (size_t)(colon - box));
    parse_point("--box (LO)", los, (int)dim, lo);
    parse_point("--box (HI)", colon + 1, (int)dim, hi);
    free(los);
    for (int a = 0; a < dim; a++)
      if (!(hi[a] > lo[a]))
        cmn_input_error("--box '%s': HI must exceed LO in every direction", box);
    sph_mesh_box(&m, lo, hi, dr, 0, 0, sph_mesh_add_source(&m, "--box"));
  }
  char msg[2048];
  if (stl) {
    int inside = stl_fluid >= 0 ? stl_fluid : !box;
    if (sph_mesh_read_stl(&m, stl, 1.0, inside, msg, sizeof msg)) cmn_input_error("%s", msg);
  }
  sph_mesh_merge_vertices(&m, 1e-9 * dr);
  sph_mesh_refine(&m, dr);
  if (sph_mesh_check(&m, NULL, msg, sizeof msg)) cmn_input_error("%s", msg);

  struct sph_kernel kern;
  if (sph_kernel_init(&kern, (int)dim, k * dr)) cmn_input_error("invalid kernel parameters");
  double support = sph_kernel_support(&kern);
  struct sph_system walls; /* to tell points outside the fluid */
  sph_system_init(&walls, (int)dim);
  walls.dr = dr;
  sph_system_add_walls(&walls, &m);
  struct sph_wall_element *el = cmn_malloc((m.nelem + 1) * sizeof *el);
  for (int p = 0; p < nat; p++) {
    double behind;
    if (sph_system_wall_side(&walls, at[p], &behind) == 0 && behind > 1e-9 * dr)
      cmn_warning(
          "--at %g,%g,%g lies outside the fluid, %g m behind the nearest wall: gamma "
          "there has no meaning",
          at[p][0], at[p][1], at[p][2], behind);
    size_t n = 0;
    for (size_t e = 0; e < m.nelem; e++) {
      double v[3][3], q[3];
      for (int c = 0; c < 3; c++)
        for (int a = 0; a < 3; a++) v[c][a] = c < dim ? m.vert[m.elem[e][c]][a] : 0.0;
      if (sph_element_distance((int)dim, v, at[p], q) < support) element_from_mesh(&m, e, &el[n++]);
    }
    double g, grad[3];
    if (sph_gamma_eval(&kern, at[p], n, el, &g, grad))
      cmn_input_error("--at %g,%g,%g: gamma is undefined there (on a wall with no fluid side?)",
                      at[p][0], at[p][1], at[p][2]);
    printf("{\"at\": [");
    for (int a = 0; a < dim; a++) printf("%s%.17g", a ? ", " : "", at[p][a]);
    printf("], \"gamma\": %.17g, \"grad_gamma\": [", g);
    for (int a = 0; a < dim; a++) printf("%s%.17g", a ? ", " : "", grad[a]);
    printf("]}\n");
  }
  free(el);
  free(at);
  sph_system_free(&walls);
  sph_mesh_free(&m);
  return cmn_stdout_status(0);
}

/* ------------------------------------------------------------------------------------------ */
/* sabre-sph mesh                                                                              */
/* ------------------------------------------------------------------------------------------ */

static const char mesh_usage[] =
    "usage: sabre-sph mesh CASE.yaml --output DIR [--set key=value]...\n"
    "Mesh the walls and fill the fluid of the case's geometry section, compute gamma, and write\n"
    "DIR/mesh.pvd (fluid and boundary VTU files) and DIR/used_case.yaml.\n"
    "See docs/sph-geometry.md, section 6.2.\n";

int sph_cmd_mesh(int argc, char **argv) {
  struct cmn_cli cli;
  if (cmn_cli_parse(&cli, argc, argv, argv[0], mesh_usage, NULL, NULL, 0))
    return cmn_stdout_status(0);
  /* No default run directory: mesh output is asked for, not a by-product. */
  if (cli.output == NULL) cmn_input_error("%s: --output DIR is required (see --help)", argv[0]);
  const char *outdir = cli.output;
  struct cmn_case *c = cmn_cli_load(&cli);

  struct sph_geometry g;
  sph_geometry_read(&g, c);
  if (cmn_case_has(c, "fluid")) { /* a full run case: check the solver's sections too */
    struct sph_config cfg;
    sph_config_read(&cfg, c, g.dim);
    sph_open_check_mesh(&cfg.open, c, &g.walls);
  }
  cmn_case_check_unused(c);
  cmn_cli_write_used(c, outdir);
  struct sph_system s;
  sph_system_from_geometry(&s, &g);
  struct sph_kernel kern;
  if (sph_kernel_init(&kern, s.dim, s.h)) cmn_input_error("invalid kernel parameters");
  compute_gamma(&s, &kern);

  struct sph_output out;
  errno = 0;
  if (sph_output_open(&out, outdir, "mesh") || sph_output_write(&out, &s, 0.0))
    cmn_input_error("cannot write the VTU output in '%s': %s", outdir,
                    errno ? strerror(errno) : "write error");
  sph_output_close(&out);

  double gmin[2] = {INFINITY, INFINITY}, gmax[2] = {-INFINITY, -INFINITY};
  for (int kind = 0; kind < 2; kind++)
    for (size_t i = 0; i < s.part[kind].n; i++) {
      gmin[kind] = fmin(gmin[kind], s.part[kind].gamma[i]);
      gmax[kind] = fmax(gmax[kind], s.part[kind].gamma[i]);
    }
  cmn_message("%dD, dr = %g m, h = %g m: %zu fluid, %zu vertex, %zu segment particles", s.dim, s.dr,
              s.h, s.part[SPH_KIND_FLUID].n, s.part[SPH_KIND_VERTEX].n, s.part[SPH_KIND_SEGMENT].n);
  if (s.part[0].n) cmn_message("gamma: fluid in [%.6f, %.6f]", gmin[0], gmax[0]);
  if (s.part[1].n) cmn_message("gamma: vertices in [%.6f, %.6f]", gmin[1], gmax[1]);
  cmn_message("wrote %s/mesh.pvd (open it in ParaView) and %s/used_case.yaml", outdir, outdir);
  sph_system_free(&s);
  sph_geometry_free(&g);
  cmn_case_free(c);
  return 0;
}
