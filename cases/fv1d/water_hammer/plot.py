#!/usr/bin/python3
"""Water hammer: pressure profiles and the valve pressure history against Joukowsky's
dp = rho0 c0 du and the exact shock (Rankine-Hugoniot for the Tait EOS, solved here).
usage: plot.py OUTPUT_DIR [--check]   (writes OUTPUT_DIR/water_hammer.png, prints the measured jump;
--check: exit status 1 unless it is within 1 % of Joukowsky and 0.1 % of the exact shock)"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

RHO0, C0, XI, U0, L = 1000.0, 1400.0, 7.0, 1.0, 100.0
B = RHO0 * C0 * C0 / XI


def pressure(rho):
    return B * ((rho / RHO0) ** XI - 1.0)


def exact_shock():
    """Fluid at (rho0, u0) brought to rest by a left-running shock: the moving-shock
    Rankine-Hugoniot relations give u0 = sqrt((p2 - p1)(rho2 - rho1)/(rho1 rho2)); solve for rho2."""
    def residual(rho2):
        return math.sqrt(pressure(rho2) * (rho2 - RHO0) / (rho2 * RHO0)) - U0

    lo, hi = RHO0 * (1 + 1e-12), RHO0 * 1.1
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if residual(mid) < 0 else (lo, mid)
    rho2 = 0.5 * (lo + hi)
    speed = -RHO0 * U0 / (rho2 - RHO0)  # mass balance across the shock
    return pressure(rho2), speed


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    dp_j = RHO0 * C0 * U0
    dp_s, speed = exact_shock()
    s = read(f"{out}/series.csv")
    # at the closed valve u = 0, so the momentum flux through the valve face is its pressure
    t, p_valve = s["t"], s["flux_momentum_right"]
    plateau = [p for ti, p in zip(t, p_valve) if 0.2 * L / C0 < ti < 1.8 * L / C0]
    dp = sum(plateau) / len(plateau)
    print(f"valve pressure plateau {dp:.6g} Pa; Joukowsky {dp_j:.6g} Pa ({100 * (dp / dp_j - 1):+.3f} %); "
          f"exact shock {dp_s:.6g} Pa ({100 * (dp / dp_s - 1):+.4f} %); shock speed {speed:.2f} m/s")
    fig, (ax_t, ax_x) = plt.subplots(2, 1, figsize=(8, 7))
    ax_t.plot([ti * C0 / L for ti in t], [p / 1e6 for p in p_valve], label="fv1d, valve")
    square = [dp_j if (ti * C0 / L) % 4 < 2 else -dp_j for ti in t]
    ax_t.plot([ti * C0 / L for ti in t], [p / 1e6 for p in square], "k--", lw=0.8,
              label="Joukowsky ±ρ0 c0 u0")
    ax_t.set_xlabel("t c0 / L")
    ax_t.set_ylabel("p at the valve [MPa]")
    ax_t.legend(fontsize=8)
    index = read(f"{out}/profiles.csv")
    for k, ti in zip(index["index"], index["t"]):
        if ti == 0 or ti * C0 / L > 2.0:
            continue
        p = read(f"{out}/profile_{int(k):04d}.csv")
        line = ax_x.plot(p["x"], [v / 1e6 for v in p["p"]], label=f"t c0/L = {ti * C0 / L:.2f}")[0]
        if ti * C0 / L < 1.0:  # exact shock before it reaches the reservoir
            xs = L + speed * ti
            ax_x.plot([0, xs, xs, L], [0, 0, dp_s / 1e6, dp_s / 1e6], "--", lw=0.8, color=line.get_color())
    ax_x.set_xlabel("x [m]")
    ax_x.set_ylabel("p [MPa]")
    ax_x.set_title(f"exact shock dp = {dp_s / 1e6:.5f} MPa (dashed), Joukowsky {dp_j / 1e6:.3f} MPa")
    ax_x.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/water_hammer.png", dpi=120)
    print(f"wrote {out}/water_hammer.png")
    if "--check" in sys.argv and not (abs(dp / dp_j - 1) < 0.01 and abs(dp / dp_s - 1) < 1e-3):
        sys.exit("check failed: valve pressure plateau off Joukowsky or the exact shock")


main()
