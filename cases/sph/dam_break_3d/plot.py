#!/usr/bin/python3
"""3D dam break in an STL box: front position over time against Ritter's ideal dam-break front,
and the energy of the run.

usage: plot.py OUTPUT_DIR [--check]
  Writes OUTPUT_DIR/dam_break_3d.png and prints the figures quoted in README.md.
  --check: exit status 1 unless every criterion of README.md holds.

The column (a = 0.22 m long, H = 0.42 m high, across the tank; a and H are read from the first
output: last column and top layer plus dr/2) collapses as a plane dam break. The
front is the largest x of a fluid particle plus dr/2 (the edge of its cell). Ritter's solution of
the shallow-water equations (frictionless, hydrostatic) moves the front at 2 sqrt(g H) from t = 0:
x_f = a + 2 sqrt(g H) t. It is an upper bound: the real front starts from rest while the column's
vertical motion builds up, and is slowed at its tip.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# the shared readers of sabre-sph output: cases/sph/sabre_output.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import Checks, read_csv, read_pvd, read_vtu, used_dr  # noqa: E402

G = 9.81  # as in case.yaml


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    dr = used_dr(out)
    fluid = read_pvd(os.path.join(out, "particles.pvd"), part="0")
    t, xf = [], []
    for ti, f in fluid:
        x = read_vtu(f)["points"]
        t.append(ti)
        xf.append(x[:, 0].max() + 0.5 * dr)
    t, xf = np.array(t), np.array(xf)
    # the column from the initial particles: a = last column + dr/2, H = top layer + dr/2 (so that
    # --set geometry.dr=... needs no edit here)
    x0 = read_vtu(fluid[0][1])["points"]
    a_col, h_col = x0[:, 0].max() + 0.5 * dr, x0[:, 2].max() + 0.5 * dr
    u_ritter = 2.0 * math.sqrt(G * h_col)
    d = read_csv(os.path.join(out, "diagnostics.csv"))
    energy = d["kinetic"] + d["potential"] + d["internal"]

    fig, (ax, ax_e) = plt.subplots(1, 2, figsize=(11, 4.2))
    ax.plot(t * math.sqrt(2 * G / a_col), xf / a_col, "o-", ms=3, label="SPH, 3D (front: max x + dr/2)")
    tr = np.linspace(0, t[-1], 50)
    ax.plot(tr * math.sqrt(2 * G / a_col), (a_col + u_ritter * tr) / a_col, "k--",
            label="Ritter, ideal front: a + 2 sqrt(gH) t")
    ax.set_xlabel(r"$T = t \sqrt{2g/a}$")
    ax.set_ylabel(r"$Z = x_f / a$")
    ax.set_title("front position, a = %.2f m, H = %.2f m, dr = %g m" % (a_col, h_col, dr),
                 fontsize=10)
    ax.legend(fontsize=8)
    ax_e.plot(d["time"], d["kinetic"], label="kinetic")
    ax_e.plot(d["time"], d["potential"] - d["potential"][0], label="potential - initial")
    ax_e.plot(d["time"], energy - energy[0], label="total - initial")
    ax_e.set_xlabel("t [s]")
    ax_e.set_ylabel("energy [J]")
    ax_e.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "dam_break_3d.png"), dpi=130)
    print("wrote %s/dam_break_3d.png" % out)

    late = t >= t[-1] - 0.1 - 1e-9
    speed = np.polyfit(t[late], xf[late], 1)[0]
    ahead = np.max(xf - (a_col + u_ritter * t))
    dm = np.max(np.abs(d["mass"] - d["mass"][0])) / d["mass"][0]
    gain = np.max(energy - energy[0]) / (d["potential"][0] - d["potential"].min())
    print("column a = %.3f m, H = %.3f m; t = %.3f s, %d fluid particles (%d..%d); front at the end "
          "%.3f m (Z = %.2f, T = %.2f); "
          "front speed over the last 0.1 s %.2f m/s = %.2f x Ritter's %.2f m/s; front - Ritter at "
          "most %+.3f m; largest energy gain %.2f %% of the potential energy released; lost %.1f %% of "
          "it; mass drift %.1e"
          % (a_col, h_col, t[-1], d["particles"][-1], d["particles"].min(), d["particles"].max(), xf[-1], xf[-1] / a_col,
             t[-1] * math.sqrt(2 * G / a_col), speed, speed / u_ritter, u_ritter, ahead, 100 * gain,
             100 * -(energy[-1] - energy[0]) / (d["potential"][0] - d["potential"][-1]), dm))
    if "--check" not in sys.argv:
        return
    checks = Checks()
    checks.require(dm <= 1e-12, "total mass constant to 1e-12")
    checks.require(d["particles"].min() == d["particles"].max() == d["particles"][0], "no particle lost")
    checks.require(ahead <= dr, "the front never runs ahead of Ritter's ideal front (by more than dr)")
    checks.require(0.5 <= speed / u_ritter <= 1.0,
            "front speed over the last 0.1 s is 0.5-1 x Ritter's 2 sqrt(g H)")
    checks.require(gain <= 0.009, "energy gain at most 0.9 % of the potential energy released (the "
            "wall terms are not skew-adjoint, M §3.2)")
    checks.done()


if __name__ == "__main__":
    main()
