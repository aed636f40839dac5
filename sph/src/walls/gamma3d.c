/*
 * γ and ∇γ_as in 3D, closed form (docs/sph-gamma.md §5). The triangle lies on a plane at signed
 * distance δ from a (δ > 0 on the fluid side); p is the foot point of a. Both integrals are of a
 * radial function over the triangle clipped to the support disc (radius R = √(4h² − δ²) around p).
 * In polar coordinates centred on p, the triangle is the signed sum of the three sub-triangles
 * (p, x_j, x_{j+1}); along the edge x_j x_{j+1} (abscissa s from the foot of p on the edge's line,
 * signed distance d from p to that line) dθ = d ds/(d² + s²) and the radial integral is done in
 * closed form, leaving for each monomial q^k (q² = c² + s², c² = δ̂² + d²)
 *   E_k = d ∫ (q^k − |δ̂|^k)/(d² + s²) ds,
 * which is again closed form: a polynomial for even k, and for odd k
 *   E_1 = d Δasinh(s/c) + |δ̂| (ΔA − Δθ),  E_k = d ΔL_{k−2} + δ̂² E_{k−2},
 * where Δθ is the angle swept along the edge, ΔA = Δatan(|δ̂| s/(d q)) (their difference is the
 * solid angle of the sub-triangle, taken with one atan2 by the half-angle formula of Van Oosterom &
 * Strackee) and L_k = ∫ q^k ds as in 2D. The parts of an edge outside the support disc contribute
 * the constant radial integral up to R times their angle.
 */
#include <math.h>

#include "kernel.h"
#include "walls/gamma_impl.h"

struct tri_frame {
  double nu[3];   /* unit normal, oriented like the element's normal */
  double delta;   /* signed distance of a from the plane [m] */
  double p[3][2]; /* vertices in the plane, relative to the foot point of a, frame (e1, e2) [m] */
  double sigma;   /* +1 if the vertices turn counter-clockwise about nu, else −1 */
};

static inline double dot3(const double *u, const double *v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

static inline void cross3(const double *u, const double *v, double *w) {
  w[0] = u[1] * v[2] - u[2] * v[1];
  w[1] = u[2] * v[0] - u[0] * v[2];
  w[2] = u[0] * v[1] - u[1] * v[0];
}

/* The part of the frame that does not depend on a. */
void sph_gamma3d_axes(const struct sph_wall_element *e, struct sph_tri_axes *ax) {
  double d1[3], d2[3], c[3];
  for (int i = 0; i < 3; i++) {
    d1[i] = e->x[1][i] - e->x[0][i];
    d2[i] = e->x[2][i] - e->x[0][i];
  }
  cross3(d1, d2, c);
  const double cn = sqrt(dot3(c, c));
  ax->sigma = dot3(c, e->normal) >= 0.0 ? 1.0 : -1.0;
  const double l1 = sqrt(dot3(d1, d1));
  for (int i = 0; i < 3; i++) {
    ax->nu[i] = ax->sigma * c[i] / cn;
    ax->e1[i] = d1[i] / l1;
  }
  cross3(ax->nu, ax->e1, ax->e2);
  /* the frame-independent rest of the pair computation (sph_gamma3d_pair_offset) */
  double cu = 0.0, cv = 0.0;
  for (int j = 0; j < 3; j++) {
    ax->x0[j] = e->x[0][j];
    ax->normal[j] = e->normal[j];
    double r[3];
    for (int i = 0; i < 3; i++) r[i] = e->x[j][i] - e->x[0][i];
    ax->u[j][0] = dot3(r, ax->e1);
    ax->u[j][1] = dot3(r, ax->e2);
    cu += ax->u[j][0] / 3.0;
    cv += ax->u[j][1] / 3.0;
  }
  ax->c[0] = cu;
  ax->c[1] = cv;
  ax->rad = 0.0;
  for (int j = 0; j < 3; j++) {
    const double *A = ax->u[j], *B = ax->u[(j + 1) % 3];
    const double ex = B[0] - A[0], ey = B[1] - A[1], len = sqrt(ex * ex + ey * ey);
    ax->dir[j][0] = ex / len;
    ax->dir[j][1] = ey / len;
    ax->rad = fmax(ax->rad, hypot(A[0] - cu, A[1] - cv));
  }
}

static void frame_at(const struct sph_wall_element *e, const struct sph_tri_axes *ax,
                     const double *a, struct tri_frame *f) {
  for (int i = 0; i < 3; i++) f->nu[i] = ax->nu[i];
  f->sigma = ax->sigma;
  /* δ from the nearest vertex: relative round-off for points close to a vertex or edge */
  double best = INFINITY;
  for (int j = 0; j < 3; j++) {
    double r[3];
    for (int i = 0; i < 3; i++) r[i] = e->x[j][i] - a[i];
    f->p[j][0] = dot3(r, ax->e1);
    f->p[j][1] = dot3(r, ax->e2);
    const double r2 = dot3(r, r);
    if (r2 < best) {
      best = r2;
      f->delta = -dot3(r, ax->nu);
    }
  }
}

static void frame(const struct sph_wall_element *e, const double *a, struct tri_frame *f) {
  struct sph_tri_axes ax;
  sph_gamma3d_axes(e, &ax);
  frame_at(e, &ax, a, f);
}

/* Per-triangle constants of the edge integrals (units of h). */
struct tri_consts {
  double dh, adh, sgn, D; /* δ̂, |δ̂|, sign(δ̂) (0 if δ̂ = 0), δ̂² */
  double R2;              /* R̂² = 4 − δ̂² */
  double out_w, out_g; /* integrands of ∫_T w and of the γ term beyond the support, per angle */
};

/* g(q) = ∫_0^q f u du and H(q) − (4/21)/q = ∫ (∫_0^q f u² du − 4/21)/q² dq, polynomial parts. */
static double g_poly(double q) {
  const double q2 = q * q, q4 = q2 * q2;
  return 0.5 * q2 + q4 * (-0.625 + q * (0.5 + q * (-5.0 / 32.0 + q / 56.0)));
}
static double h_poly(double q) {
  const double q2 = q * q, q4 = q2 * q2;
  return q2 / 6.0 + q4 * (-0.125 + q * (1.0 / 12.0 + q * (-5.0 / 224.0 + q / 448.0)));
}

static void consts(double dh, struct tri_consts *t) {
  t->dh = dh;
  t->adh = fabs(dh);
  t->sgn = dh > 0.0 ? 1.0 : (dh < 0.0 ? -1.0 : 0.0);
  t->D = dh * dh;
  t->R2 = 4.0 - t->D;
  t->out_w = g_poly(2.0) - g_poly(t->adh);
  /* −δ̂ [H(2) − H(|δ̂|)], the 1/q part written so that δ̂ → 0 is regular */
  t->out_g = -dh * (h_poly(2.0) - h_poly(t->adh)) - 2.0 / 21.0 * dh + 4.0 / 21.0 * t->sgn;
}

/* Edge piece outside the support disc, abscissae sa < sb. */
static void piece_outside(const struct tri_consts *t, double d, double sa, double sb, double *iw,
                          double *ig) {
  const double dtheta = atan2(d * (sb - sa), d * d + sa * sb);
  *iw += t->out_w * dtheta;
  *ig += t->out_g * dtheta;
}

/* Edge piece inside the support disc, abscissae sa < sb. The radial integrals are the sums
 * E_k above; Δ of the endpoint antiderivatives are formed so that they do not cancel. */
static void piece_inside(const struct tri_consts *t, double d, double sa, double sb, double *iw,
                         double *ig) {
  const double d2 = d * d, c2 = t->D + d2, D = t->D;
  const double sa2 = sa * sa, sb2 = sb * sb;
  const double qa = sqrt(c2 + sa2), qb = sqrt(c2 + sb2);
  /* q_a q_b + s_a s_b without cancellation: (q_a q_b)² − (s_a s_b)² = c²(c² + s_a² + s_b²) */
  const double sab = sa * sb, ds = sb - sa;
  const double qq = sab >= 0.0 ? qa * qb + sab : c2 * (c2 + sa2 + sb2) / (qa * qb - sab);
  /* ΔL_{−1} = Δasinh(s/c) = log1p(u), u = (s_b + q_b)/(s_a + q_a) − 1 (= (q_a − s_a)/(q_b − s_b) −
   * 1) formed without cancellation, with q_b − q_a = (s_b² − s_a²)/(q_a + q_b) and, for s_a < 0 <
   * s_b, q_a q_b − s_a s_b − c² = c² (s_b − s_a)²/(q_a q_b + s_a s_b + c²). */
  double u;
  if (sa >= 0.0)
    u = ds * (qa + qb + sa + sb) / ((qa + qb) * (sa + qa));
  else if (sb <= 0.0)
    u = ds * (qa + qb - sa - sb) / ((qa + qb) * (qb - sb));
  else
    u = ((sb * qa - sa * qb) * (qq + c2) + c2 * ds * ds) / (c2 * (qq + c2));
  /* log1p(u) as log(w) u/(w − 1), w = 1 + u (Goldberg 1991, Thm 4): as accurate, and glibc's log
   * is much faster than its log1p */
  const double w = 1.0 + u;
  const double dlm1 = w == 1.0 ? u : log(w) * (u / (w - 1.0));
  /* Solid angle of the sub-triangle (p, s_a, s_b) seen from a, Δθ − ΔA, by the half-angle
   * formula of Van Oosterom & Strackee (1983): one atan2 instead of two. */
  const double omega = 2.0 * atan2(d * (sb - sa), qq + c2 + t->adh * (qa + qb));
  const double v0 = sb - sa;
  /* divisions by constants as products with their reciprocals (division is the slow part here) */
  const double v1 = d2 * v0 + (sb2 * sb - sa2 * sa) * (1.0 / 3.0);
  const double v2 = d2 * d2 * v0 + 2.0 / 3.0 * d2 * (sb2 * sb - sa2 * sa) +
                    (sb2 * sb2 * sb - sa2 * sa2 * sa) * 0.2;
  const double qa2 = qa * qa, qb2 = qb * qb;
  const double l1 = 0.5 * (sb * qb - sa * qa + c2 * dlm1);
  const double l3 = 0.25 * (sb * qb2 * qb - sa * qa2 * qa + 3.0 * c2 * l1);
  const double l5 = (sb * qb2 * qb2 * qb - sa * qa2 * qa2 * qa + 5.0 * c2 * l3) * (1.0 / 6.0);
  const double e2 = d * v0;
  const double e4 = d * (2.0 * D * v0 + v1);
  const double e6 = d * (3.0 * D * D * v0 + 3.0 * D * v1 + v2);
  const double e1 = d * dlm1 - t->adh * omega;
  const double e3 = d * l1 + D * e1;
  const double e5 = d * l3 + D * e3;
  const double e7 = d * l5 + D * e5;
  *iw += 0.5 * e2 - 0.625 * e4 + 0.5 * e5 - 5.0 / 32.0 * e6 + (1.0 / 56.0) * e7;
  *ig += -t->dh * ((1.0 / 6.0) * e2 - 0.125 * e4 + (1.0 / 12.0) * e5 - 5.0 / 224.0 * e6 +
                   (1.0 / 448.0) * e7) +
         4.0 / 21.0 * t->sgn * omega;
}

/* Edge A → B (units of h, relative to the foot point p): abscissae of its ends and of the chord
 * through the support disc, signed distance d from p to its line. */
struct edge_geom {
  double d, sA, sB, S; /* S: half chord (0 if the line misses the disc) */
  int in;              /* part of the edge inside the disc */
};

static void edge_geometry(const struct tri_consts *t, const double *A, const double *B,
                          const double *dir, struct edge_geom *g) {
  double ex, ey;
  if (dir) { /* the element's unit edge direction, computed once */
    ex = dir[0];
    ey = dir[1];
  } else {
    ex = B[0] - A[0];
    ey = B[1] - A[1];
    const double len = sqrt(ex * ex + ey * ey);
    ex /= len;
    ey /= len;
  }
  g->sA = A[0] * ex + A[1] * ey;
  g->sB = B[0] * ex + B[1] * ey;
  /* cross(X, e) for X on the edge: dθ/ds = d/(d² + s²); from the endpoint nearer to p */
  g->d = (A[0] * A[0] + A[1] * A[1] < B[0] * B[0] + B[1] * B[1]) ? A[0] * ey - A[1] * ex
                                                                 : B[0] * ey - B[1] * ex;
  const double S2 = t->R2 - g->d * g->d;
  g->S = S2 > 0.0 ? sqrt(S2) : 0.0;
  g->in = S2 > 0.0 && g->sA < g->S && g->sB > -g->S;
}

/* Sub-triangle (p, A, B) of an edge that enters the disc (|d| ≥ 1e-150 keeps asinh(s/c) finite;
 * for p on the edge's line the sub-triangle has no area). */
static void edge_integrals(const struct tri_consts *t, const struct edge_geom *g, double *iw,
                           double *ig) {
  const double d = g->d, sA = g->sA, sB = g->sB, S = g->S;
  if (fabs(d) < 1e-150) return;
  if (!g->in) {
    piece_outside(t, d, sA, sB, iw, ig);
    return;
  }
  piece_inside(t, d, fmax(sA, -S), fmin(sB, S), iw, ig);
  if (sA < -S) piece_outside(t, d, sA, fmin(sB, -S), iw, ig);
  if (sB > S) piece_outside(t, d, fmax(sA, S), sB, iw, ig);
}

/* Solid angle of the spherical triangle of unit vectors u, v, w (Van Oosterom & Strackee 1983). */
static double solid_angle(const double *u, const double *v, const double *w) {
  double vw[3];
  cross3(v, w, vw);
  return 2.0 * atan2(fabs(dot3(u, vw)), 1.0 + dot3(u, v) + dot3(v, w) + dot3(w, u));
}

enum incidence { OUTSIDE, VERTEX, EDGE, INTERIOR };

/* Where a lies on the closed triangle, given |δ| ≤ SPH_GAMMA_PLANE_TOL·h: within tol of a vertex
 * (*j), of the edge j → j+1, or inside. */
static enum incidence classify(const double *a, const struct sph_wall_element *e,
                               const struct tri_frame *f, double tol, int *j) {
  for (*j = 0; *j < 3; (*j)++) {
    double r[3];
    for (int i = 0; i < 3; i++) r[i] = a[i] - e->x[*j][i];
    if (sqrt(dot3(r, r)) <= tol) return VERTEX;
  }
  for (*j = 0; *j < 3; (*j)++) {
    const double *x0 = e->x[*j], *x1 = e->x[(*j + 1) % 3];
    double u[3], r[3];
    for (int i = 0; i < 3; i++) {
      u[i] = x1[i] - x0[i];
      r[i] = a[i] - x0[i];
    }
    const double t = dot3(r, u) / dot3(u, u);
    if (t <= 0.0 || t >= 1.0) continue;
    for (int i = 0; i < 3; i++) r[i] -= t * u[i];
    if (sqrt(dot3(r, r)) <= tol) return EDGE;
  }
  for (int i = 0; i < 3; i++) {
    const double *P = f->p[i], *Q = f->p[(i + 1) % 3];
    /* interior: the foot point (origin) is strictly left of every edge when counter-clockwise */
    if (f->sigma * ((Q[0] - P[0]) * (-P[1]) - (Q[1] - P[1]) * (-P[0])) <= 0.0) return OUTSIDE;
  }
  return INTERIOR;
}

static void unit_to(const double *a, const double *x, double *u) {
  for (int i = 0; i < 3; i++) u[i] = x[i] - a[i];
  const double n = sqrt(dot3(u, u));
  for (int i = 0; i < 3; i++) u[i] /= n;
}

/* Limit of gamma_term for a on the plane, approaching along m: the solid angle under which
 * a + ε m sees the triangle, over 4π (docs/sph-gamma.md §5.3). */
static double limit_term(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, const struct tri_frame *f,
                         const double *m) {
  const double *mm = m == NULL ? f->nu : m;
  const double side = dot3(mm, f->nu) > 0.0 ? 1.0 : -1.0;
  const double mneg[3] = {-mm[0], -mm[1], -mm[2]};
  int j;
  double omega = 0.0, uk[3], ul[3], uj[3];
  switch (classify(a, e, f, SPH_GAMMA_PLANE_TOL * k->h, &j)) {
    case VERTEX:
      unit_to(a, e->x[(j + 1) % 3], uk);
      unit_to(a, e->x[(j + 2) % 3], ul);
      omega = solid_angle(mneg, uk, ul);
      break;
    case EDGE: /* split at a into (a, x_{j+1}, x_{j+2}) and (a, x_{j+2}, x_j) */
      unit_to(a, e->x[j], uj);
      unit_to(a, e->x[(j + 1) % 3], uk);
      unit_to(a, e->x[(j + 2) % 3], ul);
      omega = solid_angle(mneg, uk, ul) + solid_angle(mneg, ul, uj);
      break;
    case INTERIOR:
      omega = 2.0 * SPH_PI;
      break;
    case OUTSIDE:
      break;
  }
  return side * omega / (4.0 * SPH_PI);
}

/* The term and ∇γ_as of the element at a, given its frame at a. ax (NULL: none) gives the edges'
 * directions, the bounding radius and the normal; e (only read within SPH_GAMMA_PLANE_TOL·h of the
 * plane, and for the normal without ax) the vertices. */
static void element_in_frame(const struct sph_kernel *k, const double *a,
                             const struct sph_wall_element *e, const struct sph_tri_axes *ax,
                             const struct tri_frame *f, const double *m, struct sph_edge_share *sh,
                             double *term, double grad[3]) {
  grad[0] = grad[1] = grad[2] = 0.0;
  *term = 0.0;
  if (sh) sh->got = 0;
  const double h = k->h;
  if (fabs(f->delta) >= 2.0 * h) return;
  /* On the triangle the term needs the one-sided limit; anywhere else, even 1e-13 h from its
   * plane, the closed form is well conditioned (and 0 exactly on the plane off the triangle). */
  int where;
  const int on = fabs(f->delta) <= SPH_GAMMA_PLANE_TOL * h &&
                 classify(a, e, f, SPH_GAMMA_PLANE_TOL * h, &where) != OUTSIDE;
  const double dh = on ? 0.0 : f->delta * k->inv_h;
  double P[3][2];
  for (int j = 0; j < 3; j++) {
    P[j][0] = f->p[j][0] * k->inv_h;
    P[j][1] = f->p[j][1] * k->inv_h;
  }
  /* Cull on the bounding circle of the triangle before the edge integrals. */
  const double cx = (P[0][0] + P[1][0] + P[2][0]) / 3.0, cy = (P[0][1] + P[1][1] + P[2][1]) / 3.0;
  double rad;
  if (ax) {
    rad = ax->rad * k->inv_h;
  } else {
    double rad2 = 0.0;
    for (int j = 0; j < 3; j++) {
      const double ux = P[j][0] - cx, uy = P[j][1] - cy;
      rad2 = fmax(rad2, ux * ux + uy * uy);
    }
    rad = sqrt(rad2);
  }
  const double reach = sqrt(4.0 - dh * dh) + rad;
  if (cx * cx + cy * cy >= reach * reach) return; /* a is off s: not `on` either */
  struct tri_consts t;
  consts(dh, &t);
  struct edge_geom g[3];
  int cut = 0;
  for (int j = 0; j < 3; j++) {
    edge_geometry(&t, P[j], P[(j + 1) % 3], ax ? ax->dir[j] : NULL, &g[j]);
    cut |= g[j].in;
  }
  double iw = 0.0, ig = 0.0;
  if (cut) {
    /* Per edge, or taken from the coplanar neighbour that shares it (on the triangle itself the
     * constants are those of δ = 0: nothing is shared). */
    const int share = sh != NULL && !on;
    for (int j = 0; j < 3; j++) {
      double ew = 0.0, eg = 0.0;
      if (share && (sh->have >> j & 1)) {
        ew = sh->value[j][0];
        eg = sh->value[j][1];
      } else {
        edge_integrals(&t, &g[j], &ew, &eg);
      }
      if (share) {
        sh->value[j][0] = ew;
        sh->value[j][1] = eg;
      }
      iw += ew;
      ig += eg;
    }
    if (share) sh->got = 7;
  } else {
    /* No edge enters the disc: the disc is outside the triangle (exactly 0, not round-off) or
     * inside it (the whole disc), where p is on the same side of every edge (d of one sign). */
    const double full = (g[0].d >= 1e-150 && g[1].d >= 1e-150 && g[2].d >= 1e-150) ? 2.0 * SPH_PI
                        : (g[0].d <= -1e-150 && g[1].d <= -1e-150 && g[2].d <= -1e-150)
                            ? -2.0 * SPH_PI
                            : 0.0;
    iw = t.out_w * full;
    ig = t.out_g * full;
  }
  const double gw = f->sigma * SPH_WENDLAND_ALPHA3 * k->inv_h * iw;
  const double *normal = ax ? ax->normal : e->normal;
  for (int i = 0; i < 3; i++) grad[i] = gw * normal[i];
  *term = on ? limit_term(k, a, e, f, m) : f->sigma * SPH_WENDLAND_ALPHA3 * ig;
}

void sph_gamma3d_element(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, const double *m, double *term,
                         double grad[3]) {
  struct tri_frame f;
  frame(e, a, &f);
  element_in_frame(k, a, e, NULL, &f, m, NULL, term, grad);
}

/* Squared distance from the origin to the triangle p[0..2] of the plane (orientation sigma): 0
 * inside, else the least distance to the edges that have the origin on their outer side (the
 * nearest point of a convex polygon lies on one of them). */
static double plane_distance2(const double p[3][2], double sigma) {
  double best = INFINITY;
  for (int j = 0; j < 3; j++) {
    const double *A = p[j], *B = p[(j + 1) % 3];
    const double ex = B[0] - A[0], ey = B[1] - A[1];
    const double cross = ey * A[0] - ex * A[1]; /* |e| × the distance to the edge's line */
    if (sigma * cross >= 0.0) continue;         /* inner side (the interior is to the left) */
    const double along = -(A[0] * ex + A[1] * ey), ee = ex * ex + ey * ey;
    const double d2 = along <= 0.0  ? A[0] * A[0] + A[1] * A[1]
                      : along >= ee ? B[0] * B[0] + B[1] * B[1]
                                    : cross * cross / ee;
    best = d2 < best ? d2 : best;
  }
  return best == INFINITY ? 0.0 : best;
}

void sph_gamma3d_pair(const struct sph_kernel *k, const double *a, const struct sph_wall_element *e,
                      const struct sph_tri_axes *ax, struct sph_edge_share *sh, double *term,
                      double grad[3], double *dist, double *off) {
  struct tri_frame f;
  frame_at(e, ax, a, &f);
  *off = f.delta;
  *dist = sqrt(f.delta * f.delta + plane_distance2((const double(*)[2])f.p, f.sigma));
  if (*dist < 2.0 * k->h) {
    element_in_frame(k, a, e, ax, &f, NULL, sh, term, grad);
  } else {
    if (sh) sh->got = 0;
    *term = 0.0;
    grad[0] = grad[1] = grad[2] = 0.0;
  }
}

/* The frame at the point of offset d from the first vertex, from the precomputed axes, given
 * f->delta = d·ν (the caller's first test). */
static void frame_offset(const double d[3], const struct sph_tri_axes *ax, struct tri_frame *f) {
  const double au = dot3(d, ax->e1), av = dot3(d, ax->e2);
  for (int j = 0; j < 3; j++) {
    f->nu[j] = ax->nu[j];
    f->p[j][0] = ax->u[j][0] - au;
    f->p[j][1] = ax->u[j][1] - av;
  }
  f->sigma = ax->sigma;
}

int sph_gamma3d_pair_offset(const struct sph_kernel *k, const double d[3],
                            const struct sph_tri_axes *ax, struct sph_edge_share *sh, double *term,
                            double grad[3], double *off) {
  struct tri_frame f;
  f.delta = dot3(d, ax->nu);
  if (fabs(f.delta) <= SPH_GAMMA_PLANE_TOL * k->h) return 1; /* on the plane: the vertices */
  *off = f.delta;
  if (fabs(f.delta) < 2.0 * k->h) { /* element_in_frame culls on the bounding circle */
    frame_offset(d, ax, &f);
    element_in_frame(k, NULL, NULL, ax, &f, NULL, sh, term, grad);
  } else {
    if (sh) sh->got = 0;
    *term = 0.0;
    grad[0] = grad[1] = grad[2] = 0.0;
  }
  return 0;
}

double sph_gamma3d_offset_bound(const double d[3], const struct sph_tri_axes *ax) {
  const double delta = dot3(d, ax->nu);
  const double cx = ax->c[0] - dot3(d, ax->e1), cy = ax->c[1] - dot3(d, ax->e2);
  const double rho = sqrt(cx * cx + cy * cy) - ax->rad;
  return sqrt(delta * delta + (rho > 0.0 ? rho * rho : 0.0));
}

double sph_gamma3d_offset_distance(const double d[3], const struct sph_tri_axes *ax) {
  struct tri_frame f;
  f.delta = dot3(d, ax->nu);
  frame_offset(d, ax, &f);
  return sqrt(f.delta * f.delta + plane_distance2((const double(*)[2])f.p, f.sigma));
}

int sph_gamma3d_incident(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, double tol, double m[3]) {
  struct tri_frame f;
  frame(e, a, &f);
  if (fabs(f.delta) > SPH_GAMMA_PLANE_TOL * k->h) return 0;
  int j;
  double weight;
  switch (classify(a, e, &f, tol, &j)) {
    case VERTEX: {
      double u[3], v[3], c[3];
      for (int i = 0; i < 3; i++) {
        u[i] = e->x[(j + 1) % 3][i] - e->x[j][i];
        v[i] = e->x[(j + 2) % 3][i] - e->x[j][i];
      }
      cross3(u, v, c);
      weight = atan2(sqrt(dot3(c, c)), dot3(u, v));
      break;
    }
    case EDGE:
      weight = SPH_PI;
      break;
    case INTERIOR:
      weight = 2.0 * SPH_PI;
      break;
    default:
      return 0;
  }
  if (m != NULL)
    for (int i = 0; i < 3; i++) m[i] += weight * f.nu[i];
  return 1;
}

int sph_gamma3d_check(const struct sph_wall_element *e) {
  for (int i = 0; i < 3; i++)
    if (!isfinite(e->x[0][i]) || !isfinite(e->x[1][i]) || !isfinite(e->x[2][i]) ||
        !isfinite(e->normal[i]))
      return -1;
  double d1[3], d2[3], c[3];
  for (int i = 0; i < 3; i++) {
    d1[i] = e->x[1][i] - e->x[0][i];
    d2[i] = e->x[2][i] - e->x[0][i];
  }
  cross3(d1, d2, c);
  const double area2 = sqrt(dot3(c, c));
  const double nn = sqrt(dot3(e->normal, e->normal));
  if (!isfinite(area2) || !isfinite(nn) || area2 <= 0.0 || fabs(nn - 1.0) > 1e-6) return -1;
  const double l1 = sqrt(dot3(d1, d1)), l2 = sqrt(dot3(d2, d2));
  if (area2 <= 1e-12 * l1 * l2) return -1; /* collinear vertices */
  return (fabs(dot3(d1, e->normal)) <= 1e-6 * l1 && fabs(dot3(d2, e->normal)) <= 1e-6 * l2) ? 0
                                                                                            : -1;
}
