#!/usr/bin/python3
"""Robin wave, M §6.2: the analytical solution at the four times of M Fig. 6.

usage: plot_analytic.py ANALYTIC_CSV [OUTPUT_PNG]

ANALYTIC_CSV (columns t, x, u, u_t, u_x) is written by the unit test of the series M(78-79):
    SABRE_ROBIN_WAVE_CSV=analytic.csv build/tests/sph/sph_test_robin_wave_series
(4000 modes with the tail correction, truncation error ~1e-10; docs/sph-robin.md §3).
The Neumann solution that the paper superimposes (du/dn = 0 at both ends, same initial data) is
computed here from its cosine series:
    u = sum_{n odd} 4k/(k^2 - n^2 pi^2) sin(n pi t)/(n pi) cos(n pi x),  k = 2 pi.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

# the shared readers of sabre-sph output: cases/sph/sabre_output.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import read_csv  # noqa: E402

K = 2.0 * math.pi


def neumann(x, t, nmax=20001):
    n = np.arange(1, nmax + 1, 2, dtype=float)[:, None]
    c = 4.0 * K / (K * K - (n * math.pi) ** 2)
    return np.sum(c * np.sin(n * math.pi * t) / (n * math.pi) * np.cos(n * math.pi * x), axis=0)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[2] if len(sys.argv) > 2 else "robin_wave_analytic.png"
    a = read_csv(sys.argv[1])
    times = sorted(set(a["t"]))
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.5), sharex=True)
    for ax, t, label in zip(axes.flat, times, "abcd"):
        sel = a["t"] == t
        x, u = a["x"][sel], a["u"][sel]
        ax.plot(x, u, "k-", label=r"Robin $\partial u/\partial n = u$, M(78)")
        ax.plot(x, neumann(x, t), "b--", label=r"Neumann $\partial u/\partial n = 0$")
        ax.set_title(f"({label}) t = {t:g}")
        ax.set_xlim(0.0, 1.0)
        ax.grid(alpha=0.3)
        # Robin residual at the ends from the tabulated derivative (column u_x)
        ux0, ux1 = a["u_x"][sel][0], a["u_x"][sel][-1]
        print(f"t = {t:g}: u(0) = {u[0]:+.6f}, u(1) = {u[-1]:+.6f}, "
              f"u_x(0) - u(0) = {ux0 - u[0]:.1e}, -u_x(1) - u(1) = {-ux1 - u[-1]:.1e}")
    for ax in axes[1]:
        ax.set_xlabel("x")
    for ax in axes[:, 0]:
        ax.set_ylabel("u")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("Wave equation with Robin conditions, M Fig. 6: analytical solutions")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
