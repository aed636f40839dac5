/*
 * Boundary-corrected SPH operators at a fluid particle (THEORY §3.2, docs/sph-solver.md §2):
 * Grad^{γ,k} M(37) (k = 1: J 6 / M 11), Div^{γ,k} M(38) (k = 1: J 7 / M 8), Lap^γ J(8) with the
 * harmonic mean J(9); the momentum equation's pressure gradient, in which a wall does not pull a
 * particle that moves towards it (operators/pressure.h). Gather form: particle a sums over its
 * neighbours, deterministic for a fixed thread count. The pair geometry is shared with the solver
 * through operators/pair.h.
 */
#include <math.h>

#include "operators/pair.h"
#include "operators/pressure.h"
#include "sabre/sph_solver.h"

/* The velocity of wall element j of pw as it moves [m/s]: its own for walls, 0 for open elements
 * (fixed in space; their velocity is the fluid's at the boundary, from their Riemann solve). */
static double motion(const struct sph_parts *pw, size_t j, int c) {
  return pw->flags[j] & SPH_FLAG_OPEN ? 0.0 : pw->v[c][j];
}

/* Relative normal velocity (v_a − v_w)·n/|n| of fluid particle a towards wall element j of pw, v_w
 * the element's motion (n into the fluid: negative when a approaches the element). */
static double approach(const struct sph_parts *pa, size_t a, const struct sph_parts *pw, size_t j) {
  double un = 0.0, nn = 0.0;
  for (int c = 0; c < 3; c++) {
    un += (pa->v[c][a] - motion(pw, j, c)) * pw->normal[c][j];
    nn += pw->normal[c][j] * pw->normal[c][j];
  }
  return nn > 0.0 ? un / sqrt(nn) : 0.0;
}

/* ω_ae of the contact form (operators/pressure.h) for a pair at distance d from the element's
 * plane; 1 for the acoustic form (reach 0). */
static double contact_weight(const struct sph_wall_impedance *imp, double d) {
  if (imp->reach == 0.0) return 1.0;
  return d > 0.0 ? fmax(0.0, 1.0 - d / imp->reach) : 0.0;
}

double sph_op_open_share(const struct sph_op *op, size_t a) {
  const struct sph_parts *ps = &op->sys->part[SPH_KIND_SEGMENT];
  const struct sph_nlist *nl = &op->nb->list[SPH_KIND_SEGMENT];
  double open = 0.0, all = 0.0;
  for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
    const double t = fabs(op->nb->term_as[q]);
    all += t;
    if (ps->flags[nl->index[q]] & SPH_FLAG_WET) open += t; /* dry ones act as walls */
  }
  return all > 0.0 ? open / all : 0.0;
}

/* (v_a − v_b)·(r_a − r_b) for fluid particle a and vertex b at separation r = r_a − r_b (v_b its
 * motion): not positive when a does not move away from b. */
static double closing_vertex(const struct sph_parts *pa, size_t a, const struct sph_parts *pb,
                             size_t b, const double r[3]) {
  double s = 0.0;
  for (int c = 0; c < 3; c++) s += (pa->v[c][a] - motion(pb, b, c)) * r[c];
  return s;
}

/* numerics.no_pull: normal, for fluid particle a and vertex b at separation r = r_a − r_b (v_b its
 * motion): 1 when a closes in on b along the vertex's unit normal n̂ (stored in n),
 * (r·n̂)((v_a − v_b)·n̂) ≤ 0, so that the pull's part along n̂ would do work ≥ 0 on the pair's
 * relative motion; 0 otherwise. A vertex without a normal is tested along n̂ = r/|r| (the whole
 * pull, as the radial rule). */
static int pull_cut_normal(const struct sph_parts *pa, size_t a, const struct sph_parts *pb,
                           size_t b, const double r[3], double n[3]) {
  double nn = 0.0;
  for (int c = 0; c < 3; c++) {
    n[c] = pb->normal[c][b];
    nn += n[c] * n[c];
  }
  if (!(nn > 0.0)) {
    for (int c = 0; c < 3; c++) n[c] = r[c];
    nn = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  }
  const double inv = 1.0 / sqrt(nn);
  double rn = 0.0, un = 0.0;
  for (int c = 0; c < 3; c++) {
    n[c] *= inv;
    rn += r[c] * n[c];
    un += (pa->v[c][a] - motion(pb, b, c)) * n[c];
  }
  return rn * un <= 0.0;
}

/* g += t d, less its part along the unit vector n when n is given. */
static void add_term(double g[3], double t, const double d[3], const double *n) {
  if (n) {
    const double dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    for (int c = 0; c < 3; c++) g[c] += t * (d[c] - dn * n[c]);
  } else {
    for (int c = 0; c < 3; c++) g[c] += t * d[c];
  }
}

/* Grad^{γ,k}_a(f), M(37); with no_pull, a wall pair (vertex or segment) whose weighted sum
 * (ρ_a/ρ_b)^k f_b + (ρ_b/ρ_a)^k f_a is negative is left out while a does not move away from the
 * element (sph_op_grad_pressure): a pull that would do work ≥ 0 on the pair's relative motion.
 * g_fluid (NULL: none): the sum over the fluid pairs already formed by the caller (same pairs,
 * order and arithmetic); the sum then goes on over the vertices and segments only. */
static void grad(const struct sph_op *op, double k, const double *const f[SPH_NKINDS], size_t a,
                 int no_pull, const struct sph_wall_impedance *impedance, int open_difference,
                 const struct sph_vertex_layer *layer, const double *g_fluid, double out[3]) {
  const struct sph_system *s = op->sys;
  const struct sph_parts *pa = &s->part[SPH_KIND_FLUID];
  const double rho_a = pa->rho[a], fa = f[SPH_KIND_FLUID][a];
  double g[3] = {0.0, 0.0, 0.0};
  if (g_fluid)
    for (int c = 0; c < 3; c++) g[c] = g_fluid[c];
  /* Near an open boundary, χ_a f_a × the zeroth-order defect is taken out of every pair:
   * (ρ_a/ρ_b)^k (f_b − χ_a f_a) + (1 − χ_a) f_a (ρ_b/ρ_a)^k (docs/sph-solver.md §10). */
  const double chi = open_difference ? sph_op_open_share(op, a) : 0.0, fc = chi * fa;
  const double qa = (fa - fc) / rho_a; /* the fluid pairs' f_a part for k = 1 */
  for (int kind = g_fluid ? SPH_KIND_VERTEX : SPH_KIND_FLUID; kind <= SPH_KIND_VERTEX; kind++) {
    const struct sph_parts *pb = &s->part[kind];
    const struct sph_nlist *nl = &op->nb->list[kind];
    for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
      size_t b = nl->index[q];
      struct sph_pair pr;
      if (!sph_pair_eval(op->kernel, s, pa, a, pb, b, &pr)) continue;
      if (kind == SPH_KIND_FLUID && k == 1.0) { /* as the fused loop (solver.c: fluid_pairs) */
        const double t = sph_pair_pressure_k1(pb->mass[b], rho_a, sph_inv_rho2(pb->rho[b]),
                                              f[kind][b] - fc, qa) *
                         pr.dwdr_over_r;
        for (int c = 0; c < 3; c++) g[c] += t * pr.r[c];
        continue;
      }
      const double rho_b = pb->rho[b], vb = pb->mass[b] / rho_b;
      const double ratio = sph_rho_ratio_k(rho_a, rho_b, k);
      double fb = f[kind][b];
      if (impedance && kind == SPH_KIND_VERTEX && !(pb->flags[b] & SPH_FLAG_OPEN)) {
        const double un = approach(pa, a, pb, b);
        if (un < 0.0) {
          double d = 0.0, nn = 0.0; /* (r_a − r_v)·n̂_v */
          for (int c = 0; c < 3; c++) {
            d += pr.r[c] * pb->normal[c][b];
            nn += pb->normal[c][b] * pb->normal[c][b];
          }
          d = nn > 0.0 ? d / sqrt(nn) : 0.0;
          fb -= contact_weight(impedance, d) * impedance->z[a] * un;
        }
      }
      double sum = ratio * fb + fa / ratio;
      double nv[3]; /* numerics.no_pull: normal: the pull's part along n̂_v is left out */
      const int pull = no_pull && kind == SPH_KIND_VERTEX && sum < 0.0;
      if (pull && !op->no_pull_normal && closing_vertex(pa, a, pb, b, pr.r) <= 0.0) continue;
      const double *cut =
          pull && op->no_pull_normal && pull_cut_normal(pa, a, pb, b, pr.r, nv) ? nv : NULL;
      if (fc != 0.0) sum -= fc * (ratio + 1.0 / ratio);
      const double lv = layer && kind == SPH_KIND_VERTEX ? layer->vol[b] : 0.0;
      const double t = (vb - lv) * sum * pr.dwdr_over_r;
      add_term(g, t, pr.r, cut);
      if (lv != 0.0) { /* the vertex's entered mass, at the centre of its layer */
        const double xa[3] = {pa->x[0][a], pa->x[1][a], pa->x[2][a]};
        const double xl[3] = {layer->x[0][b], layer->x[1][b], layer->x[2][b]};
        double d[3];
        sph_domain_delta(&s->domain, xl, xa, d); /* r_a − the layer's centre */
        const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        const double r = sqrt(r2);
        if (r > 0.0 && r < sph_kernel_support(op->kernel)) {
          const double tl = lv * sum * sph_kernel_dwdr_inline(op->kernel, r) / r;
          add_term(g, tl, d, cut);
        }
      }
    }
  }
  const struct sph_parts *ps = &s->part[SPH_KIND_SEGMENT];
  const struct sph_nlist *nl = &op->nb->list[SPH_KIND_SEGMENT];
  for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
    size_t j = nl->index[q];
    const double ratio = sph_rho_ratio_k(rho_a, ps->rho[j], k);
    double fs = f[SPH_KIND_SEGMENT][j];
    if (impedance && !(ps->flags[j] & SPH_FLAG_OPEN)) { /* open values come from their solve */
      const double un = approach(pa, a, ps, j);
      if (un < 0.0) fs -= contact_weight(impedance, op->nb->dist_as[q]) * impedance->z[a] * un;
    }
    double t = ratio * fs + fa / ratio;
    if (no_pull && t < 0.0 && approach(pa, a, ps, j) <= 0.0) continue;
    if (fc != 0.0) t -= fc * (ratio + 1.0 / ratio);
    for (int c = 0; c < 3; c++) g[c] -= t * op->nb->grad_gamma_as[c][q];
  }
  const double inv_gamma = 1.0 / pa->gamma[a];
  for (int c = 0; c < 3; c++) out[c] = g[c] * inv_gamma;
}

void sph_op_grad(const struct sph_op *op, double k, const double *const f[SPH_NKINDS], size_t a,
                 double out[3]) {
  grad(op, k, f, a, 0, NULL, 0, NULL, NULL, out);
}

void sph_op_grad_pressure(const struct sph_op *op, double k, const double *const p[SPH_NKINDS],
                          size_t a, const struct sph_wall_impedance *impedance, int open_difference,
                          const struct sph_vertex_layer *layer, double out[3]) {
  grad(op, k, p, a, 1, impedance, open_difference, layer, NULL, out);
}

void sph_op_grad_pressure_walls(const struct sph_op *op, double k,
                                const double *const p[SPH_NKINDS], size_t a,
                                const struct sph_wall_impedance *impedance, int open_difference,
                                const struct sph_vertex_layer *layer, const double g_fluid[3],
                                double out[3]) {
  grad(op, k, p, a, 1, impedance, open_difference, layer, g_fluid, out);
}

static double comp(const double *const B[3], int c, size_t i) { return B[c] ? B[c][i] : 0.0; }

double sph_op_div(const struct sph_op *op, double k, const double *const B[SPH_NKINDS][3],
                  size_t a) {
  const struct sph_system *s = op->sys;
  const struct sph_parts *pa = &s->part[SPH_KIND_FLUID];
  const double rho_a = pa->rho[a];
  const double Ba[3] = {comp(B[SPH_KIND_FLUID], 0, a), comp(B[SPH_KIND_FLUID], 1, a),
                        comp(B[SPH_KIND_FLUID], 2, a)};
  double sum = 0.0;
  for (int kind = SPH_KIND_FLUID; kind <= SPH_KIND_VERTEX; kind++) {
    const struct sph_parts *pb = &s->part[kind];
    const struct sph_nlist *nl = &op->nb->list[kind];
    for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
      size_t b = nl->index[q];
      struct sph_pair pr;
      if (!sph_pair_eval(op->kernel, s, pa, a, pb, b, &pr)) continue;
      const double vb = pb->mass[b] / pb->rho[b];
      /* ρ_a^k ρ_b^k / ρ_a^{2k} = (ρ_b/ρ_a)^k */
      const double ratio = 1.0 / sph_rho_ratio_k(rho_a, pb->rho[b], k);
      double dot = 0.0;
      for (int c = 0; c < 3; c++) dot += (comp(B[kind], c, b) - Ba[c]) * pr.r[c];
      sum += vb * ratio * dot * pr.dwdr_over_r;
    }
  }
  const struct sph_parts *ps = &s->part[SPH_KIND_SEGMENT];
  const struct sph_nlist *nl = &op->nb->list[SPH_KIND_SEGMENT];
  for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
    size_t j = nl->index[q];
    const double ratio = 1.0 / sph_rho_ratio_k(rho_a, ps->rho[j], k);
    double dot = 0.0;
    for (int c = 0; c < 3; c++)
      dot += (comp(B[SPH_KIND_SEGMENT], c, j) - Ba[c]) * op->nb->grad_gamma_as[c][q];
    sum -= ratio * dot;
  }
  return sum / pa->gamma[a];
}

/* l_fluid (NULL: none): as g_fluid of grad(). */
static void lap(const struct sph_op *op, const double *const beta[SPH_NKINDS],
                const double *const A[SPH_NKINDS][3], const double *const wall_flux[3],
                const struct sph_wall_shear *shear, size_t a, const double *l_fluid,
                double out[3]) {
  const struct sph_system *s = op->sys;
  const struct sph_parts *pa = &s->part[SPH_KIND_FLUID];
  const double beta_a = beta[SPH_KIND_FLUID][a];
  const double Aa[3] = {comp(A[SPH_KIND_FLUID], 0, a), comp(A[SPH_KIND_FLUID], 1, a),
                        comp(A[SPH_KIND_FLUID], 2, a)};
  double l[3] = {0.0, 0.0, 0.0};
  if (l_fluid)
    for (int c = 0; c < 3; c++) l[c] = l_fluid[c];
  for (int kind = l_fluid ? SPH_KIND_VERTEX : SPH_KIND_FLUID; kind <= SPH_KIND_VERTEX; kind++) {
    const struct sph_parts *pb = &s->part[kind];
    const struct sph_nlist *nl = &op->nb->list[kind];
    for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
      size_t b = nl->index[q];
      struct sph_pair pr;
      if (!sph_pair_eval(op->kernel, s, pa, a, pb, b, &pr) || pr.dist == 0.0) continue;
      const double beta_b = beta[kind][b];
      const double bsum = beta_a + beta_b;
      const double bbar = bsum > 0.0 ? 2.0 * beta_a * beta_b / bsum : 0.0; /* J(9) */
      /* r_ab·∇w_ab / r_ab² = dw/dr / r */
      const double t = pb->mass[b] / pb->rho[b] * 2.0 * bbar * pr.dwdr_over_r;
      for (int c = 0; c < 3; c++) l[c] += t * (Aa[c] - comp(A[kind], c, b));
    }
  }
  if (wall_flux || shear) {
    const struct sph_nlist *nl = &op->nb->list[SPH_KIND_SEGMENT];
    for (size_t q = nl->offset[a]; q < nl->offset[a + 1]; q++) {
      const double *gg[3] = {op->nb->grad_gamma_as[0], op->nb->grad_gamma_as[1],
                             op->nb->grad_gamma_as[2]};
      const double mag = sqrt(gg[0][q] * gg[0][q] + gg[1][q] * gg[1][q] + gg[2][q] * gg[2][q]);
      if (shear) {
        double fl[3];
        sph_wall_shear_flux(s, op->nb, shear, a, q, fl);
        for (int c = 0; c < 3; c++) l[c] -= fl[c] * mag;
        continue;
      }
      for (int c = 0; c < 3; c++)
        if (wall_flux[c]) l[c] -= wall_flux[c][q] * mag;
    }
  }
  const double inv_gamma = 1.0 / pa->gamma[a];
  for (int c = 0; c < 3; c++) out[c] = l[c] * inv_gamma;
}

void sph_op_lap(const struct sph_op *op, const double *const beta[SPH_NKINDS],
                const double *const A[SPH_NKINDS][3], const double *const wall_flux[3], size_t a,
                double out[3]) {
  lap(op, beta, A, wall_flux, NULL, a, NULL, out);
}

void sph_op_lap_walls(const struct sph_op *op, const double *const beta[SPH_NKINDS],
                      const double *const A[SPH_NKINDS][3], const struct sph_wall_shear *shear,
                      size_t a, const double l_fluid[3], double out[3]) {
  lap(op, beta, A, NULL, shear, a, l_fluid, out);
}
