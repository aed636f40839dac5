#!/usr/bin/python3
"""Write box.stl: the closed tank of this case, [0, LX] x [0, LY] x [0, LZ], as an ASCII STL of
12 triangles (two per face), each facet's vertices counter-clockwise seen from outside the box
(right-hand normal pointing out of the solid the surface bounds, as the STL format requires).
usage: make_box_stl.py [LX LY LZ [FILE]]   (defaults: 1.0 0.32 0.6 box.stl next to this script)"""
import os
import sys


def faces(lx, ly, lz):
    """Six faces as (outward normal, four corners counter-clockwise seen from outside)."""
    return [
        ((-1, 0, 0), [(0, 0, 0), (0, 0, lz), (0, ly, lz), (0, ly, 0)]),
        ((1, 0, 0), [(lx, 0, 0), (lx, ly, 0), (lx, ly, lz), (lx, 0, lz)]),
        ((0, -1, 0), [(0, 0, 0), (lx, 0, 0), (lx, 0, lz), (0, 0, lz)]),
        ((0, 1, 0), [(0, ly, 0), (0, ly, lz), (lx, ly, lz), (lx, ly, 0)]),
        ((0, 0, -1), [(0, 0, 0), (0, ly, 0), (lx, ly, 0), (lx, 0, 0)]),
        ((0, 0, 1), [(0, 0, lz), (lx, 0, lz), (lx, ly, lz), (0, ly, lz)]),
    ]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    lx, ly, lz = (float(v) for v in sys.argv[1:4]) if len(sys.argv) >= 4 else (1.0, 0.32, 0.6)
    path = sys.argv[4] if len(sys.argv) >= 5 else os.path.join(here, "box.stl")
    lines = ["solid tank"]
    for n, (a, b, c, d) in faces(lx, ly, lz):
        for tri in ((a, b, c), (a, c, d)):
            lines.append("  facet normal %g %g %g" % n)
            lines.append("    outer loop")
            lines += ["      vertex %.9g %.9g %.9g" % p for p in tri]
            lines.append("    endloop")
            lines.append("  endfacet")
    lines.append("endsolid tank")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
