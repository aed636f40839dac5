/* Local orthonormal frame (n, t1, t2) of a boundary segment, J §III. */
#include <math.h>

#include "sabre/riemann.h"

int rmn_frame_from_normal(int dim, const double *normal, struct rmn_frame *frame) {
  if (dim < 1 || dim > 3 || !normal || !frame) return RMN_EINVAL;
  double norm2 = 0.0;
  for (int i = 0; i < dim; ++i) {
    if (!isfinite(normal[i])) return RMN_EINVAL;
    norm2 += normal[i] * normal[i];
  }
  if (!(norm2 > 0.0)) return RMN_EINVAL;
  struct rmn_frame f = {.dim = dim};
  double inv = 1.0 / sqrt(norm2);
  for (int i = 0; i < dim; ++i) f.n[i] = normal[i] * inv;
  if (dim == 2) {
    f.t1[0] = -f.n[1];
    f.t1[1] = f.n[0];
  } else if (dim == 3) {
    /* Project the coordinate axis least aligned with n onto the plane orthogonal to n. */
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (fabs(f.n[i]) < fabs(f.n[k])) k = i;
    double e[3] = {0.0, 0.0, 0.0};
    e[k] = 1.0;
    double dot = f.n[k];
    double t[3], tn = 0.0;
    for (int i = 0; i < 3; ++i) {
      t[i] = e[i] - dot * f.n[i];
      tn += t[i] * t[i];
    }
    tn = 1.0 / sqrt(tn);
    for (int i = 0; i < 3; ++i) f.t1[i] = t[i] * tn;
    f.t2[0] = f.n[1] * f.t1[2] - f.n[2] * f.t1[1];
    f.t2[1] = f.n[2] * f.t1[0] - f.n[0] * f.t1[2];
    f.t2[2] = f.n[0] * f.t1[1] - f.n[1] * f.t1[0];
  }
  *frame = f;
  return RMN_SUCCESS;
}

void rmn_frame_to_local(const struct rmn_frame *frame, const double *v, double *local) {
  const int d = frame->dim;
  const double *axes[3] = {frame->n, frame->t1, frame->t2};
  double out[3];
  for (int a = 0; a < d; ++a) {
    double s = 0.0;
    for (int i = 0; i < d; ++i) s += axes[a][i] * v[i];
    out[a] = s;
  }
  for (int a = 0; a < d; ++a) local[a] = out[a];
}

void rmn_frame_to_global(const struct rmn_frame *frame, const double *local, double *v) {
  const int d = frame->dim;
  const double *axes[3] = {frame->n, frame->t1, frame->t2};
  double out[3] = {0.0, 0.0, 0.0};
  for (int a = 0; a < d; ++a)
    for (int i = 0; i < d; ++i) out[i] += local[a] * axes[a][i];
  for (int i = 0; i < d; ++i) v[i] = out[i];
}
