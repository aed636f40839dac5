"""The zeroth-order defect of the wall terms on a constant field, |sum_b V_b grad w_ab - grad
gamma_a| h / gamma_a, at t = 0 in the four closed tanks of tests/sph/invariant_rest.c: on the start
lattice with the fitted vertex layer (top) and with the geometric vertex volumes after the
repacking (bottom). Data: run the test with SABRE_TEST_OUTPUT=DIR, then

    /usr/bin/python3 docs/figures/wall_defect.py DIR docs/figures/wall_defect.png
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

CASES = [("box2d", "2D box"), ("slanted2d", "2D box, 45° wall"), ("wedge2d", "2D wedge apex"),
         ("tank3d", "3D tank (x-z, largest over y)")]


def read(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def main(src, out):
    fig, axes = plt.subplots(2, 4, figsize=(16, 7.5), constrained_layout=True)
    norm = matplotlib.colors.LogNorm(vmin=1e-7, vmax=0.3)
    for col, (tag, title) in enumerate(CASES):
        for row, (kind, label) in enumerate([("lattice", "lattice, fitted layer"),
                                             ("repacked", "geometric + repacked")]):
            data = read(f"{src}/wall_defect_{tag}_{kind}.csv")
            if tag == "tank3d":  # project on x-z, keeping the largest defect over y
                cells = {}
                for p in data:
                    key = (round(p["x"], 6), round(p["z"], 6))
                    cells[key] = max(cells.get(key, 0.0), p["defect"])
                xs, ys, ds = zip(*[(k[0], k[1], d) for k, d in cells.items()])
            else:
                xs, ys, ds = ([p["x"] for p in data], [p["y"] for p in data],
                              [p["defect"] for p in data])
            ds = [max(d, 1e-7) for d in ds]
            ax = axes[row][col]
            sc = ax.scatter(xs, ys, c=ds, s=14 if tag != "wedge2d" else 5, norm=norm,
                            cmap="viridis")
            ax.set_aspect("equal")
            ax.set_title(f"{title}\n{label}: max {max(ds):.1e}", fontsize=10)
            ax.set_xlabel("x [m]")
            ax.set_ylabel("z [m]" if tag == "tank3d" else "y [m]")
    fig.colorbar(sc, ax=axes, shrink=0.8, label="|Σ V_b ∇w_ab − ∇γ_a| h / γ_a")
    fig.savefig(out, dpi=80)
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
