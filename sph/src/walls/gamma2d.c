/*
 * γ and ∇γ_as in 2D, closed form (docs/sph-gamma.md §4). The segment lies on a line at signed
 * distance δ from a (δ > 0 on the fluid side); τ is the abscissa along it from the foot point of a,
 * in units of h, so q² = δ̂² + τ² with δ̂ = δ/h. After clipping [τ1, τ2] to |τ| ≤ √(4 − δ̂²):
 *   ∇γ_as      = α_2/h ∫ f(q) dτ n_s                                         (S2)
 *   gamma_term = α_2 [ −δ̂ ∫ (q²/2 − 5/8 q⁴ + ... + q⁷/56)/q² dτ + (2/7) sign(δ̂) Δφ ] (G2)
 * with Δφ the angle under which a sees the clipped segment. Every ∫ q^k dτ is closed form:
 * polynomials for even k and the recursion L_k = (τ q^k + k δ̂² L_{k−2})/(k+1) from
 * L_{-1} = asinh(τ/|δ̂|) for odd k.
 */
#include <math.h>

#include "kernel.h"
#include "walls/gamma_impl.h"

struct seg_frame {
  double e[2];  /* unit tangent x1 − x0 */
  double nu[2]; /* unit normal, oriented like the element's normal */
  double len;   /* |x1 − x0| [m] */
  double delta; /* signed distance of a from the line [m] */
  double t[2];  /* abscissae of x0 and x1 from the foot point of a [m] */
};

/* Every quantity is taken relative to the vertex it belongs to, and δ relative to the nearer
 * vertex, so that a point ε away from a vertex gets relative (not absolute) round-off in ε. */
static void frame(const struct sph_wall_element *e, const double *a, struct seg_frame *f) {
  const double dx = e->x[1][0] - e->x[0][0], dy = e->x[1][1] - e->x[0][1];
  f->len = hypot(dx, dy);
  f->e[0] = dx / f->len;
  f->e[1] = dy / f->len;
  const double sgn = (-f->e[1] * e->normal[0] + f->e[0] * e->normal[1]) >= 0.0 ? 1.0 : -1.0;
  f->nu[0] = -sgn * f->e[1];
  f->nu[1] = sgn * f->e[0];
  double r2[2];
  for (int j = 0; j < 2; j++) {
    const double rx = e->x[j][0] - a[0], ry = e->x[j][1] - a[1];
    f->t[j] = rx * f->e[0] + ry * f->e[1];
    r2[j] = rx * rx + ry * ry;
  }
  const int near = r2[1] < r2[0];
  f->delta = (a[0] - e->x[near][0]) * f->nu[0] + (a[1] - e->x[near][1]) * f->nu[1];
}

/* Antiderivatives in τ of q^k, k = 0..5, q² = d2 + τ², d = |δ̂| (d2 = d²). */
struct powers {
  double l0, l1, l2, l3, l4, l5;
};

static void antiderivatives(double d, double d2, double t, struct powers *p) {
  const double q = sqrt(d2 + t * t), q2 = q * q;
  const double t2 = t * t, t3 = t2 * t;
  p->l0 = t;
  p->l2 = d2 * t + t3 / 3.0;
  p->l4 = d2 * d2 * t + 2.0 / 3.0 * d2 * t3 + t3 * t2 / 5.0;
  /* δ̂² asinh(τ/δ̂) → 0 as δ̂ → 0: the δ̂ = 0 branch is the limit, not a special case. */
  p->l1 = 0.5 * (t * q + (d > 0.0 ? d2 * asinh(t / d) : 0.0));
  p->l3 = 0.25 * (t * q2 * q + 3.0 * d2 * p->l1);
  p->l5 = (t * q2 * q2 * q + 5.0 * d2 * p->l3) / 6.0;
}

/*
 * For δ̂ = dh (signed) and the segment [t1, t2] (units of h): *iw = ∫ f dτ and *poly = the
 * polynomial part of G2, both over the part inside the support; *angle = Δφ ≥ 0 of that part.
 * All three are 0 when the segment misses the support.
 */
static void segment_integrals(double dh, double t1, double t2, double *iw, double *poly,
                              double *angle) {
  *iw = *poly = *angle = 0.0;
  const double d = fabs(dh), d2 = dh * dh;
  if (d >= 2.0) return;
  const double tmax = sqrt(4.0 - d2);
  const double ta = fmax(t1, -tmax), tb = fmin(t2, tmax);
  if (!(ta < tb)) return;
  struct powers pa, pb;
  antiderivatives(d, d2, ta, &pa);
  antiderivatives(d, d2, tb, &pb);
  const double l0 = pb.l0 - pa.l0, l2 = pb.l2 - pa.l2, l3 = pb.l3 - pa.l3, l4 = pb.l4 - pa.l4,
               l5 = pb.l5 - pa.l5;
  /* f = 1 − 5/2 q² + 5/2 q³ − 15/16 q⁴ + 1/8 q⁵ */
  *iw = l0 - 2.5 * l2 + 2.5 * l3 - 15.0 / 16.0 * l4 + 0.125 * l5;
  /* g(q)/q² with g = ∫_0^q f u du = q²/2 − 5/8 q⁴ + 1/2 q⁵ − 5/32 q⁶ + 1/56 q⁷ */
  *poly = 0.5 * l0 - 0.625 * l2 + 0.5 * l3 - 5.0 / 32.0 * l4 + l5 / 56.0;
  *angle = atan2(d * (tb - ta), d2 + ta * tb);
}

/* Whether a lies on the closed segment: within SPH_GAMMA_PLANE_TOL·h of its line and within tol of
 * the segment along it. */
static int on_segment(const struct sph_kernel *k, const struct seg_frame *f, double tol) {
  return fabs(f->delta) <= SPH_GAMMA_PLANE_TOL * k->h && f->t[0] <= tol && f->t[1] >= -tol;
}

/* Limit of gamma_term for a on the segment, approaching along m (docs/sph-gamma.md §4): the angle
 * under which a + ε m sees the segment, over 2π. */
static double limit_term(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, const struct seg_frame *f,
                         const double *m) {
  const double tol = SPH_GAMMA_PLANE_TOL * k->h;
  const double mx = m == NULL ? f->nu[0] : m[0], my = m == NULL ? f->nu[1] : m[1];
  const double side = (mx * f->nu[0] + my * f->nu[1]) > 0.0 ? 1.0 : -1.0;
  for (int j = 0; j < 2; j++) {
    if (hypot(a[0] - e->x[j][0], a[1] - e->x[j][1]) <= tol) {
      /* a at an end: angle between −m and the direction to the other end. */
      const double ux = e->x[1 - j][0] - a[0], uy = e->x[1 - j][1] - a[1];
      const double angle = atan2(fabs(-mx * uy + my * ux), -mx * ux - my * uy);
      return side * angle / (2.0 * SPH_PI);
    }
  }
  if (f->t[0] < 0.0 && f->t[1] > 0.0) return 0.5 * side;
  return 0.0;
}

void sph_gamma2d_element(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, const double *m, double *term,
                         double grad[3]) {
  struct seg_frame f;
  frame(e, a, &f);
  /* On the segment the term needs the one-sided limit; anywhere else, even 1e-13 h from its line,
   * the closed form is well conditioned (and 0 exactly on the line off the segment). */
  const int on = on_segment(k, &f, SPH_GAMMA_PLANE_TOL * k->h);
  const double dh = on ? 0.0 : f.delta * k->inv_h;
  const double t1 = f.t[0] * k->inv_h, t2 = f.t[1] * k->inv_h;
  double iw, poly, angle;
  segment_integrals(dh, t1, t2, &iw, &poly, &angle);
  const double gw = SPH_WENDLAND_ALPHA2 * k->inv_h * iw;
  grad[0] = gw * e->normal[0];
  grad[1] = gw * e->normal[1];
  grad[2] = 0.0;
  if (on) {
    *term = limit_term(k, a, e, &f, m);
  } else {
    const double sgn = dh > 0.0 ? 1.0 : (dh < 0.0 ? -1.0 : 0.0);
    *term = SPH_WENDLAND_ALPHA2 * (-dh * poly + 2.0 / 7.0 * sgn * angle);
  }
}

int sph_gamma2d_incident(const struct sph_kernel *k, const double *a,
                         const struct sph_wall_element *e, double tol, double m[3]) {
  struct seg_frame f;
  frame(e, a, &f);
  if (!on_segment(k, &f, tol)) return 0;
  /* Equal weights: at a shared end this is the bisector of the two normals. */
  if (m != NULL) {
    m[0] += f.nu[0];
    m[1] += f.nu[1];
  }
  return 1;
}

int sph_gamma2d_check(const struct sph_wall_element *e) {
  for (int i = 0; i < 2; i++)
    if (!isfinite(e->x[0][i]) || !isfinite(e->x[1][i]) || !isfinite(e->normal[i])) return -1;
  const double dx = e->x[1][0] - e->x[0][0], dy = e->x[1][1] - e->x[0][1];
  const double len = hypot(dx, dy);
  const double nn = hypot(e->normal[0], e->normal[1]);
  if (!isfinite(len) || !isfinite(nn) || len <= 0.0 || fabs(nn - 1.0) > 1e-6) return -1;
  return fabs(dx * e->normal[0] + dy * e->normal[1]) <= 1e-6 * len ? 0 : -1;
}
