#!/usr/bin/python3
"""Still water in a closed 3D tank: energies, maximum speed, free surface and
the final hydrostatic pressure, with the gravity-corrected diffusion (default, local form of M 81)
and without the correction (M 49).
usage: plot.py OUTPUT_DIR [--check]
  OUTPUT_DIR holds the runs of ./check: corrected/ (the case as committed) and uncorrected/.
  Writes OUTPUT_DIR/still_water_tank_3d.png and prints the measured figures; --check: exit status 1
  unless every criterion of README.md holds."""
import os
import sys

# the shared readers of sabre-sph output and still-water analysis: cases/sph/sabre_output.py and
# cases/sph/still_water.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from still_water import Criteria, Tank, check_rest, check_surface, figure_3d  # noqa: E402

TANK = Tank(rho0=1000.0, c0=15.0, xi=7.0, g=9.81, H=0.2125, dr=0.025)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    crit = Criteria("--check" in sys.argv)

    # the walls issue's still-water criteria: max|u| <= 0.5 % sqrt(gH), hydrostatic L2 <= 1 %
    d, t_end, zs, ps = check_rest(TANK, f"{out}/corrected", 2, crit, rest=0.005, l2_max=0.01)
    surfaces = check_surface(TANK, out, crit)
    figure_3d(TANK, out, d, surfaces, zs, ps, t_end, f"{out}/still_water_tank_3d.png")
    crit.done()


main()
