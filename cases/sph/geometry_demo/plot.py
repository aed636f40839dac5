#!/usr/bin/env python3
"""Plot the output of `sabre-sph mesh` for a 2D case: walls (segments, with their normals into the
fluid, open segments in red), vertex particles and fluid particles coloured by gamma.

usage: plot.py OUTPUT_DIR [FIGURE.png]

Reads the VTU files with ../sabre_output.py (SABRE's appended raw binary format, no VTK needed).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# the shared readers of sabre-sph output: cases/sph/sabre_output.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import read_vtu  # noqa: E402


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    outdir = sys.argv[1]
    figure = sys.argv[2] if len(sys.argv) > 2 else outdir + "/mesh.png"
    fluid = read_vtu(outdir + "/fluid_000000.vtu", by_section=True)
    bnd = read_vtu(outdir + "/boundary_000000.vtu", by_section=True)
    xf = fluid["Points"]["points"]
    gamma = fluid["PointData"]["gamma"]
    xv = bnd["Points"]["points"]
    conn = bnd["Cells"]["connectivity"].reshape(-1, 2)
    normal = bnd["CellData"]["normal"]
    is_open = bnd["CellData"]["flags"] & 1

    fig, ax = plt.subplots(figsize=(10, 5.5))
    sc = ax.scatter(xf[:, 0], xf[:, 1], c=gamma, s=2, cmap="viridis", vmin=0.25, vmax=1)
    fig.colorbar(sc, ax=ax, label=r"$\gamma$ (fluid particles)")
    for (a, b), op in zip(conn, is_open):
        ax.plot(xv[[a, b], 0], xv[[a, b], 1], color="red" if op else "black", lw=1)
    mid = 0.5 * (xv[conn[:, 0]] + xv[conn[:, 1]])
    every = max(1, len(mid) // 150)
    ax.quiver(mid[::every, 0], mid[::every, 1], normal[::every, 0], normal[::every, 1],
              color="tab:orange", scale=40, width=0.002, label="normal (into the fluid)")
    ax.plot(xv[:, 0], xv[:, 1], ".", color="tab:blue", ms=2, label="vertex particles")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("sabre-sph mesh: %d fluid, %d vertex, %d segment particles"
                 % (len(xf), len(xv), len(conn)))
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    fig.savefig(figure, dpi=150)
    print("wrote", figure)


if __name__ == "__main__":
    main()
