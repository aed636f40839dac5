#!/usr/bin/python3
"""Write tank.stl: the closed boundary of the water's domain in SPHERIC test 2 (Kleefsman et al.
2005): the tank [0, 3.22] x [0, 1] x [0, 1] m minus the box obstacle [0.6635, 0.8245] x
[0.2985, 0.7015] x [0, 0.161] m that stands on its floor, as one closed ASCII STL surface.

Why one surface: SABRE's walls must be closed (docs/sph-geometry.md §3, every edge in exactly two
triangles running through it in opposite directions) and must not overlap. A `box` tank plus an
obstacle STL read with `fluid: outside` cannot express a box standing ON the floor: a closed
obstacle would overlap the floor with its bottom face, an open one (five faces) leaves its bottom
edges in one triangle. So the floor here has a rectangular hole where the obstacle stands, and
the obstacle's five wetted faces close it; the case reads the surface with `fluid: inside`.

Every face is a grid of near-square rectangles (each cut in two triangles) on breakpoints common to
all faces (the obstacle's edges among them), so the surface is conforming (no hanging nodes) and
SABRE's longest-edge bisection refines it to triangles of edge <= 1.5 dr whatever the case's dr.
Facets run counter-clockwise seen from outside the water's domain (right-hand normal pointing out
of the solid the surface bounds, as the STL format requires): out of the tank's walls, into the
obstacle.

usage: make_tank_stl.py [FILE] [--tank LX,LY,LZ] [--obstacle X0,X1,Y0,Y1,HEIGHT] [--name NAME]
  FILE defaults to tank.stl next to this script; the other options default to SPHERIC test 2 and
  also make the tank of sph/bench/bench_dambreak.c (DualSPHysics' CaseDambreak, see its header)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from stl_grid import breaks, face, numbers, write_stl  # noqa: E402

TANK = (3.22, 1.0, 1.0)                       # tank (Kleefsman et al. 2005, Fig. 2)
OBSTACLE = (0.6635, 0.8245, 0.2985, 0.7015, 0.161)   # x0, x1, y0, y1, height: 0.161 x 0.403 x 0.161 m
CELL = 0.17                                   # target size of the coarse grid [m]


def surface(tank=TANK, obstacle=OBSTACLE):
    LX, LY, LZ = tank
    OX, OY, OZ = obstacle[0:2], obstacle[2:4], obstacle[4]
    if not (0 < OX[0] < OX[1] < LX and 0 < OY[0] < OY[1] < LY and 0 < OZ < LZ):
        sys.exit("make_tank_stl.py: the obstacle must stand inside the tank, below its lid")
    XS = breaks([0.0, OX[0], OX[1], LX], CELL)
    YS = breaks([0.0, OY[0], OY[1], LY], CELL)
    ZS = breaks([0.0, OZ, LZ], CELL)      # OZ among them keeps the grid of the side walls regular
    eps = 1e-12
    inside = [v for v in XS if OX[0] - eps <= v <= OX[1] + eps]
    ys_o = [v for v in YS if OY[0] - eps <= v <= OY[1] + eps]
    zs_o = [v for v in ZS if v <= OZ + eps]

    def under_obstacle(x0, x1, y0, y1):
        return x0 >= OX[0] - eps and x1 <= OX[1] + eps and y0 >= OY[0] - eps and y1 <= OY[1] + eps

    tris = []
    # the tank, normals pointing out of it
    tris += face(0, 0.0, -1, YS, ZS) + face(0, LX, +1, YS, ZS)
    tris += face(1, 0.0, -1, XS, ZS) + face(1, LY, +1, XS, ZS)
    tris += face(2, 0.0, -1, XS, YS, skip=under_obstacle) + face(2, LZ, +1, XS, YS)
    # the obstacle, normals pointing into it (out of the water's domain)
    tris += face(0, OX[1], -1, ys_o, zs_o) + face(0, OX[0], +1, ys_o, zs_o)
    tris += face(1, OY[0], +1, inside, zs_o) + face(1, OY[1], -1, inside, zs_o)
    tris += face(2, OZ, -1, inside, ys_o)
    return tris


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    path, tank, obstacle, name = os.path.join(here, "tank.stl"), TANK, OBSTACLE, "spheric_test2"
    args = sys.argv[1:]
    while args:
        arg = args.pop(0)
        if arg in ("--tank", "--obstacle", "--name") and not args:
            sys.exit("make_tank_stl.py: %s needs a value" % arg)
        if arg == "--tank":
            tank = numbers(args.pop(0), 3, arg, "make_tank_stl.py")
        elif arg == "--obstacle":
            obstacle = numbers(args.pop(0), 5, arg, "make_tank_stl.py")
        elif arg == "--name":
            name = args.pop(0)
        elif arg.startswith("-"):
            sys.exit("make_tank_stl.py: unknown option %s" % arg)
        else:
            path = arg
    count = write_stl(path, [(name, surface(tank, obstacle))])
    print("wrote %s (%d triangles)" % (path, count))


if __name__ == "__main__":
    main()
