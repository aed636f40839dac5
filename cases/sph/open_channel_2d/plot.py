#!/usr/bin/python3
"""Open channel with a free surface (2D): the water level at three gauges, the mass in the channel
(fluid and vertices), the particle count and the volume fluxes through the inlet and the outlet,
over the run, against the uniform flow that the case starts from and should keep.

usage: plot.py OUTPUT_DIR [--check]
  Writes OUTPUT_DIR/open_channel_2d.png and prints the figures of README.md; --check: exit status
  1 unless every criterion of README.md holds (over the last half of the committed end time).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import (Checks, mass_balance, read_csv, beyond_flux_rate, time_mean,  # noqa: E402
                          used_dr)

DEPTH = 0.21        # the initial free surface (top row + dr/2) and the outlet's depth [m]
U = 0.5             # inflow speed [m/s]
T_END = 100.0       # the committed end time [s]
GAUGES = (0.25, 0.5, 0.75)


def main():
    out = next((a for a in sys.argv[1:] if not a.startswith("--")), None)
    if not out:
        sys.exit(__doc__)
    dr = used_dr(out)
    d = read_csv(os.path.join(out, "diagnostics.csv"))
    g = read_csv(os.path.join(out, "probes.csv"))
    fin = read_csv(os.path.join(out, "open_inlet.csv"))
    fout = read_csv(os.path.join(out, "open_outlet.csv"))
    t, mass, count = d["time"], d["mass"], d["particles"]
    t_end, half = float(t[-1]), 0.5 * T_END
    late = t >= half
    print("dr = %g m: run to t = %g s (committed end %g s)" % (dr, t_end, T_END))
    levels = [g["eta%d" % i] for i in range(len(GAUGES))]
    dev = [float(np.max(np.abs(lv[g["time"] >= half] - DEPTH))) if np.any(g["time"] >= half)
           else float("nan") for lv in levels]
    dev_all = [float(np.max(np.abs(lv - DEPTH))) for lv in levels]
    print("  water level at x = %s m: largest |eta - d| over the last half %s dr (whole run %s dr)"
          % (", ".join("%g" % x for x in GAUGES), ", ".join("%.2f" % (v / dr) for v in dev),
             ", ".join("%.2f" % (v / dr) for v in dev_all)))
    mdev = float(np.max(np.abs(mass[late] / mass[0] - 1))) if np.any(late) else float("nan")
    cdev = float(np.max(np.abs(count[late] / count[0] - 1))) if np.any(late) else float("nan")
    print("  mass in the channel: largest deviation over the last half %.2f %% (whole run %.2f %%)"
          % (100 * mdev, 100 * float(np.max(np.abs(mass / mass[0] - 1)))))
    print("  fluid particles: %d at the start, %d-%d over the run; largest deviation over the last "
          "half %.2f %%" % (count[0], count.min(), count.max(), 100 * cdev))
    qin, qout = time_mean(fin["time"], fin["volume_flux"], half), \
        -time_mean(fout["time"], fout["volume_flux"], half)
    # the particles carry U (d - dr/2): the floor's vertex layer stands for the fluid below dr/2
    # (the corner rule gives its flux to no vertex, docs/sph-solver.md §10)
    print("  volume flux over the last half: in %.5f m^2/s, out %.5f (U (d - dr/2) = %.5f)"
          % (qin, qout, U * (DEPTH - 0.5 * dr)))
    # mass rates: the outlet's flux of J(15) plus the mass its deleted particles took out beyond
    # what its vertices took back (mass_released) less what its vertices did not take
    # (mass_withheld, docs/sph-solver.md §10)
    min_ = time_mean(fin["time"], fin["mass_flux"], half)
    released = beyond_flux_rate(fout, half)
    mout = -time_mean(fout["time"], fout["mass_flux"], half) + released
    print("  mass flux over the last half: in %.4f kg/(m s), out %.4f (of which released - withheld %.4f)"
          % (min_, mout, released))

    fig, ax = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    for x, lv in zip(GAUGES, levels):
        ax[0].plot(g["time"], lv, lw=0.8, label="x = %g m" % x)
    ax[0].axhspan(DEPTH - dr, DEPTH + dr, color="0.85", label="d ± dr")
    ax[0].set_ylabel("water level [m]")
    ax[0].legend(fontsize=8)
    ax[1].plot(t, mass / mass[0] - 1, "k-", lw=0.8, label="mass (fluid and vertices)")
    ax[1].plot(t, count / count[0] - 1, "b-", lw=0.8, label="fluid particles")
    ax[1].axhspan(-0.01, 0.01, color="0.85")
    ax[1].set_ylabel("relative change")
    ax[1].legend(fontsize=8)
    ax[2].plot(fin["time"], fin["volume_flux"], lw=0.8, label="inlet")
    ax[2].plot(fout["time"], -fout["volume_flux"], lw=0.8, label="outlet")
    ax[2].axhline(U * (DEPTH - 0.5 * dr), color="k", lw=0.6, ls="--", label="U (d - dr/2)")
    ax[2].set_ylabel("volume flux [m²/s]")
    ax[2].set_xlabel("t [s]")
    ax[2].legend(fontsize=8)
    ax[0].set_title("Open channel, dr = %g m: uniform flow at %g m/s, depth %g m (run to %g s)"
                    % (dr, U, DEPTH, t_end))
    fig.tight_layout()
    fig.savefig(os.path.join(out, "open_channel_2d.png"), dpi=100)

    if "--check" not in sys.argv:
        return
    checks = Checks()
    checks.require(t_end >= T_END - 1e-9, "the run reaches t = %g s (50 transit times)" % T_END)
    checks.require(max(dev) <= dr, "water level within dr of d at every gauge over the last half")
    checks.require(mdev <= 0.01, "mass in the channel within 1 % over the last half")
    checks.require(cdev <= 0.02, "particle count within 2 % over the last half")
    checks.require(abs(mout / min_ - 1) <= 0.01, "mean outflow within 1 % of the inflow (mass)")
    balance = mass_balance(out)
    checks.require(balance <= 1e-12, "mass - entered + released constant to 1e-12 (%.1e)" % balance)
    checks.done()


if __name__ == "__main__":
    main()
