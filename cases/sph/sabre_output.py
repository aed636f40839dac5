"""Readers for the output of sabre-sph, shared by the plot scripts of cases/sph/*/.

A script in cases/sph/<case>/ imports it with
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    import sabre_output  # noqa: E402
so that it runs from any directory. Only the standard library is needed, except for the numpy
forms of read_vtu and read_csv (numpy is imported when they are called).

    read_csv(path, lists=False)        CSV with a header row (diagnostics.csv, probes.csv,
                                       forces.csv, series.csv, profiles.csv) -> {column: values}
    read_vtu(path, tuples=False, by_section=False)
                                       VTK XML UnstructuredGrid with raw appended data and UInt64
                                       headers (fluid_*.vtu, boundary_*.vtu) -> {name: array}
    read_pvd(path, part=None)          ParaView collection (particles.pvd) -> [(time, file)]
    used_dr(run_dir)                   geometry.dr of a run, from its used_case.yaml
    mass_balance(run_dir)              the open boundaries' mass balance of a run, row by row
    Checks()                           the criteria of a `plot.py --check`: require(ok, what)
                                       prints one ok/FAIL line, done() exits 1 if one failed
"""
import csv
import os
import re
import struct
import sys

# VTK type name -> (struct / numpy code, size in bytes)
TYPES = {"Float64": ("d", 8), "Int64": ("q", 8), "UInt8": ("B", 1)}
SECTIONS = ("PointData", "CellData", "Points", "Cells")


def read_csv(path, lists=False):
    """Columns of a CSV file with a header row, every value as a float: {column: numpy array},
    or {column: list of float} with lists=True (no numpy needed)."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if lists:
        return {k: [float(r[k]) for r in rows] for k in rows[0]}
    import numpy as np
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def _arrays(path):
    """(section, name, type, components, bytes) of every DataArray of a VTU file in SABRE's raw
    appended binary format (UInt64 byte-count headers), in file order. The points' DataArray
    has no Name: it is called "points"."""
    raw = open(path, "rb").read()
    start = raw.index(b"<AppendedData")
    blob = raw[raw.index(b"_", start) + 1:]
    head = raw[:start].decode()
    found = []
    for sec in re.finditer(r"<(%s)>(.*?)</\1>" % "|".join(SECTIONS), head, re.S):
        for arr in re.finditer(r"<DataArray ([^>]*)/>", sec.group(2)):
            attrs = dict(re.findall(r'(\w+)="([^"]*)"', arr.group(1)))
            off = int(attrs["offset"])
            nbytes = struct.unpack_from("<Q", blob, off)[0]
            found.append((sec.group(1), attrs.get("Name", "points"), attrs["type"],
                          int(attrs.get("NumberOfComponents", "1")), blob, off + 8, nbytes))
    return found


def read_vtu(path, tuples=False, by_section=False):
    """Arrays of a VTU file written by sabre-sph, by name ("points" for the positions).

    Default: {name: numpy array}, shape (n, components) or (n,) for one component; when a name
    occurs in several sections (PointData and CellData of a boundary file) the first one is kept.
    tuples=True: the same with a list of tuples of Python numbers per array (a 1-tuple per point
    for one component), no numpy needed.
    by_section=True: {"PointData": {...}, "CellData": {...}, "Points": {...}, "Cells": {...}} of
    numpy arrays."""
    if tuples:
        out = {}
        for _, name, typ, ncomp, blob, off, nbytes in _arrays(path):
            code, size = TYPES[typ]
            count = nbytes // size
            vals = struct.unpack_from("<%d%s" % (count, code), blob, off)
            if name not in out:
                out[name] = [vals[i:i + ncomp] for i in range(0, count, ncomp)]
        return out
    import numpy as np
    out = {sec: {} for sec in SECTIONS} if by_section else {}
    for sec, name, typ, ncomp, blob, off, nbytes in _arrays(path):
        code, size = TYPES[typ]
        data = np.frombuffer(blob, dtype="<" + code, count=nbytes // size, offset=off)
        if ncomp > 1:
            data = data.reshape(-1, ncomp)
        if by_section:
            out[sec][name] = data
        else:
            out.setdefault(name, data)
    return out


def read_pvd(path, part=None):
    """[(time, file)] of the DataSets of a .pvd collection in the order listed; file is joined
    to the collection's directory. part: only the DataSets of that part ("0": fluid_*.vtu,
    "1": boundary_*.vtu in particles.pvd)."""
    found = []
    for tag in re.findall(r"<DataSet\b[^>]*>", open(path).read()):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', tag))
        if "timestep" not in attrs or "file" not in attrs:
            continue
        if part is not None and attrs.get("part") != str(part):
            continue
        found.append((float(attrs["timestep"]), os.path.join(os.path.dirname(path), attrs["file"])))
    return found


def time_mean(t, y, t0):
    """Mean of the CSV column y over the rows with t >= t0, each row weighted by the time step
    that ended at it (rows are diagnostics rows, whose steps vary); nan when no row is that late.
    t and y are numpy arrays (read_csv's default)."""
    import numpy as np
    w = np.diff(t, prepend=t[0]) * (t >= t0)
    return float(np.sum(w * y) / np.sum(w)) if np.sum(w) > 0 else float("nan")


def beyond_flux_rate(c, t0):
    """The rate [kg/s, 2D per unit depth] that adds to an open_<name>.csv group's -mass_flux to
    make the mass that left through it, over the rows with t >= t0: what its deleted particles took
    out beyond what its outflow vertices took back (mass_released, cumulative) less the outflow
    its vertices did not take, being at their floor (mass_withheld, cumulative; docs/sph-solver.md
    §10); 0 for a CSV without those columns, nan for fewer than two rows."""
    import numpy as np
    if "mass_released" not in c:
        return 0.0
    t = c["time"]
    late = t >= t0
    if np.count_nonzero(late) < 2:
        return float("nan")
    m = c["mass_released"][late]
    if "mass_withheld" in c:
        m = m - c["mass_withheld"][late]
    tl = t[late]
    return float((m[-1] - m[0]) / (tl[-1] - tl[0]))


def mass_balance(run_dir):
    """max over the rows of |M - M(0) - sum entered + sum released| / M(0), with M the mass of
    diagnostics.csv and entered, released the mass_entered and mass_released columns of every
    open_<name>.csv of the run (one row with each diagnostics row): what the fluid and vertex
    masses gained beyond what the open boundaries let in, relative (docs/sph-solver.md §10; round-off
    when mass is conserved). None when the run has no open boundaries."""
    import numpy as np
    d = read_csv(os.path.join(run_dir, "diagnostics.csv"))
    groups = [f for f in sorted(os.listdir(run_dir)) if f.startswith("open_") and f.endswith(".csv")]
    if not groups:
        return None
    net = d["mass"] - d["mass"][0]
    for f in groups:
        c = read_csv(os.path.join(run_dir, f))
        n = min(len(net), len(c["time"]))
        if n < len(net) or np.any(np.abs(c["time"][:n] - d["time"][:n]) > 1e-12 * max(1.0, d["time"][-1])):
            raise ValueError("%s: its rows are not those of diagnostics.csv" % f)
        net = net - (c["mass_entered"] - c["mass_entered"][0]) + (c["mass_released"] - c["mass_released"][0])
    return float(np.max(np.abs(net)) / d["mass"][0])


def used_dr(run_dir):
    """geometry.dr of a run, read from its used_case.yaml (so that the scripts also serve
    --set geometry.dr=...)."""
    text = open(os.path.join(run_dir, "used_case.yaml")).read()
    return float(re.search(r"^\s*dr:\s*([0-9.eE+-]+)", text, re.M).group(1))


class Checks:
    """The criteria of a `plot.py --check`: prints "criteria (README.md):", then require(ok, what)
    prints "  ok   what" or "  FAIL what"; done() exits with "check failed: N criterion(s)" (status
    1) when one failed, else prints "all criteria hold"."""

    def __init__(self):
        self.failures = []
        print("criteria (README.md):")

    def require(self, ok, what):
        print("  %-4s %s" % ("ok" if ok else "FAIL", what))
        if not ok:
            self.failures.append(what)

    def done(self):
        if self.failures:
            sys.exit("check failed: %d criterion(s)" % len(self.failures))
        print("all criteria hold")
