#!/usr/bin/python3
"""SPHERIC test 2, dam break against a box obstacle (Kleefsman et al. 2005): water heights H1-H4
and pressures P1-P8 over time against the measurements, and the criteria of README.md.

usage: plot.py OUTPUT_DIR [--check]
  Writes OUTPUT_DIR/dam_break_3d_obstacle.png and prints the figures quoted in README.md.
  --check: exit status 1 unless every criterion of README.md holds.

Reads probes.csv (columns p0..p7 = P1..P8; level0..level3 = H1..H4, the kernel-sum levels, with
eta0..eta3, the highest particle + dr/2, dashed; a gauge without water is NaN and drawn as 0), diagnostics.csv, used_case.yaml and the first fluid output (the column's free face and
height, so that --set geometry.dr=... needs no edit here). The measurements are the samples of
kleefsman2005_samples.csv (see its header for where they come from).

Impact: the first time P1 exceeds 1 kPa. The column's free face (x_c, the smallest x of a fluid
particle minus dr/2) is L = x_c - 0.8245 m from the obstacle's upstream face. Ritter's ideal front
(shallow water, frictionless) runs at 2 sqrt(gH) from t = 0 and is an upper bound on the speed of
a real front, which starts from rest and is slowed at its tip: the impact cannot come before
L / (2 sqrt(gH)). A front slower on average than half of Ritter's speed would be wrong too (the
bound that cases/sph/dam_break_3d checks over its last 0.1 s): the impact must come before
2 L / (2 sqrt(gH)). The measured impact (0.393 s, L = 1.1675 m, H = 0.55 m) is at 0.64 x Ritter's
speed on average.
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

G = 9.81            # as in case.yaml
RHO0 = 1000.0       # as in case.yaml
X_FACE = 0.8245     # the obstacle's upstream face [m] (case.yaml, make_tank_stl.py)
T_IMPACT_EXP = 0.393  # first P1 > 0.5 kPa in the measurements (kleefsman2005_samples.csv)
P_IMPACT = 1000.0   # [Pa] P1 above this marks the impact
HERE = os.path.dirname(os.path.abspath(__file__))


def measurements():
    rows = [line for line in open(os.path.join(HERE, "kleefsman2005_samples.csv"))
            if not line.startswith("#")]
    names = rows[0].strip().split(",")
    data = np.array([[float(v) for v in r.split(",")] for r in rows[1:]])
    return {n: data[:, i] for i, n in enumerate(names)}


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    dr = used_dr(out)
    pr = read_csv(os.path.join(out, "probes.csv"))
    d = read_csv(os.path.join(out, "diagnostics.csv"))
    exp = measurements()
    x0 = read_vtu(read_pvd(os.path.join(out, "particles.pvd"), part="0")[0][1])["points"]
    x_col, h_col = x0[:, 0].min() - 0.5 * dr, x0[:, 2].max() + 0.5 * dr
    dist = x_col - X_FACE
    u_ritter = 2.0 * math.sqrt(G * h_col)
    t = pr["time"]
    p1 = pr["p0"]

    fig, axes = plt.subplots(2, 4, figsize=(16, 7), sharex=True)
    for i in range(4):
        ax = axes[0, i]
        if "level%d" % i in pr:  # the kernel-sum level (docs/sph-solver.md §6): spray does not count
            ax.plot(t, np.nan_to_num(pr["level%d" % i], nan=0.0), "b-", lw=1,
                    label="SPH, dr = %g m: level" % dr)
        ax.plot(t, np.nan_to_num(pr["eta%d" % i], nan=0.0), "c--", lw=0.7,
                label="SPH: top particle + dr/2")
        ax.plot(exp["t"], exp["H%d" % (i + 1)], "ro", ms=3, label="measured (samples)")
        ax.set_title("H%d, x = %s m" % (i + 1, ("0.496", "0.992", "1.488", "2.638")[i]), fontsize=10)
        ax.set_ylim(0, 0.65)
        ax.set_ylabel("water height [m]")
    axes[0, 0].legend(fontsize=8)
    for i, k in enumerate((0, 2, 4, 6)):
        ax = axes[1, i]
        ax.plot(t, pr["p%d" % k] / 1000.0, "b-", lw=1, label="SPH (0.01 m off the wall)")
        if "P%d" % (k + 1) in exp:
            ax.plot(exp["t"], exp["P%d" % (k + 1)] / 1000.0, "ro", ms=3, label="measured (samples)")
        ax.axvline(T_IMPACT_EXP, color="k", ls=":", lw=1, label="measured impact on P1")
        ax.set_title("P%d" % (k + 1), fontsize=10)
        ax.set_ylabel("pressure [kPa]")
        ax.set_xlabel("t [s]")
    axes[1, 0].legend(fontsize=8)
    axes[1, 0].set_xlim(0, max(t[-1], 1.0))   # the run's span (the measurements go to 7.4 s)
    fig.suptitle("SPHERIC test 2 (Kleefsman et al. 2005), dr = %g m: column %.3f m long, "
                 "H = %.3f m" % (dr, 3.22 - x_col, h_col), fontsize=11)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "dam_break_3d_obstacle.png"), dpi=110)
    print("wrote %s/dam_break_3d_obstacle.png" % out)

    hit = np.nonzero(np.nan_to_num(p1, nan=0.0) > P_IMPACT)[0]
    t_imp = t[hit[0]] if len(hit) else math.inf
    t_min, t_max = dist / u_ritter, 2.0 * dist / u_ritter
    window = (t >= t_imp) & (t <= t_imp + 0.1)
    p1_peak = np.nanmax(p1[window]) if window.any() else math.nan
    u_mean = dist / t_imp if len(hit) else math.nan
    p_stag = 0.5 * RHO0 * u_mean ** 2
    dm = np.max(np.abs(d["mass"] - d["mass"][0])) / d["mass"][0]
    print("t = %.3f s; column free face %.4f m, H = %.3f m, %.4f m from the obstacle; %d fluid "
          "particles (%d..%d); mass drift %.1e" % (t[-1], x_col, h_col, dist, d["particles"][-1],
                                                   d["particles"].min(), d["particles"].max(), dm))
    print("impact on P1 (> %.0f Pa) at %.3f s (measured %.3f s); Ritter's bound %.3f s, half "
          "Ritter's speed %.3f s; mean front speed %.2f m/s = %.2f x 2 sqrt(gH)"
          % (P_IMPACT, t_imp, T_IMPACT_EXP, t_min, t_max, u_mean, u_mean / u_ritter))
    print("P1 peak within 0.1 s of the impact %.0f Pa (measured 11239 Pa at 0.415 s); rho0 u^2/2 "
          "of the mean front speed %.0f Pa" % (p1_peak, p_stag))
    if "--check" not in sys.argv:
        return
    checks = Checks()
    checks.require(dm <= 1e-12, "total mass constant to 1e-12")
    checks.require(d["particles"].min() == d["particles"].max() == d["particles"][0], "no particle lost")
    checks.require(t_min <= t_imp <= t_max,
            "impact on P1 between L/(2 sqrt(gH)) (Ritter's ideal front) and twice that")
    checks.require(p_stag <= p1_peak <= 10 * p_stag,
            "P1 rises at the impact: its peak within 0.1 s between 1 and 10 x rho0 u^2/2 of the "
            "mean front speed u = L / t_impact")
    checks.done()


if __name__ == "__main__":
    main()
