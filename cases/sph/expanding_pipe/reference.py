#!/usr/bin/python3
"""Reference head for the expanding pipe: the steady incompressible Navier-Stokes flow of the same
problem (2D plates, R1, L1, R2, L2, nu and the inlet's Poiseuille profile of case.yaml; no-slip
walls, p = 0 and du/dx = dv/dx = 0 on the outlet), on a uniform MAC grid of spacing h (R1/h cells
across pipe 1) with central differences, solved by Picard (Oseen) iterations, each a sparse direct
solve (scipy's SuperLU), until the velocity changes by less than 1e-10 U1. The head is
H = Û²/2g + P/g (P the kinematic pressure, Û² and P the means over the cells of a column), as
plot.py makes it from the SPH.

usage: reference.py [H ...]
  Solves at each spacing H (default 0.0025 m = R1/52), prints the fits of plot.py (gradients of
  both pipes, loss) for each, and writes the last one's head to reference_head.csv next to this
  script (x [m], H [m]). Measured (the reentrant corner makes it first order in the loss):
    h = 0.01   loss 5.4285e-07 m, gradients -9.6997e-07 and -1.2060e-07
    h = 0.005  loss 5.4559e-07 m, gradients -9.7181e-07 and -1.2059e-07
    h = 0.0025 loss 5.4682e-07 m, gradients -9.7227e-07 and -1.2058e-07 (J40 5.4917e-07)
  h = 0.0025 takes about 3 minutes. Needs python3-scipy (not installed by `make deps`: the check
  reads the committed reference_head.csv).
"""
import os
import sys
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

NU, G = 3.19e-5, 9.81
R1, R2 = 0.13, 0.26
L1, L2 = 3 * R1, 4 * R2
U1 = 0.0025274


def solve(h, tol=1e-10, verbose=True):
    """Cell-centre x, y, u, kinematic p and the fluid mask of the solution at spacing h."""
    X0, Y0 = -L1, -R2
    nx, ny = int(round((L1 + L2) / h)), int(round(2 * R2 / h))
    xc = X0 + (np.arange(nx) + 0.5) * h
    yc = Y0 + (np.arange(ny) + 0.5) * h
    XC, YC = np.meshgrid(xc, yc, indexing="ij")
    fluid = (XC > 0) | (np.abs(YC) < R1)

    def fl(i, j):  # fluid, with the column beyond the outlet a ghost copy of the last one
        if j < 0 or j >= ny or i < 0:
            return False
        if i >= nx:
            return bool(fluid[nx - 1, j])
        return bool(fluid[i, j])

    # u faces (iu, j), iu = 0..nx: kinds 1 unknown, 2 inlet, 3 wall (0), 0 none
    ukind = np.zeros((nx + 1, ny), int)
    for iu in range(nx + 1):
        for j in range(ny):
            a, b = fl(iu - 1, j), fl(iu, j)
            if iu == 0:
                ukind[iu, j] = 2 if b else 0
            elif a and b:
                ukind[iu, j] = 1
            elif a or b:
                ukind[iu, j] = 3
    vkind = np.zeros((nx, ny + 1), int)
    for i in range(nx):
        for jv in range(ny + 1):
            a, b = fl(i, jv - 1), fl(i, jv)
            vkind[i, jv] = 1 if (a and b) else (3 if (a or b) else 0)
    uid = -np.ones_like(ukind)
    vid = -np.ones_like(vkind)
    pid = -np.ones((nx, ny), int)
    n = 0
    for iu, j in zip(*np.nonzero(ukind == 1)):
        uid[iu, j] = n
        n += 1
    for i, jv in zip(*np.nonzero(vkind == 1)):
        vid[i, jv] = n
        n += 1
    for i, j in zip(*np.nonzero(fluid)):
        pid[i, j] = n
        n += 1
    uin = np.where(ukind[0] == 2, U1 * (1 - (yc / R1) ** 2), 0.0)

    def uval(sol, iu, j):
        if iu > nx or j < 0 or j >= ny:
            return 0.0
        k = ukind[iu, j]
        return sol[uid[iu, j]] if k == 1 else (uin[j] if k == 2 else 0.0)

    def vval(sol, i, jv):
        if i >= nx:
            i = nx - 1
        if i < 0 or jv < 0 or jv > ny:
            return 0.0
        return sol[vid[i, jv]] if vkind[i, jv] == 1 else 0.0

    sol = np.zeros(n)
    for iu, j in zip(*np.nonzero(ukind == 1)):  # start: the pipes' Poiseuille flows
        x = X0 + iu * h
        r = R1 if x <= 0 else R2
        sol[uid[iu, j]] = U1 * R1 / r * max(0.0, 1 - (yc[j] / r) ** 2)
    inv_h2, inv_2h, inv_h = 1 / h**2, 1 / (2 * h), 1 / h
    for it in range(100):
        rows, cols, vals, rhs = [], [], [], np.zeros(n)

        def add(r, c, v):
            rows.append(r)
            cols.append(c)
            vals.append(v)

        # u momentum
        for iu, j in zip(*np.nonzero(ukind == 1)):
            r = uid[iu, j]
            Ub = sol[r]
            Vb = 0.25 * (vval(sol, iu - 1, j) + vval(sol, iu - 1, j + 1) + vval(sol, iu, j) +
                         vval(sol, iu, j + 1))
            diag = 4 * NU * inv_h2
            # neighbours: (face, conv coefficient)
            nb = [((iu + 1, j), Ub * inv_2h), ((iu - 1, j), -Ub * inv_2h),
                  ((iu, j + 1), Vb * inv_2h), ((iu, j - 1), -Vb * inv_2h)]
            for (fi, fj), cc in nb:
                coef = cc - NU * inv_h2
                if fi > nx:  # beyond the outlet: du/dx = 0
                    diag += coef
                elif fj < 0 or fj >= ny or ukind[fi, fj] == 0:  # wall half a cell away
                    diag -= coef
                elif ukind[fi, fj] == 1:
                    add(r, uid[fi, fj], coef)
                else:
                    rhs[r] -= coef * uval(sol, fi, fj)
            add(r, r, diag)
            add(r, pid[iu - 1, j], -inv_h)
            if iu < nx:
                add(r, pid[iu, j], inv_h)
            else:  # p = 0 on the outlet face: ghost p = -p_last
                add(r, pid[iu - 1, j], -inv_h)
        # v momentum
        for i, jv in zip(*np.nonzero(vkind == 1)):
            r = vid[i, jv]
            Vb = sol[r]
            Ub = 0.25 * (uval(sol, i, jv - 1) + uval(sol, i + 1, jv - 1) + uval(sol, i, jv) +
                         uval(sol, i + 1, jv))
            diag = 4 * NU * inv_h2
            nb = [((i + 1, jv), Ub * inv_2h), ((i - 1, jv), -Ub * inv_2h),
                  ((i, jv + 1), Vb * inv_2h), ((i, jv - 1), -Vb * inv_2h)]
            for (fi, fj), cc in nb:
                coef = cc - NU * inv_h2
                if fi >= nx:  # beyond the outlet: dv/dx = 0
                    diag += coef
                elif fi < 0 or vkind[fi, fj] == 0:  # inlet (v = 0) or wall half a cell away
                    diag -= coef
                elif vkind[fi, fj] == 1:
                    add(r, vid[fi, fj], coef)
                # kind 3: a wall face, v = 0
            add(r, r, diag)
            add(r, pid[i, jv], inv_h)
            add(r, pid[i, jv - 1], -inv_h)
        # continuity
        for i, j in zip(*np.nonzero(fluid)):
            r = pid[i, j]
            for (fi, fj), s in (((i + 1, j), 1), ((i, j), -1)):
                if ukind[fi, fj] == 1:
                    add(r, uid[fi, fj], s * inv_h)
                else:
                    rhs[r] -= s * inv_h * uval(sol, fi, fj)
            for (fi, fj), s in (((i, j + 1), 1), ((i, j), -1)):
                if vkind[fi, fj] == 1:
                    add(r, vid[fi, fj], s * inv_h)
        A = sp.csc_matrix((vals, (rows, cols)), shape=(n, n))
        new = spla.splu(A).solve(rhs)
        du = np.max(np.abs(new - sol)[: np.count_nonzero(ukind == 1)])
        sol = new
        if verbose:
            print("h %g iteration %d max|du| %.3e" % (h, it, du), file=sys.stderr)
        if du < tol * U1:
            break
    # cell-centre fields
    p = np.full((nx, ny), np.nan)
    u = np.full((nx, ny), np.nan)
    for i, j in zip(*np.nonzero(fluid)):
        p[i, j] = sol[pid[i, j]]
        u[i, j] = 0.5 * (uval(sol, i, j) + uval(sol, i + 1, j))
    return xc, yc, u, p, fluid


def head(xc, u, p, fluid):
    """H = Û²/2g + P/g (p kinematic), cross-section means of the fluid cells."""
    H = np.empty(len(xc))
    for i in range(len(xc)):
        m = fluid[i]
        H[i] = np.mean(u[i, m] ** 2) / (2 * G) + np.mean(p[i, m]) / G
    return H


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    spacings = [float(a) for a in sys.argv[1:]] or [0.0025]
    for h in spacings:
        xc, _, u, p, fluid = solve(h)
        H = head(xc, u, p, fluid)
        m1 = (xc > -0.30) & (xc < -0.08)
        m2 = (xc > 0.60) & (xc < 0.95)
        a1, a2 = np.polyfit(xc[m1], H[m1], 1), np.polyfit(xc[m2], H[m2], 1)
        print("h = %g m: loss %.4e m, gradients %.4e and %.4e (J37 %.4e and %.4e)"
              % (h, np.polyval(a1, -L1) - np.polyval(a2, L2), a1[0], a2[0],
                 -2 * NU * U1 / (G * R1**2), -NU * U1 / (G * R2**2)))
    np.savetxt(os.path.join(here, "reference_head.csv"), np.c_[xc, H], delimiter=",",
               header="x,H", comments="", fmt="%.6f,%.10e")


if __name__ == "__main__":
    main()
