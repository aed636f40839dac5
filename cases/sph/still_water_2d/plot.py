#!/usr/bin/python3
"""Still water (M §7.1, Fig. 8): free-surface elevation, energies and the final hydrostatic
pressure for the gravity-corrected diffusion (default, local form of M 81), the paper's linear M(81)
and the uncorrected Ferrari term M(49).
usage: plot.py OUTPUT_DIR [--check]
  OUTPUT_DIR holds the runs of ./check: corrected/ (the case as committed), linear/, uncorrected/.
  Writes OUTPUT_DIR/still_water_2d.png and prints the measured figures; --check: exit status 1
  unless every criterion of README.md holds."""
import os
import sys

# the shared readers of sabre-sph output and still-water analysis: cases/sph/sabre_output.py and
# cases/sph/still_water.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from still_water import (Criteria, Tank, check_floor_force, check_rest,  # noqa: E402
                         check_surface, plot_profile, pyplot, surface,
                         surface_panel)

TANK = Tank(rho0=1000.0, c0=20.0, xi=7.0, g=9.81, H=1.025, dr=0.05)
C0, H, DR = TANK.c0, TANK.H, TANK.dr


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    crit = Criteria("--check" in sys.argv)

    runs = {"corrected": "gravity-corrected, local (default)", "linear": "M(81) as printed",
            "uncorrected": "uncorrected M(49)"}
    d, t_end, ys, ps = check_rest(TANK, f"{out}/corrected", 1, crit)
    check_floor_force(TANK, f"{out}/corrected", "floor_fy", 1.0, crit)  # the floor is 1 m wide
    corrected, uncorrected = check_surface(TANK, out, crit)
    tl, levl = surface(f"{out}/linear")
    linear = (tl, levl, surface(f"{out}/linear", "eta")[1])
    print(f"     linear M(81): max |level - H| = {max(abs(e - H) for e in levl) / DR:.3f} dr")

    plt = pyplot()
    if plt is None:
        crit.done()
        return
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    surface_panel(ax1, {runs["corrected"]: corrected, runs["linear"]: linear,
                        runs["uncorrected"]: uncorrected}, C0, H, DR)
    plot_profile(ax2, TANK, ys, ps, t_end, [i / 100 for i in range(101)], "y [m]")
    fig.tight_layout()
    fig.savefig(f"{out}/still_water_2d.png", dpi=120)
    print(f"figure: {out}/still_water_2d.png")
    crit.done()


main()
