#!/usr/bin/python3
"""Still water in a closed tank (M §7.2, Fig. 9): particle speeds near the free-surface/wall
corners with the least-squares vertex pressure constrained by M(82) and by M(83).
usage: plot.py OUTPUT_DIR [--check]
  OUTPUT_DIR holds the runs of ./check: M83/ (the case as committed) and M82/; optional extra
  runs M83_m1/ and M82_m1/ (order m = 1) are reported when present.
  Writes OUTPUT_DIR/still_water_corner.png (if matplotlib is installed) and prints the figures;
  --check: exit status 1 unless the criterion of README.md holds."""
import math
import os
import sys

# the shared readers of sabre-sph output: cases/sph/sabre_output.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import read_pvd, read_vtu  # noqa: E402

DR, H, WIDTH = 0.05, 0.525, 1.0
T_SETTLED = 2.0          # the start-up sloshing has decayed by then (README)
CORNER_X = 3.5 * DR      # "near the corner": within 3.5 dr of a side wall ...
CORNER_Y = H - 3.5 * DR  # ... and of the free surface (the case's dr; a fixed region)


def outputs(run):
    """(time, path) of the fluid VTU files listed in particles.pvd."""
    return [(t, f) for t, f in read_pvd(os.path.join(run, "particles.pvd"))
            if "fluid_" in os.path.basename(f)]


def near_corner(p):
    return (p[0] < CORNER_X or p[0] > WIDTH - CORNER_X) and p[1] > CORNER_Y


def analyse(run):
    """Per output: time, max speed near the corners, max speed anywhere; last snapshot."""
    rows, last = [], None
    for t, f in outputs(run):
        a = read_vtu(f, tuples=True)
        speed = [math.hypot(v[0], v[1]) for v in a["velocity"]]
        corner = [s for s, p in zip(speed, a["points"]) if near_corner(p)]
        rows.append((t, max(corner) if corner else 0.0, max(speed)))
        last = (a["points"], speed)
    return rows, last


def summary(rows):
    late = [r for r in rows if r[0] >= T_SETTLED - 1e-9]
    return (max(r[1] for r in late), sum(r[1] for r in late) / len(late),
            max(r[2] for r in late), max(r[1] for r in rows))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    check = "--check" in sys.argv
    runs = {}
    for name in ("M82", "M83", "M82_m1", "M83_m1"):
        if os.path.isdir(os.path.join(out, name)):
            runs[name] = analyse(os.path.join(out, name))
    figures = {}
    for name, (rows, _) in runs.items():
        cmax, cmean, amax, cmax_all = summary(rows)
        figures[name] = cmax
        print(f"{name:7s} t >= {T_SETTLED:g} s: max speed near the corners {cmax:.3e} m/s "
              f"(mean over outputs {cmean:.3e}), anywhere {amax:.3e}; over the whole run "
              f"{cmax_all:.3e}")
    ok = True
    for m in ("", "_m1"):
        a, b = figures.get("M82" + m), figures.get("M83" + m)
        if a is None or b is None:
            continue
        ratio = a / b
        crit = m == ""
        good = ratio >= 5.0
        if crit:
            ok &= good
        tag = ("ok  " if good else "FAIL") if crit else "info"
        order = "m = 1" if m else "m = 2 (the case)"
        print(f"{tag} {order}: corner speed M(82)/M(83) = {a:.3e}/{b:.3e} = {ratio:.1f} "
              f"({'criterion >= 5' if crit else 'not a criterion'}; paper: about 10)")
    if "M82" not in figures or "M83" not in figures:
        print("FAIL the runs M82/ and M83/ are needed")
        ok = False
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        plt = None
        print("matplotlib is not installed: no figure")
    if plt is not None and "M82" in runs and "M83" in runs:
        fig, ax = plt.subplots(1, 3, figsize=(15, 4))
        vmax = max(max(runs[n][1][1]) for n in ("M82", "M83"))
        for k, name in enumerate(("M82", "M83")):
            pts, speed = runs[name][1]
            sc = ax[k].scatter([p[0] for p in pts], [p[1] for p in pts], c=speed, s=40,
                               cmap="viridis", vmin=0, vmax=vmax)
            ax[k].set_aspect("equal")
            ax[k].set_xlim(0, WIDTH)
            ax[k].set_ylim(0, 0.6)
            ax[k].set_title(f"{name}: |v| at t = {runs[name][0][-1][0]:g} s")
            fig.colorbar(sc, ax=ax[k], label="|v| [m/s]")
        for name in runs:
            rows = runs[name][0]
            ax[2].semilogy([r[0] for r in rows], [max(r[1], 1e-8) for r in rows], label=name)
        ax[2].set_xlabel("t [s]")
        ax[2].set_ylabel("max |v| near the corners [m/s]")
        ax[2].legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, "still_water_corner.png"), dpi=120)
        print(f"figure: {out}/still_water_corner.png")
    if check and not ok:
        sys.exit(1)


if __name__ == "__main__":
    main()
