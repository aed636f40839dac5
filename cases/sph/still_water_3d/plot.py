#!/usr/bin/python3
"""Still water in an infinite 3D layer (M §7.1, Fig. 8 in 3D): free surface, maximum speed and
the final hydrostatic pressure with the gravity-corrected diffusion (default, local form of M 81)
and without the correction (M 49).
usage: plot.py OUTPUT_DIR [--check]
  OUTPUT_DIR holds the runs of ./check: corrected/ (the case as committed) and uncorrected/.
  Writes OUTPUT_DIR/still_water_3d.png and prints the measured figures; --check: exit status 1
  unless every criterion of README.md holds."""
import os
import sys

# the shared readers of sabre-sph output and still-water analysis: cases/sph/sabre_output.py and
# cases/sph/still_water.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from still_water import (Criteria, Tank, check_floor_force, check_rest,  # noqa: E402
                         check_surface, figure_3d)

TANK = Tank(rho0=1000.0, c0=19.0, xi=7.0, g=9.81, H=0.3625, dr=0.025)
AREA = 0.3 * 0.3  # the periodic cell's floor [m²]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    crit = Criteria("--check" in sys.argv)

    d, t_end, zs, ps = check_rest(TANK, f"{out}/corrected", 2, crit)
    check_floor_force(TANK, f"{out}/corrected", "floor_fz", AREA, crit)
    surfaces = check_surface(TANK, out, crit)
    figure_3d(TANK, out, d, surfaces, zs, ps, t_end, f"{out}/still_water_3d.png")
    crit.done()


main()
