#!/usr/bin/python3
"""Write channel.stl: the closed boundary of the water's domain of J §IV.C (Joly et al. 2016,
Fig. 9, "a sloped domain"): a flat-bottomed channel whose bed rises by a ramp to a shelf, open at
both ends.

    x in [0, LENGTH] along the channel, y in [0, WIDTH] across, z up; the bed is z = 0 up to
    x = RAMP_START, rises linearly to z = SHELF at x = RAMP_END and stays there to the outlet;
    a lid at z = TOP closes the domain above the water.

Three named solids (docs/sph-geometry.md §4.2), selected by the case's open boundaries:
`inlet` (the end x = 0, bed to lid), `outlet` (the end x = LENGTH, shelf to lid) and `walls`
(bed, side walls and lid). The bed, lid and ends are grids of near-square rectangles; each side
wall is a column per bed interval, filled between the breakpoints of its two vertical edges
(cases/sph/stl_grid.py), so the surface is conforming and SABRE refines it to the case's dr.

usage: make_channel_stl.py [FILE] [--length L] [--width W] [--top Z] [--ramp X0,X1,HEIGHT]
  FILE defaults to channel.stl next to this script; the options default to the case's channel
  (README.md): L = 2.88 m, W = 0.48 m, Z = 1.2 m, a ramp from x = 0.96 m to 1.68 m up to
  0.24 m (multiples of 0.08 m and 0.048 m: README.md, "Set-up")."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from stl_grid import breaks, face, numbers, oriented, strip, write_stl  # noqa: E402

LENGTH, WIDTH, TOP = 2.88, 0.48, 1.2
RAMP = (0.96, 1.68, 0.24)                    # start, end of the ramp, height of the shelf [m]
CELL = 0.24                                   # target size of the coarse grid [m]


def surface(length=LENGTH, width=WIDTH, top=TOP, ramp=RAMP):
    """[(name, triangles)] of the channel: walls, inlet, outlet."""
    x0, x1, shelf = ramp
    if not (0 < x0 < x1 < length and 0 < shelf < top and width > 0):
        sys.exit("make_channel_stl.py: the ramp must lie inside the channel, below its lid")

    def bed(x):
        return 0.0 if x <= x0 else shelf if x >= x1 else shelf * (x - x0) / (x1 - x0)

    XS = breaks([0.0, x0, x1, length], CELL)
    YS = breaks([0.0, width], CELL)
    ZS = breaks([0.0, shelf, top], CELL)

    def column(x, y):
        """The breakpoints of the vertical line (x, y) of a side wall or end: the bed, then the
        grid's heights above it (those closer than CELL/3 to the bed left out)."""
        zb = bed(x)
        return [(x, y, zb)] + [(x, y, z) for z in ZS if z > zb + CELL / 3]

    walls = []
    for a, b in zip(XS[:-1], XS[1:]):               # the bed, out of the water: downwards
        for c, d in zip(YS[:-1], YS[1:]):
            p = [(a, c, bed(a)), (b, c, bed(b)), (b, d, bed(b)), (a, d, bed(a))]
            walls += [oriented((p[0], p[1], p[2]), (0, 0, -1)), oriented((p[0], p[2], p[3]), (0, 0, -1))]
        for y, out in ((0.0, (0, -1, 0)), (width, (0, 1, 0))):   # the side walls
            walls += strip(column(a, y), column(b, y), out)
    walls += face(2, top, +1, XS, YS)               # the lid
    ends = []
    for x, out in ((0.0, (-1, 0, 0)), (length, (1, 0, 0))):
        tris = []
        for c, d in zip(YS[:-1], YS[1:]):
            tris += strip(column(x, c), column(x, d), out)
        ends.append(tris)
    return [("walls", walls), ("inlet", ends[0]), ("outlet", ends[1])]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    path, length, width, top, ramp = os.path.join(here, "channel.stl"), LENGTH, WIDTH, TOP, RAMP
    args = sys.argv[1:]
    while args:
        arg = args.pop(0)
        if arg in ("--length", "--width", "--top", "--ramp") and not args:
            sys.exit("make_channel_stl.py: %s needs a value" % arg)
        if arg == "--length":
            length = numbers(args.pop(0), 1, arg, "make_channel_stl.py")[0]
        elif arg == "--width":
            width = numbers(args.pop(0), 1, arg, "make_channel_stl.py")[0]
        elif arg == "--top":
            top = numbers(args.pop(0), 1, arg, "make_channel_stl.py")[0]
        elif arg == "--ramp":
            ramp = numbers(args.pop(0), 3, arg, "make_channel_stl.py")
        elif arg.startswith("-"):
            sys.exit("make_channel_stl.py: unknown option %s" % arg)
        else:
            path = arg
    count = write_stl(path, surface(length, width, top, ramp))
    print("wrote %s (%d triangles)" % (path, count))


if __name__ == "__main__":
    main()
