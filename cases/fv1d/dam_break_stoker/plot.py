#!/usr/bin/python3
"""Compare the fv1d dam break (xi = 2) with Stoker's wet-bed solution, computed here from the
shock (hydraulic jump) relations and the rarefaction invariants, independently of SABRE.
usage: plot.py OUTPUT_DIR [--check]   (writes OUTPUT_DIR/stoker.png, prints the relative L1 errors;
--check: exit status 1 unless every error is below 1 %)"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

G, H_L, H_R = 9.81, 1.0, 0.35


def stoker():
    c_l = math.sqrt(G * H_L)

    def residual(h):
        return 2 * (c_l - math.sqrt(G * h)) - (h - H_R) * math.sqrt(0.5 * G * (h + H_R) / (h * H_R))

    lo, hi = H_R, H_L
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if residual(mid) > 0 else (lo, mid)
    h_m = 0.5 * (lo + hi)
    c_m = math.sqrt(G * h_m)
    u_m = 2 * (c_l - c_m)
    s = h_m * u_m / (h_m - H_R)
    return c_l, h_m, c_m, u_m, s


def exact(x, t):
    c_l, h_m, c_m, u_m, s = stoker()
    xi = x / t
    if xi <= -c_l:
        return H_L, 0.0
    if xi <= u_m - c_m:
        c = (2 * c_l - xi) / 3
        return c * c / G, 2.0 / 3.0 * (c_l + xi)
    if xi < s:
        return h_m, u_m
    return H_R, 0.0


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    index = read(f"{out}/profiles.csv")
    worst = 0.0
    fig, (ax_h, ax_u) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for k, t in zip(index["index"], index["t"]):
        if t == 0:
            continue
        p = read(f"{out}/profile_{int(k):04d}.csv")
        ex = [exact(x, t) for x in p["x"]]
        err = sum(abs(h - e[0]) for h, e in zip(p["rho"], ex)) / sum(e[0] for e in ex)
        print(f"t = {t:.3f} s: relative L1 error of h = {100 * err:.3f} %")
        worst = max(worst, err)
        line = ax_h.plot(p["x"], p["rho"], lw=1.2, label=f"fv1d t = {t:.2f} s")[0]
        ax_h.plot(p["x"], [e[0] for e in ex], "k--", lw=0.8)
        ax_u.plot(p["x"], p["u"], lw=1.2, color=line.get_color())
        ax_u.plot(p["x"], [e[1] for e in ex], "k--", lw=0.8)
    c_l, h_m, c_m, u_m, s = stoker()
    ax_h.set_title(f"Dam break, Stoker (dashed): h_m = {h_m:.4f} m, u_m = {u_m:.4f} m/s, S = {s:.4f} m/s")
    ax_h.set_ylabel("h = rho [m]")
    ax_u.set_ylabel("u [m/s]")
    ax_u.set_xlabel("x [m]")
    ax_h.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/stoker.png", dpi=120)
    print(f"wrote {out}/stoker.png")
    if "--check" in sys.argv and not worst < 0.01:
        sys.exit(f"check failed: relative L1 error {100 * worst:.3f} % >= 1 %")


main()
