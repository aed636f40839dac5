"""The mean zeroth-order defect that a through-flow sees next to an inlet and an outlet of a 2D
channel (docs/sph-solver.md §10, "The pressure level with M(37)"): a model, independent of the
solver, of the phase average of D_a = sum_b V_b grad w_ab - grad gamma_a over one period of the
rows moving through the open face.

The layout is SABRE's: a channel between walls at y = 0 and y = H = 11 dr, the open face at x = 0,
fluid rows dr apart with the first row dr from each wall, wall vertices dr apart with the volume
phi dr^2 of their wall layer (phi = 1/2, or the first argument), open vertices at the face with the
same wall volume plus the mass that has entered (inlet: delta m = theta m_ref, the rows at
(phi + 1/2 + theta + k) dr, a particle created at (phi + 1/2) dr when delta m reaches m_ref) or left (outlet: delta m = -theta m_ref, the rows at
-(k + 1 - theta) dr, the row at the face giving its mass back when it crosses); corners keep their
wall volume. grad gamma_a is the exact boundary integral sum_s int_s w n_in dl over the face and the
two walls (Gauss-Legendre, 8 panels of 64 points per element), the Wendland C2 kernel with
h = 2 dr. The entered or left mass is counted at the vertex ("at_v", J 14 as it is), at the centre
of the layer it stands for ("layer": r_v + (phi + delta m / (2 m_ref)) dr n), or not at all
("none").

Printed per representation: the integral over the first five rows of G_x = 2 D_x (the pressure
gradient of a constant 1 with M(37)), in the row next to a wall (lane 1), the second (lane 2) and
the middle of the channel (lane 5); a pressure level p pushes the fluid with -p G / rho, so that
p times the integral is the pressure difference it needs. Runs in a few seconds:

    /usr/bin/python3 docs/figures/open_phase.py [PHI]
"""
import sys

import numpy as np

DR = 0.02
H_SMOOTH = 2 * DR
PHI = float(sys.argv[1]) if len(sys.argv) > 1 else 0.5
NY = 11
HEIGHT = NY * DR
A_KERNEL = 7.0 / (4 * np.pi * H_SMOOTH * H_SMOOTH)
GL_X, GL_W = np.polynomial.legendre.leggauss(64)


def w(r):
    q = r / H_SMOOTH
    return np.where(q < 2, A_KERNEL * (1 - q / 2) ** 4 * (2 * q + 1), 0.0)


def dwdr_over_r(r):
    q = r / H_SMOOTH
    return np.where(q < 2, A_KERNEL * (-5.0 / H_SMOOTH ** 2) * (1 - q / 2) ** 3, 0.0)


def element_integral(p, a, b, n_in):
    """int_a^b w(|p - r'|) dl' times the element's unit normal into the fluid."""
    length = np.linalg.norm(b - a)
    t = (b - a) / length
    total = 0.0
    for k in range(8):
        s0, s1 = k * length / 8, (k + 1) * length / 8
        s = 0.5 * (s1 - s0) * GL_X + 0.5 * (s1 + s0)
        pts = a[None, :] + s[:, None] * t[None, :]
        total += np.sum(0.5 * (s1 - s0) * GL_W * w(np.linalg.norm(p[None, :] - pts, axis=1)))
    return total * n_in


def grad_gamma(p, side):
    """The face x = 0 (fluid on side +1 or -1) and the two walls, 3h beyond the support."""
    x0, x1 = (0.0, 3 * H_SMOOTH) if side > 0 else (-3 * H_SMOOTH, 0.0)
    g = element_integral(p, np.array([0.0, 0.0]), np.array([0.0, HEIGHT]), np.array([side, 0.0]))
    g = g + element_integral(p, np.array([x0, 0.0]), np.array([x1, 0.0]), np.array([0.0, 1.0]))
    return g + element_integral(p, np.array([x0, HEIGHT]), np.array([x1, HEIGHT]),
                                np.array([0.0, -1.0]))


def layout(side, theta, where):
    nrow = 14
    if side > 0:
        rows = [(PHI + 0.5 + theta + k) * DR for k in range(nrow)]
    else:
        rows = [-(k + 1 - theta) * DR for k in range(nrow)]
    pts = [(x, j * DR) for x in rows for j in range(1, NY)]
    vol = [DR * DR] * len(pts)
    for i in range(1, nrow + 4):
        pts += [(side * i * DR, 0.0), (side * i * DR, HEIGHT)]
        vol += [PHI * DR * DR] * 2
    dm = theta if side > 0 else -theta  # in particle masses
    for j in range(NY + 1):
        pts.append((0.0, j * DR))
        vol.append(PHI * DR * DR)
        if 0 < j < NY and where != "none":
            off = 0.0 if where == "at_v" else PHI + 0.5 * dm
            pts.append((side * off * DR, j * DR))
            vol.append(dm * DR * DR)
    return np.array(pts), np.array(vol), rows


def mean_defect(side, where, nphase=24, nrows=5):
    acc = {}
    for theta in (np.arange(nphase) + 0.5) / nphase:
        pts, vol, rows = layout(side, theta, where)
        for k in range(nrows):
            for j in (1, 2, 5):
                p = np.array([rows[k], j * DR])
                d = p[None, :] - pts
                f = dwdr_over_r(np.linalg.norm(d, axis=1))
                s = np.sum((vol * f)[:, None] * d, axis=0)
                acc.setdefault((k, j), []).append(s - grad_gamma(p, side))
    return {key: np.mean(v, axis=0) for key, v in acc.items()}


def main():
    for side, name in ((1, "inlet "), (-1, "outlet")):
        for where in ("at_v", "layer", "none"):
            r = mean_defect(side, where)
            cols = " ".join("lane %d %+.3f" % (j, sum(2 * r[(k, j)][0] * DR for k in range(5)))
                            for j in (1, 2, 5))
            print("%s %-5s  integral of G_x over 5 rows: %s" % (name, where, cols))


if __name__ == "__main__":
    main()
