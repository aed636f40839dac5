#!/usr/bin/python3
"""Dam break over a wedge (M §8): the pressure force on the left wedge wall over time with and
without volume diffusion (the paper's Fig. 10), and the particles at the times of Fig. 11.

usage: plot.py OUTPUT_DIR [--check [--quick]]
  OUTPUT_DIR holds the runs `ferrari/` (numerics.diffusion: ferrari, M 84), `none/` and `fine/`
  (ferrari at dr = 0.0125 m), as written by ./check (a single run directory with forces.csv is plotted alone). Writes
  OUTPUT_DIR/dam_break_wedge_force.png and OUTPUT_DIR/dam_break_wedge_snapshots.png and prints the
  figures quoted in README.md. --check: exit status 1 unless every criterion of README.md holds
(--quick: without the run at dr = 0.0125 m).

The force is the one the paper plots, the integral of the pressure along the wall: forces.csv gives
the vector F of the fluid on the wall (wall group `wedge_left`); its component along the wall's
outward normal, F = F . (sin 60°, -cos 60°), is positive when the water pushes on the wedge.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# the shared readers of sabre-sph output: cases/sph/sabre_output.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import Checks, read_csv, read_pvd, read_vtu  # noqa: E402

# as in case.yaml
RHO0, C0, XI, G, H_COL = 1000.0, 40.0, 7.0, 9.81, 1.0
WALL_L = 0.25  # side of the equilateral wedge [m]
PUSH = (math.sin(math.radians(60.0)), -math.cos(math.radians(60.0)))  # out of the fluid
RUNS = (("ferrari", "with volume diffusion M(84)"), ("none", "without volume diffusion"),
        ("fine", "with volume diffusion, dr = 0.0125 m"))
COLORS = {"ferrari": "tab:blue", "none": "tab:orange", "fine": "tab:green", ".": "tab:blue"}
DIFFUSED = ("ferrari", "fine")  # the runs with diffusion (and their labels in the criteria)
SNAP_TIMES = (0.25, 0.5, 0.75, 1.1, 2.0, 2.5)  # Fig. 11 has 0.5, 0.75, 1.1 and 2.5 s


def outputs(run_dir):
    """(time, fluid file, boundary file) of every output listed in particles.pvd."""
    files = {}
    for part in ("0", "1"):
        for t, f in read_pvd(os.path.join(run_dir, "particles.pvd"), part=part):
            files.setdefault(t, {})[part] = f
    return sorted((t, f.get("0"), f.get("1")) for t, f in files.items())


def force(run_dir):
    f = read_csv(os.path.join(run_dir, "forces.csv"))
    return f["time"], f["wedge_left_fx"] * PUSH[0] + f["wedge_left_fy"] * PUSH[1]


def smooth(t, f, width):
    """Centred moving average over `width` seconds (rows are not evenly spaced)."""
    out = np.empty_like(f)
    for i, ti in enumerate(t):
        sel = np.abs(t - ti) <= 0.5 * width
        out[i] = f[sel].mean()
    return out


def figures(t, f, t_noise_end):
    """Impact time (F first above 100 N), peak of the 0.02 s mean and its time, raw maximum,
    mean over t >= 1.5 s, rms of F minus its 0.05 s mean over t >= 0.4 s (noise)."""
    hit = np.nonzero(f > 100.0)[0]
    t_hit = t[hit[0]] if len(hit) else math.nan
    fs = smooth(t, f, 0.02)  # the one- or two-step acoustic spikes of the impact left out
    k = int(np.argmax(fs))
    late = t >= 1.5
    calm = (t >= 0.4) & (t <= t_noise_end)
    noise = f - smooth(t, f, 0.05)
    return dict(t_hit=t_hit, peak=fs[k], t_peak=t[k], spike=f.max(), end=t[-1],
                late=f[late].mean() if late.any() else math.nan,
                noise=math.sqrt(np.mean(noise[calm] ** 2)) if calm.any() else math.nan)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    checking = "--check" in sys.argv
    runs = [(n, l) for n, l in RUNS if os.path.exists(os.path.join(out, n, "forces.csv"))]
    if not runs and os.path.exists(os.path.join(out, "forces.csv")):
        runs = [(".", "this run")]
    if not runs:
        sys.exit("%s: no forces.csv (run ./check or sabre-sph run case.yaml --output %s)" % (out, out))

    f_scale = RHO0 * G * H_COL * WALL_L  # hydrostatic pressure of the column over the wall
    # Ritter's ideal front leaves the column (x = 0.5 m) at 2 sqrt(g H): nothing arrives earlier
    t_ritter = (0.85 - 0.5) / (2.0 * math.sqrt(G * H_COL))
    # settled state: the water (0.5 m^2) at rest over the floor and the wedge
    wedge_h = WALL_L * math.sin(math.radians(60.0))
    depth = (0.5 + 0.5 * WALL_L * wedge_h) / 2.2
    f_rest = RHO0 * G * WALL_L * (depth - 0.5 * wedge_h)

    fig, ax = plt.subplots(figsize=(8, 4.5))
    res = {}
    # the noise is compared over the time both runs have (the run without diffusion may stop)
    t_common = min(force(os.path.join(out, name))[0][-1] for name, _ in runs)
    order = sorted(runs, key=lambda r: r[0] != "none")  # without diffusion first, under the others
    for name, label in order:
        t, f = force(os.path.join(out, name))
        ax.plot(t, f, lw=0.8, label=label, color=COLORS[name])
        res[name] = figures(t, f, t_common)
        d = read_csv(os.path.join(out, name, "diagnostics.csv"))
        res[name]["mass"] = d["mass"]
        res[name]["n"] = d["particles"]
    ax.axhline(f_rest, color="k", ls="--", lw=0.8, label="water at rest (hydrostatic), %.0f N" % f_rest)
    ax.set_xlim(0, 2)
    ax.set_ylim(-500, max(2000, 1.1 * max(r["peak"] for r in res.values())))
    ax.set_xlabel("time [s]")
    ax.set_ylabel("force on the left wedge wall [N/m]")
    ax.set_title("Dam break over a wedge (M Fig. 10)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "dam_break_wedge_force.png"), dpi=130)

    name0 = runs[0][0]
    series = outputs(os.path.join(out, name0))
    times = [ts for ts in SNAP_TIMES if ts <= series[-1][0] + 1e-9]
    fig, axes = plt.subplots(len(times), 1, figsize=(8, 2.2 * len(times)), sharex=True,
                             squeeze=False)
    axes = axes[:, 0]
    for ax, ts in zip(axes, times):
        t, ffile, bfile = min(series, key=lambda s: abs(s[0] - ts))
        p = read_vtu(ffile)
        b = read_vtu(bfile)
        x = p["points"]
        pres = RHO0 * C0 * C0 / XI * ((p["density"] / RHO0) ** XI - 1.0)
        sc = ax.scatter(x[:, 0], x[:, 1], c=pres / 1e3, s=1.5, cmap="viridis", vmin=0, vmax=12)
        conn = b["connectivity"].reshape(-1, 2)
        xv = b["points"]
        for i, j in conn:
            ax.plot(xv[[i, j], 0], xv[[i, j], 1], "k-", lw=0.6)
        ax.set_aspect("equal")
        ax.set_ylim(-0.05, 1.1)
        ax.set_title("t = %.2f s (%s)" % (t, dict(runs)[name0]), fontsize=9)
        fig.colorbar(sc, ax=ax, label="p [kPa]", shrink=0.8)
    axes[-1].set_xlabel("x [m]")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "dam_break_wedge_snapshots.png"), dpi=110)
    print("wrote %s/dam_break_wedge_force.png and dam_break_wedge_snapshots.png" % out)

    for name, label in runs:
        r = res[name]
        dm = np.max(np.abs(r["mass"] - r["mass"][0])) / r["mass"][0]
        print("%s: to t = %.3f s; impact (F > 100 N) at %.3f s; peak of the 0.02 s mean %.0f N at "
              "%.3f s (%.2f rho g H L), raw maximum %.0f N; mean F over t >= 1.5 s %.0f N (%.2f x "
              "at rest, %.0f N); rms of F minus its 0.05 s mean over 0.4-%.2f s %.0f N; mass drift "
              "%.1e; particles %d..%d"
              % (label, r["end"], r["t_hit"], r["peak"], r["t_peak"], r["peak"] / f_scale, r["spike"], r["late"],
                 r["late"] / f_rest, f_rest, t_common, r["noise"], dm, r["n"].min(), r["n"].max()))
    if not checking:
        return
    checks = Checks()
    if len(runs) < 2:
        checks.require(False, "both runs present")
    for name, label in runs:
        r = res[name]
        checks.require(np.max(np.abs(r["mass"] - r["mass"][0])) <= 1e-12 * r["mass"][0],
                "%s: total mass constant to 1e-12" % label)
        checks.require(r["n"].min() == r["n"].max() == r["n"][0], "%s: no particle lost" % label)
        checks.require(t_ritter <= r["t_hit"] <= 0.3,
                "%s: the front reaches the wedge after Ritter's ideal front (%.3f s), before 0.3 s"
                % (label, t_ritter))
    for name in DIFFUSED:
        if name not in res:
            if name == "fine" and len(runs) > 1 and "--quick" not in sys.argv:
                checks.require(False, "the run at dr = 0.0125 m present (fine/)")
            continue
        r, label = res[name], dict(RUNS)[name]
        checks.require(r["end"] >= 2.0 - 1e-9, "%s: the run reaches 2 s" % label)
        checks.require(0.8 <= r["late"] / f_rest <= 1.5,
                "%s: mean force over 1.5-2 s is 0.8-1.5 x the hydrostatic force at "
                "rest (settling)" % label)
        checks.require(0.4 <= r["peak"] / f_scale <= 1.5,
                "%s: peak of the 0.02 s mean force 0.4-1.5 rho g H L (dam-break "
                "pressures are of order rho g H)" % label)
    if "none" in res:
        checks.require(res["none"]["end"] >= 1.0, "without diffusion: the run reaches at least 1 s")
    if "none" in res and "ferrari" in res:
        checks.require(res["ferrari"]["noise"] < res["none"]["noise"],
                "diffusion reduces the force noise after the impact (M §8)")
    checks.done()


if __name__ == "__main__":
    main()
