#!/usr/bin/python3
"""Still water in a closed 2D tank (side walls): the still-water criteria at
dr = 0.025 m, the convergence of the spurious motion between dr = 0.05 m and 0.025 m, free surface
with and without the gravity correction and the final hydrostatic pressure.
usage: plot.py OUTPUT_DIR [--check]
  OUTPUT_DIR holds the runs of ./check: corrected/ (the case as committed), uncorrected/ and
  coarse/ (dr = 0.05 m). Writes OUTPUT_DIR/still_water_box_2d.png and prints the measured figures;
  --check: exit status 1 unless every criterion of README.md holds."""
import math
import os
import sys

# the shared readers of sabre-sph output and still-water analysis: cases/sph/sabre_output.py and
# cases/sph/still_water.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import read_csv  # noqa: E402
from still_water import (Criteria, Tank, check_floor_force, check_rest,  # noqa: E402
                         check_surface, figure_rest, rms_speed, tail_max_speed)

TANK = Tank(rho0=1000.0, c0=20.0, xi=7.0, g=9.81, H=1.0125, dr=0.025)
# the walls issue's still-water criteria: max|u| < REST sqrt(gH), hydrostatic L2 < L2_MAX
REST, L2_MAX = 0.005, 0.01
H_COARSE = 1.025  # dr = 0.05 m: 20 rows, the surface dr/2 above the top one


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    crit = Criteria("--check" in sys.argv)

    d, t_end, ys, ps = check_rest(TANK, f"{out}/corrected", 1, crit, rest=REST, l2_max=L2_MAX)
    check_floor_force(TANK, f"{out}/corrected", "floor_fy", 1.0, crit)  # the floor is 1 m wide
    surfaces = check_surface(TANK, out, crit)
    dc = read_csv(f"{out}/coarse/diagnostics.csv", lists=True)
    uf, uc = rms_speed(f"{out}/corrected", d), rms_speed(f"{out}/coarse", dc)
    crit("first order in dr", uc / uf >= 1.8,
         f"rms speed over the second half {uc:.3e} m/s at dr = 0.05 m, {uf:.3e} m/s at 0.025 m: "
         f"ratio {uc / uf:.2f} (>= 1.8; first order gives 2)")
    uc_tail, ref = tail_max_speed(dc), REST * math.sqrt(TANK.g * H_COARSE)
    crit("coarse rest", uc_tail < ref,
         f"dr = 0.05 m: max|u| at the end {dc['max_speed'][-1]:.3e} m/s, at most {uc_tail:.3e} "
         f"over the last 10 % of the run (< {100 * REST:g}% sqrt(gH) = {ref:.3e})")

    labels = ("gravity-corrected (local)", "uncorrected M(49)")
    speeds = {"Δr = 0.025 m (committed)": d, "Δr = 0.05 m": dc}
    figure_rest(TANK, dict(zip(labels, surfaces)), speeds, ys, ps, t_end, "y [m]",
                f"{out}/still_water_box_2d.png")
    crit.done()


main()
