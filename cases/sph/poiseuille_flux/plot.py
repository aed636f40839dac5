#!/usr/bin/python3
"""Plane Poiseuille flow driven by an imposed volume flux (M §5, Fig. 4): relative bulk-velocity
error over time for the driving forces M(63) and M(58), and the velocity profile of the M(63) run
against the analytical one.
usage: plot.py OUTPUT_DIR [--check]
  OUTPUT_DIR holds the runs of ./check: M63/ (the case as committed) and M58/.
  Writes OUTPUT_DIR/poiseuille_flux.png (if matplotlib is installed) and prints the figures;
  --check: exit status 1 unless the criteria of README.md hold."""
import glob
import math
import os
import sys

# the shared readers of sabre-sph output: cases/sph/sabre_output.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import read_csv, read_vtu, used_dr  # noqa: E402

H, V, NU = 1.0, 1.0, 0.2              # channel height, target bulk velocity, viscosity
VMAX = 1.5 * V                        # centre-line velocity of plane Poiseuille flow
F_EXACT = 12 * NU * V / H**2          # driving acceleration of the steady flow
T_SETTLED = 1.0                       # errors are taken over [T_SETTLED, end)


def exact(y):
    return 6 * V * y * (H - y) / H**2


def bulk_error(run):
    d = read_csv(os.path.join(run, "diagnostics.csv"), lists=True)
    t, e = d["time"], [abs(v - V) / VMAX for v in d["flux_velocity"]]
    # the last step is shortened to end at time.end (a different Δt): left out of the figures
    late = [k for k in range(len(t) - 1) if t[k] >= T_SETTLED]
    return t, e, d["flux_force"], late


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    check = "--check" in sys.argv
    dr = used_dr(os.path.join(out, "M63"))
    hs = 2 * dr                       # smoothing length h (h_over_dr = 2)
    ok = True
    res = {}
    for name in ("M63", "M58"):
        t, e, f, late = bulk_error(os.path.join(out, name))
        emax = max(e[k] for k in late)
        emean = sum(e[k] for k in late) / len(late)
        fmean = sum(f[k] for k in late) / len(late)
        res[name] = (t, e, emax)
        print(f"{name}: |v~ - v|/v_max over t in [{T_SETTLED:g}, {t[-1]:g}) s: max {emax:.3e}, "
              f"mean {emean:.3e}; driving acceleration {fmean:.5g} m/s2 = {fmean / F_EXACT:.5f} "
              f"x 12 nu v/H^2")
    ratio = res["M58"][2] / res["M63"][2]
    good = ratio >= 1e4
    ok &= good
    print(f"{'ok  ' if good else 'FAIL'} bulk-velocity error M(58)/M(63) = {ratio:.3g} = "
          f"{math.log10(ratio):.2f} orders of magnitude (criterion >= 4; paper: about 5)")
    # velocity profile of the M(63) run at the end
    last = sorted(glob.glob(os.path.join(out, "M63", "fluid_*.vtu")))[-1]
    a = read_vtu(last, tuples=True)
    pts, vel = a["points"], a["velocity"]
    perr = max(abs(v[0] - exact(p[1])) for p, v in zip(pts, vel)) / VMAX
    rows = {}
    for p, v in zip(pts, vel):
        rows.setdefault(round(p[1] / dr), []).append((p[1], v[0]))
    prof = sorted((sum(r[0] for r in rs) / len(rs), sum(r[1] for r in rs) / len(rs))
                  for rs in rows.values())
    rerr = max(abs(u - exact(y)) for y, u in prof) / VMAX
    good = perr <= 0.01
    ok &= good
    print(f"{'ok  ' if good else 'FAIL'} profile at t = {res['M63'][0][-1]:g} s: max over the "
          f"{len(pts)} particles |u - u_exact(y)|/U_max = {perr:.3e} (criterion <= 1e-2); "
          f"row means {rerr:.3e}")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        plt = None
        print("matplotlib is not installed: no figure")
    if plt is not None:
        fig, ax = plt.subplots(1, 2, figsize=(11, 4))
        for name, label in (("M58", "Violeau (2012), M(58)"), ("M63", "present, M(63)")):
            t, e, _ = res[name]
            ax[0].semilogy([x * VMAX / hs for x in t[1:-1]], [max(x, 1e-16) for x in e[1:-1]],
                           label=label)
        ax[0].set_xlabel("t v_max / h")
        ax[0].set_ylabel("|v~ - v| / v_max")
        ax[0].set_ylim(1e-12, 1)
        ax[0].legend()
        ys = [k / 200 * H for k in range(201)]
        ax[1].plot([exact(y) for y in ys], ys, "k-", label="Poiseuille")
        ax[1].plot([v[0] for v in vel], [p[1] for p in pts], "o", ms=3, label="SPH, M(63)")
        ax[1].set_xlabel("u [m/s]")
        ax[1].set_ylabel("y [m]")
        ax[1].legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, "poiseuille_flux.png"), dpi=120)
        print(f"figure: {out}/poiseuille_flux.png")
    if check and not ok:
        sys.exit(1)


if __name__ == "__main__":
    main()
