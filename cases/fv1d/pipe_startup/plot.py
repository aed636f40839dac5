#!/usr/bin/python3
"""Pipe start-up: velocity at mid-pipe and mean velocity against the linear-acoustics solution
(method of images for a pipe with imposed pressure at both ends) and the rigid-column law.
usage: plot.py OUTPUT_DIR [--check]   (writes OUTPUT_DIR/pipe_startup.png; --check: exit status 1
unless the mean velocity is within 1 % of the rigid column and the mid-pipe velocity within
0.05 m/s of linear acoustics)"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

RHO0, C0, L, DP, RAMP = 1000.0, 50.0, 10.0, 5000.0, 0.02


def inlet(t):
    return 0.0 if t <= 0 else DP * min(t / RAMP, 1.0)


def acoustic_u(x, t):
    """u = (1/(rho c)) sum_n [f(t - (x + 2nL)/c) + f(t - (2L - x + 2nL)/c)]: both ends reflect
    pressure with coefficient -1."""
    total, n = 0.0, 0
    while t - (x + 2 * n * L) / C0 > 0:
        total += inlet(t - (x + 2 * n * L) / C0) + inlet(t - (2 * L - x + 2 * n * L) / C0)
        n += 1
    return total / (RHO0 * C0)


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    index = read(f"{out}/profiles.csv")
    t_mid, u_mid = [], []
    for k, t in zip(index["index"], index["t"]):
        p = read(f"{out}/profile_{int(k):04d}.csv")
        i = min(range(len(p["x"])), key=lambda j: abs(p["x"][j] - 0.5 * L))
        t_mid.append(t)
        u_mid.append(p["u"][i])
    s = read(f"{out}/series.csv")
    mean_u = [m / M for m, M in zip(s["momentum"], s["mass"])]
    fig, ax = plt.subplots(figsize=(8, 5))
    tt = [i * s["t"][-1] / 2000 for i in range(2001)]
    ax.plot(tt, [acoustic_u(0.5 * L, t) for t in tt], "k-", lw=0.8, label="linear acoustics, x = L/2")
    ax.plot(t_mid, u_mid, "o", ms=3, label="fv1d, x = L/2")
    ax.plot(s["t"], mean_u, lw=1.2, label="fv1d, mean velocity")
    ax.plot(tt, [DP * max(t - RAMP / 2, 0) / (RHO0 * L) for t in tt], "--", lw=0.8,
            label="rigid column Δp (t − ramp/2) / (ρ0 L)")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("u [m/s]")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/pipe_startup.png", dpi=120)
    err = max(abs(u - acoustic_u(0.5 * L, t)) for t, u in zip(t_mid, u_mid))
    print(f"final mean velocity {mean_u[-1]:.4f} m/s, rigid column {DP * (s['t'][-1] - RAMP / 2) / (RHO0 * L):.4f} m/s; "
          f"max |u - u_acoustic| at mid-pipe {err:.4f} m/s")
    print(f"wrote {out}/pipe_startup.png")
    rigid = DP * (s["t"][-1] - RAMP / 2) / (RHO0 * L)
    if "--check" in sys.argv and not (abs(mean_u[-1] / rigid - 1) < 0.01 and err < 0.05):
        sys.exit("check failed: mean velocity or mid-pipe velocity off")


main()
