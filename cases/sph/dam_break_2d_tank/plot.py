#!/usr/bin/python3
"""2D dam break in a closed tank: front position over time against Ritter's ideal front, and how
far the run got.

usage: plot.py OUTPUT_DIR [--check]
  Writes OUTPUT_DIR/dam_break_2d_tank.png and prints the figures quoted in README.md.
  --check: exit status 1 unless every criterion of README.md holds.

The column (a long, H high; both read from the first output: last column and top row plus dr/2)
collapses; the front is the largest x of a fluid particle plus dr/2. Ritter's solution of the
shallow-water equations moves it at 2 sqrt(g H) from t = 0 (an upper bound: the real front
starts from rest and is slowed at its tip) until it reaches the far wall at x = L.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import Checks, read_csv, read_pvd, read_vtu, used_dr  # noqa: E402

G = 9.81      # as in case.yaml
L = 1.61      # tank length [m]
T_END = 8.0   # the run's end in units of sqrt(H/g), H = 0.3 m as in case.yaml


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    dr = used_dr(out)
    fluid = read_pvd(os.path.join(out, "particles.pvd"), part="0")
    t = np.array([ti for ti, _ in fluid])
    xf = np.array([read_vtu(f)["points"][:, 0].max() + 0.5 * dr for _, f in fluid])
    x0 = read_vtu(fluid[0][1])["points"]
    a_col, h_col = x0[:, 0].max() + 0.5 * dr, x0[:, 1].max() + 0.5 * dr
    u_ritter = 2.0 * math.sqrt(G * h_col)
    d = read_csv(os.path.join(out, "diagnostics.csv"))
    scale = math.sqrt(G / 0.3)
    t_reached = d["time"][-1] * scale
    dm = abs(d["mass"] / d["mass"][0] - 1).max()
    # front speed before the wall: from the first output to the last one with x_f < L - 2 dr
    free = xf < L - 2 * dr
    k = np.nonzero(free)[0][-1] if free.any() else 0
    speed = (xf[k] - xf[0]) / (t[k] - t[0]) if k > 0 else float("nan")

    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    ax.plot(t * scale, xf, "o-", ms=3, label="SPH, front: max x + dr/2")
    tr = np.linspace(0, (L - a_col) / u_ritter, 20)
    ax.plot(tr * scale, a_col + u_ritter * tr, "k--", label="Ritter: a + 2 sqrt(gH) t")
    ax.axhline(L, color="0.5", lw=0.8)
    ax.axvline(T_END, color="r", lw=0.8, ls=":", label="end of the run asked for")
    ax.set_xlabel(r"$t\,\sqrt{g/H}$ (H = 0.3 m)")
    ax.set_ylabel("front x [m]")
    ax.set_title("2D dam break, dr = %g m: reached t sqrt(g/H) = %.2f" % (dr, t_reached))
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "dam_break_2d_tank.png"), dpi=100)
    print("a = %.3f m, H = %.3f m, dr = %g m; reached t = %.4f s = %.2f sqrt(H/g) of %.1f; "
          "particles %d..%d; mass drift %.1e; front speed before the wall %.2f m/s = %.2f x "
          "Ritter's %.2f m/s"
          % (a_col, h_col, dr, d["time"][-1], t_reached, T_END, d["particles"].min(),
             d["particles"].max(), dm, speed, speed / u_ritter, u_ritter))
    if "--check" not in sys.argv:
        return
    checks = Checks()
    checks.require(t_reached >= T_END * (1 - 1e-6), "the run reaches t sqrt(g/H) = 8 (no particle lost)")
    checks.require(dm <= 1e-12, "total mass constant to 1e-12")
    checks.require(d["particles"].min() == d["particles"].max(), "particle count constant")
    checks.require(0.5 <= speed / u_ritter <= 1.0, "front speed before the wall 0.5-1 x 2 sqrt(gH)")
    checks.done()


if __name__ == "__main__":
    main()
