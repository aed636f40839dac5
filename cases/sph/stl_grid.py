"""Closed ASCII STL surfaces made of axis-aligned faces, shared by the geometry scripts of
cases/sph/*/ (make_tank_stl.py, make_channel_stl.py).

A script in cases/sph/<case>/ imports it with
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    import stl_grid  # noqa: E402

Every face is a grid of near-square rectangles, each cut in two triangles, on breakpoints that the
faces of one surface share, so the surface is conforming (no hanging nodes) and SABRE's
longest-edge bisection refines it to triangles of edge <= 1.5 dr whatever the case's dr
(docs/sph-geometry.md §3, "Meshing"). Facets run counter-clockwise seen from outside the water's
domain (right-hand normal pointing out of the solid the surface bounds, as the STL format requires).

    breaks(points, cell)           sorted breakpoints through the given points, each interval cut
                                   into pieces of about `cell`
    face(axis, level, normal, us, vs, skip=None)
                                   triangles of the plane coordinate[axis] = level
    oriented(tri, outward)         the triangle with its vertices ordered so that its right-hand
                                   normal points along `outward` (any vector on that side)
    strip(left, right, outward)    triangles between two polylines of increasing height (a
                                   column of a wall whose breakpoints differ on its two sides)
    write_stl(path, solids)        an ASCII STL of named solids: [(name, triangles), ...]
    numbers(text, count, option, prog)
                                   a command-line value of `count` comma-separated numbers
"""


import sys


def numbers(text, count, option, prog):
    """The tuple of `count` numbers in text ("1,2,3"), or exit naming the script and the option."""
    try:
        vals = tuple(float(v) for v in text.split(","))
    except ValueError:
        vals = ()
    if len(vals) != count:
        sys.exit("%s: %s expects %d comma-separated numbers, got '%s'" % (prog, option, count, text))
    return vals


def breaks(points, cell):
    """Sorted breakpoints through the given (increasing) points, intervals cut into pieces of
    about `cell`."""
    out = [points[0]]
    for a, b in zip(points[:-1], points[1:]):
        n = max(1, round((b - a) / cell))
        out += [a + (b - a) * k / n for k in range(1, n)] + [b]
    return out


def sub(a, b):
    return tuple(p - q for p, q in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def face(axis, level, normal, us, vs, skip=None):
    """Triangles of the plane coordinate[axis] = level, gridded by us x vs on the two other axes
    (in increasing axis order), oriented so that the right-hand normal is `normal` (+1/-1 along
    axis); skip(u0, u1, v0, v1) -> True leaves a rectangle out."""
    other = [k for k in range(3) if k != axis]
    tris = []
    for i in range(len(us) - 1):
        for j in range(len(vs) - 1):
            if skip and skip(us[i], us[i + 1], vs[j], vs[j + 1]):
                continue
            quad = []
            for u, v in ((us[i], vs[j]), (us[i + 1], vs[j]), (us[i + 1], vs[j + 1]), (us[i], vs[j + 1])):
                p = [0.0, 0.0, 0.0]
                p[axis], p[other[0]], p[other[1]] = level, u, v
                quad.append(tuple(p))
            a, b, c, d = quad
            if cross(sub(b, a), sub(c, a))[axis] * normal < 0:
                a, b, c, d = a, d, c, b
            tris += [(a, b, c), (a, c, d)]
    return tris


def oriented(tri, outward):
    """tri with its last two vertices swapped if its right-hand normal points against outward."""
    a, b, c = tri
    n = cross(sub(b, a), sub(c, a))
    return (a, b, c) if sum(p * q for p, q in zip(n, outward)) > 0 else (a, c, b)


def strip(left, right, outward):
    """Triangles filling the band between the polylines left and right (points ordered the same
    way along both, e.g. by height), every point of both a vertex: the zipper that always advances
    on the side whose next point comes first along the band, so the band stays conforming with
    whatever its neighbours put on its two edges."""
    axis = max(range(3), key=lambda k: abs(left[-1][k] - left[0][k]))
    i, j, tris = 0, 0, []
    while i < len(left) - 1 or j < len(right) - 1:
        if j == len(right) - 1 or (i < len(left) - 1 and left[i + 1][axis] <= right[j + 1][axis]):
            tris.append(oriented((left[i], right[j], left[i + 1]), outward))
            i += 1
        else:
            tris.append(oriented((left[i], right[j], right[j + 1]), outward))
            j += 1
    return tris


def write_stl(path, solids):
    """Write the named solids [(name, triangles), ...] as one ASCII STL file (one
    `solid NAME ... endsolid NAME` block each, triangles numbered through the file); returns the
    number of triangles."""
    lines = []
    count = 0
    for name, tris in solids:
        lines.append("solid " + name)
        for tri in tris:
            n = cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]))
            norm = sum(c * c for c in n) ** 0.5
            lines.append("  facet normal %g %g %g" % tuple(c / norm for c in n))
            lines.append("    outer loop")
            lines += ["      vertex %.9g %.9g %.9g" % p for p in tri]
            lines.append("    endloop")
            lines.append("  endfacet")
        lines.append("endsolid " + name)
        count += len(tris)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return count
