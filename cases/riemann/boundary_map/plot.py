#!/usr/bin/python3
"""Plot the boundary Riemann problem maps written by `run`: wave type (contact/expansion/shock,
or the error that stops the solve: supersonic, cavitation) and the computed field, over the
imposed value and the interior normal velocity. Usage: plot.py OUTPUT_DIR"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.colors import ListedColormap

CODES = {"expansion": 0, "contact": 1, "shock": 2, "RMN_ESUPERSONIC": 3, "RMN_ECAVITATION": 4}
LABELS = ["expansion", "contact", "shock", "supersonic", "cavitation"]
COLOURS = ["#4c9be8", "#000000", "#e8704c", "#bbbbbb", "#7a4ce8"]


def load(path):
    rows = list(csv.DictReader(open(path)))
    values = sorted({float(r["value"]) for r in rows})
    uns = sorted({float(r["un_int"]) for r in rows})
    iv = {v: i for i, v in enumerate(values)}
    iu = {u: j for j, u in enumerate(uns)}
    kind = [[float("nan")] * len(values) for _ in uns]
    other = [[float("nan")] * len(values) for _ in uns]
    for r in rows:
        i, j = iv[float(r["value"])], iu[float(r["un_int"])]
        key = r["wave"] if r["status"] == "RMN_SUCCESS" else r["status"]
        kind[j][i] = CODES.get(key, float("nan"))
        if r["status"] == "RMN_SUCCESS":
            other[j][i] = float(r["un"] if r["imposed"] == "pressure" else r["p"])
    return values, uns, kind, other


def main():
    out = sys.argv[1]
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), constrained_layout=True)
    cmap = ListedColormap(COLOURS)
    for col, (name, xlabel, field) in enumerate(
        [("pressure", "imposed pressure p [Pa]", "segment normal velocity u_n [m/s]"),
         ("velocity", "imposed normal velocity u_n [m/s]", "segment pressure p [Pa]")]):
        values, uns, kind, other = load(f"{out}/sweep_{name}.csv")
        ext = [values[0], values[-1], uns[0], uns[-1]]
        im = axes[0][col].imshow(kind, origin="lower", extent=ext, aspect="auto", cmap=cmap,
                                 vmin=-0.5, vmax=4.5, interpolation="nearest")
        axes[0][col].set_title(f"wave type of λ+1, imposed {name}")
        axes[0][col].set_xlabel(xlabel)
        axes[0][col].set_ylabel("interior normal velocity [m/s]")
        cb = fig.colorbar(im, ax=axes[0][col], ticks=range(5))
        cb.ax.set_yticklabels(LABELS)
        im2 = axes[1][col].imshow(other, origin="lower", extent=ext, aspect="auto", cmap="viridis")
        axes[1][col].set_title(field)
        axes[1][col].set_xlabel(xlabel)
        axes[1][col].set_ylabel("interior normal velocity [m/s]")
        fig.colorbar(im2, ax=axes[1][col])
    fig.suptitle("Boundary Riemann problem, Tait ξ = 7, ρ0 = 1000 kg/m³, c0 = 20 m/s, ρ_int = ρ0")
    fig.savefig(f"{out}/boundary_map.png", dpi=110)
    print(f"wrote {out}/boundary_map.png")


if __name__ == "__main__":
    main()
