#!/usr/bin/python3
"""3D solitary wave over a sloped bed through open boundaries (J §IV.C): side views of the breaking
wave coloured by the speed (J Fig. 10), the water level along the centre line, and the reflection
of the outlet measured against a run in a channel twice as long.

usage: plot.py OUTPUT_DIR [--reference LONG_DIR] [--check]
  OUTPUT_DIR is a run of case.yaml, LONG_DIR the same run in channel_long.stl (README.md; any dr,
  read from used_case.yaml). Writes OUTPUT_DIR/solitary_wave_3d.png and prints the figures of
  README.md. --check: exit status 1 unless the criteria of README.md hold (they need LONG_DIR).

The reflection: the head H = p/(rho0 g) + z - D at the pressure probes 0.05 m above the shelf
(a smooth measure of the level of a long wave), in the case and in the long channel, whose
outlet is 3 m farther. Until a wave from the long channel's outlet could reach a probe, the two
runs differ only by what came back from the case's outlet: R = max |H_case - H_long| / A over
that window and over the probes beyond the ramp.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import Checks, mass_balance, read_csv, read_pvd, read_vtu, used_dr  # noqa: E402

DEPTH, AMPLITUDE, G, RHO0 = 0.6, 0.3, 9.81, 1000.0     # J §IV.C, case.yaml
RAMP, SHELF, LENGTH, LONG = (0.96, 1.68), 0.24, 2.88, 5.76  # make_channel_stl.py
SNAPSHOTS = (1.4, 1.8, 2.2, 2.6, 3.0, 3.4)             # s, side views
REFLECTION_PROBES = (5, 6)                             # p5, p6: x = 2.52, 2.7 m on the shelf
BOUND = 0.05                                           # reflection / A


def probes(run):
    """time, the pressure probes' points and their heads H_k(t) [m]."""
    pr = read_csv(os.path.join(run, "probes.csv"))
    text = open(os.path.join(run, "used_case.yaml")).read()
    block = text[text.index("pressure:", text.index("probes:")):]
    pts = []
    for line in block.splitlines()[1:]:
        line = line.strip()
        if not line.startswith("- ["):
            break
        pts.append([float(v) for v in line[3:line.index("]")].split(",")])
    t = pr["time"]
    heads = [pr["p%d" % k] / (RHO0 * G) + pts[k][2] - DEPTH for k in range(len(pts))]
    return t, pts, heads


def window_end(long_run, x_probe):
    """The earliest time a gravity wave from the long channel's outlet could reach x_probe: when
    that outlet first sees the wave (its outflow exceeds 0.3 m/s; the still water's start-up moves
    it by about 0.1 m/s) plus the travel time back at the shelf's long-wave speed
    sqrt(g (D - shelf + A))."""
    c = read_csv(os.path.join(long_run, "open_outlet.csv"))
    moving = np.nonzero(c["un"] < -0.3)[0]
    t_seen = c["time"][moving[0]] if moving.size else c["time"][-1]
    return t_seen + (LONG - x_probe) / np.sqrt(G * (DEPTH - SHELF + AMPLITUDE))


def reflection(t, pts, h, long_run):
    """R = max |H_case - H_long| / A over the reflection probes and their windows, with the time
    and probe where it occurs (t, pts, h: the case's probes)."""
    tl, _, hl = probes(long_run)
    worst = (0.0, 0.0, 0)
    for k in REFLECTION_PROBES:
        tw = min(window_end(long_run, pts[k][0]), t[-1], tl[-1])
        sel = t <= tw
        diff = np.abs(h[k][sel] - np.interp(t[sel], tl, hl[k])) / AMPLITUDE
        i = int(np.nanargmax(diff))
        if diff[i] > worst[0]:
            worst = (float(diff[i]), float(t[sel][i]), k)
    return worst


def side_views(ax_list, run):
    frames = read_pvd(os.path.join(run, "particles.pvd"), part="0")
    bed_x = [0.0, RAMP[0], RAMP[1], LONG]
    bed_z = [0.0, 0.0, SHELF, SHELF]
    for ax, ts in zip(ax_list, SNAPSHOTS):
        if not frames:
            break
        t, path = min(frames, key=lambda f: abs(f[0] - ts))
        v = read_vtu(path)
        x, u = v["points"], v["velocity"]
        order = np.argsort(x[:, 1])[::-1]            # the near side (small y) drawn last
        sc = ax.scatter(x[order, 0], x[order, 2], c=np.linalg.norm(u[order], axis=1), s=4,
                        cmap="jet", vmin=0.0, vmax=3.0)
        ax.plot(bed_x, bed_z, "k-", lw=1)
        ax.set_xlim(-0.05, LENGTH + 0.05)
        ax.set_ylim(-0.05, 1.2)
        ax.set_aspect("equal")
        ax.set_title("t = %.2f s" % t, fontsize=9)
    return sc


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if not args:
        sys.exit(__doc__)
    run = args[0]
    long_run = sys.argv[sys.argv.index("--reference") + 1] if "--reference" in sys.argv else None
    dr = used_dr(run)
    t, pts, heads = probes(run)

    fig = plt.figure(figsize=(13, 10))
    views = [fig.add_subplot(4, 3, i + 1) for i in range(6)]
    sc = side_views(views, run)
    fig.colorbar(sc, ax=views, label="|u| [m/s]", shrink=0.6)
    ax = fig.add_subplot(4, 1, 3)
    for k, p in enumerate(pts):
        ax.plot(t, heads[k] / AMPLITUDE, lw=1, label="x = %.2f m" % p[0])
    ax.set_ylabel("head (p/ρ0g + z − D) / A")
    ax.legend(fontsize=7, ncol=4)
    ax.grid(True, alpha=0.3)
    ax = fig.add_subplot(4, 1, 4)
    R = None
    if long_run and os.path.exists(os.path.join(long_run, "probes.csv")):
        tl, _, hl = probes(long_run)
        for k in REFLECTION_PROBES:
            ax.plot(t, heads[k] / AMPLITUDE, lw=1, label="case, x = %.2f m" % pts[k][0])
            ax.plot(tl, hl[k] / AMPLITUDE, "--", lw=1, label="long channel, x = %.2f m" % pts[k][0])
            ax.axvline(window_end(long_run, pts[k][0]), color="grey", lw=0.5)
        R = reflection(t, pts, heads, long_run)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("head / A")
    if R is not None:
        ax.legend(fontsize=7, ncol=2)
    ax.grid(True, alpha=0.3)
    fig.suptitle("Solitary wave over a sloped bed, dr = %g m (A/dr = %.0f)" % (dr, AMPLITUDE / dr))
    out = os.path.join(run, "solitary_wave_3d.png")
    fig.savefig(out, dpi=110)
    print("wrote %s" % out)

    d = read_csv(os.path.join(run, "diagnostics.csv"))
    t_end = float(d["time"][-1])
    peak = [float(np.nanmax(h)) / AMPLITUDE for h in heads]
    print("dr = %g m: ran to t = %.3f s; peak head / A at the probes: %s" % (
        dr, t_end, ", ".join("%.2f" % v for v in peak)))
    if R is not None:
        print("reflection of the outlet: max |H_case - H_long| / A = %.4f (t = %.3f s, x = %.2f m)"
              % (R[0], R[1], pts[R[2]][0]))
    if "--check" not in sys.argv:
        return
    checks = Checks()
    text = open(os.path.join(run, "used_case.yaml")).read()
    end = float(text[text.index("end:", text.index("time:")):].split()[1])
    checks.require(t_end >= end - 1e-9, "the run reaches t = %g s" % end)
    g = read_csv(os.path.join(run, "probes.csv"))["eta0"]
    crest = float(np.nanmax(g)) - dr / 2 - DEPTH
    checks.require(abs(crest / AMPLITUDE - 1) <= 0.1,
                   "the wave enters with its amplitude: crest at x = %.2f m within 10 %% of A (%.3f m)"
                   % (pts[0][0], crest))
    balance = mass_balance(run)
    checks.require(balance <= 1e-12, "mass - entered + released constant to 1e-12 (%.1e)" % balance)
    checks.require(R is not None and R[0] <= BOUND,
                   "the outlet reflects <= %g A (head against the long channel)" % BOUND)
    checks.done()


if __name__ == "__main__":
    main()
