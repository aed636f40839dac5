#!/usr/bin/python3
"""Acoustic pulse: pressure and velocity profiles against linear acoustics (pulse.py), and the
acoustic energy history (half leaves through the right end).
usage: plot.py OUTPUT_DIR [--check]   (writes OUTPUT_DIR/acoustic_pulse.png, prints the errors;
--check: exit status 1 unless every deviation is below 3 % of the amplitude and half of the
energy has left, within 2 %)"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

sys.dont_write_bytecode = True
from pulse import A, C0, pressure, velocity


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    index = read(f"{out}/profiles.csv")
    worst = 0.0
    fig, (ax_p, ax_u, ax_e) = plt.subplots(3, 1, figsize=(8, 9))
    for k, t in zip(index["index"], index["t"]):
        if int(k) % 2:
            continue
        p = read(f"{out}/profile_{int(k):04d}.csv")
        pe = [pressure(x, t) for x in p["x"]]
        err = max(abs(a - b) for a, b in zip(p["p"], pe)) / A
        print(f"t = {t:.3f} s: max |p - p_linear| / A = {100 * err:.2f} %")
        worst = max(worst, err)
        line = ax_p.plot(p["x"], p["p"], lw=1.2, label=f"t = {t:.2f} s")[0]
        ax_p.plot(p["x"], pe, "k--", lw=0.7)
        ax_u.plot(p["x"], p["u"], lw=1.2, color=line.get_color())
        ax_u.plot(p["x"], [velocity(x, t) for x in p["x"]], "k--", lw=0.7)
    ax_p.set_ylabel("p [Pa]")
    ax_p.set_title("fv1d (solid) and linear acoustics (dashed)")
    ax_p.legend(fontsize=8, ncol=2)
    ax_u.set_ylabel("u [m/s]")
    ax_u.set_xlabel("x [m]")
    s = read(f"{out}/series.csv")
    e0 = s["energy"][0]
    ax_e.plot(s["t"], [e / e0 for e in s["energy"]], label="energy in the pipe / initial")
    ax_e.plot(s["t"], [1 + (l - r) / e0 for l, r in zip(s["int_energy_left"], s["int_energy_right"])],
              "--", label="1 + net energy inflow through the ends / initial")
    ax_e.set_xlabel("t [s]")
    ax_e.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/acoustic_pulse.png", dpi=120)
    print(f"energy left in the pipe at t = {s['t'][-1]:.3f} s: {s['energy'][-1] / e0:.4f} of the initial")
    print(f"wrote {out}/acoustic_pulse.png")
    if "--check" in sys.argv and not (worst < 0.03 and abs(s["energy"][-1] / e0 - 0.5) < 0.01):
        sys.exit("check failed: pulse off linear acoustics or energy not halved")


main()
