#!/usr/bin/python3
"""Still water in an infinite 3D layer (M §7.1, Fig. 8 in 3D): free surface, maximum speed and
the final hydrostatic pressure with the gravity-corrected diffusion (default, local form of M 81)
and without the correction (M 49).
usage: plot.py OUTPUT_DIR [--check]
  OUTPUT_DIR holds the runs of ./check: corrected/ (the case as committed) and uncorrected/.
  Writes OUTPUT_DIR/still_water_3d.png and prints the measured figures; --check: exit status 1
  unless every criterion of README.md holds."""
import math
import os
import sys

# the shared readers of sabre-sph output and still-water analysis: cases/sph/sabre_output.py and
# cases/sph/still_water.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import read_csv  # noqa: E402
from still_water import (Criteria, Tank, check_floor_force, check_rest,  # noqa: E402
                         check_surface, plot_profile, pyplot)

TANK = Tank(rho0=1000.0, c0=19.0, xi=7.0, g=9.81, H=0.3625, dr=0.025)
G, C0, H, DR = TANK.g, TANK.c0, TANK.H, TANK.dr
AREA = 0.3 * 0.3  # the periodic cell's floor [m²]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    crit = Criteria("--check" in sys.argv)

    d, t_end, zs, ps = check_rest(TANK, f"{out}/corrected", 2, crit)
    check_floor_force(TANK, f"{out}/corrected", "floor_fz", AREA, crit)
    (ts, eta), (tu, etau) = check_surface(TANK, out, crit)

    plt = pyplot()
    if plt is None:
        crit.done()
        return
    du = read_csv(f"{out}/uncorrected/diagnostics.csv", lists=True)
    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(15, 4.2))
    for lab, (t, e) in {"gravity-corrected (local)": (ts, eta), "uncorrected M(49)": (tu, etau)}.items():
        ax1.plot([ti * C0 / H for ti in t], [ei / H for ei in e], label=lab)
    ax1.axhspan(1 - 0.5 * DR / H, 1 + 0.5 * DR / H, color="0.9", label="H ± Δr/2")
    ax1.set_xlabel("t c0 / H")
    ax1.set_ylabel("free surface / H (mean of 5 gauges)")
    ax1.legend(fontsize=8)
    for lab, dd in {"gravity-corrected (local)": d, "uncorrected M(49)": du}.items():
        ax2.semilogy([ti / math.sqrt(H / G) for ti in dd["time"]],
                     [max(u, 1e-9) / math.sqrt(G * H) for u in dd["max_speed"]], label=lab)
    ax2.axhline(0.01, color="k", ls="--", lw=1, label="1 %")
    ax2.set_ylim(1e-5, 1)
    ax2.set_xlabel("t / sqrt(H/g)")
    ax2.set_ylabel("max|u| / sqrt(gH)")
    ax2.legend(fontsize=8)
    plot_profile(ax3, TANK, zs, ps, t_end, [i * H / 100 for i in range(101)], "z [m]")
    fig.tight_layout()
    fig.savefig(f"{out}/still_water_3d.png", dpi=120)
    print(f"figure: {out}/still_water_3d.png")
    crit.done()


main()
