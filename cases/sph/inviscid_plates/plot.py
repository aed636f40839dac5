#!/usr/bin/python3
"""Inviscid flow between two plates (M §3.2): the energy budget of M(39) over t+ = t c0/H without
and with volume diffusion (the paper's Fig. 2), and the wall-normal velocity of every particle at
t+ = 0.5 and t+ = 9 (Fig. 3).

usage: plot.py OUTPUT_DIR [--check]
  OUTPUT_DIR holds the two runs `none/` (numerics.diffusion: none) and `ferrari/` (M 84), as
  written by ./check. Writes OUTPUT_DIR/inviscid_plates_energy.png and
  OUTPUT_DIR/inviscid_plates_velocity.png and prints the figures quoted in README.md.
  --check: exit status 1 unless every criterion of README.md holds.

Energy budget. Without viscosity the semi-discrete system conserves E = kinetic + internal +
potential exactly when Grad and Div are skew-adjoint (M 26-27); the time integral of their defect,
M(39), is therefore the change of E, which diagnostics.csv gives at every step:
  E+(t+) = [E(t) - E(0)] / (rho0 c0^2 H^2)   (energy per unit depth of a periodic cell H long),
positive when the discrete operators put energy into the flow.
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
from sabre_output import read_csv, read_pvd, read_vtu, used_dr  # noqa: E402

RHO0, C0, H = 1000.0, 10.0, 1.0  # as in case.yaml (dr is read from used_case.yaml)
E_SCALE = RHO0 * C0 * C0 * H * H
V_SCALE = C0 / 10.0
RUNS = (("none", "without volume diffusion"), ("ferrari", "with volume diffusion M(84)"))


def snapshot(run_dir, t_plus):
    """Fluid particles of the output nearest to t+ (from particles.pvd)."""
    best = None
    for t, f in read_pvd(os.path.join(run_dir, "particles.pvd"), part="0"):
        t = t * C0 / H
        if best is None or abs(t - t_plus) < abs(best[0] - t_plus):
            best = (t, f)
    if best is None:
        sys.exit("%s/particles.pvd: no fluid output listed" % run_dir)
    return best[0], read_vtu(best[1])


def noise(p, dr):
    """Departure from the exact 1D flow: rms of v_x, and rms of v_y minus the mean of its particle
    row (rows of W/dr particles never cross in a 1D flow), both over c0/10."""
    x, v = p["points"], p["velocity"]
    per_row = int(round(H / dr))  # the periodic cell is H wide
    order = np.argsort(x[:, 1], kind="stable")
    vy = v[order, 1].reshape(-1, per_row)
    dev = vy - vy.mean(axis=1, keepdims=True)
    return math.sqrt(np.mean(v[:, 0] ** 2)) / V_SCALE, math.sqrt(np.mean(dev ** 2)) / V_SCALE


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    checking = "--check" in sys.argv
    failures = []

    def require(ok, what):
        print("  %-4s %s" % ("ok" if ok else "FAIL", what))
        if not ok:
            failures.append(what)

    fig, ax = plt.subplots(figsize=(7, 4.2))
    res = {}
    for name, label in RUNS:
        d = read_csv(os.path.join(out, name, "diagnostics.csv"))
        tp = d["time"] * C0 / H
        e = d["kinetic"] + d["internal"] + d["potential"]
        ep = (e - e[0]) / E_SCALE
        ax.plot(tp, ep, label=label)
        # largest climb of E+ above its running minimum: energy put back into the flow
        rise = np.max(ep - np.minimum.accumulate(ep))
        res[name] = dict(tp=tp, ep=ep, rise=rise, mass=d["mass"], n=d["particles"],
                         vmax=d["max_speed"])
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(r"$t^+ = t c_0 / H$")
    ax.set_ylabel(r"$E^+ = [E(t) - E(0)] / (\rho_0 c_0^2 H^2)$")
    dr = used_dr(os.path.join(out, "none"))
    ax.set_title("Inviscid plates: energy budget M(39), H/dr = %d, h = 2 dr" % round(H / dr))
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "inviscid_plates_energy.png"), dpi=130)

    fig, axes = plt.subplots(1, 3, figsize=(11, 4.2), sharey=True)
    t0, p0 = snapshot(os.path.join(out, "none"), 0.5)
    axes[0].plot(p0["velocity"][:, 1] / V_SCALE, p0["points"][:, 1], ".", ms=2)
    axes[0].set_title(r"$t^+$ = %.2f (both runs alike)" % t0)
    for ax, (name, label) in zip(axes[1:], RUNS):
        t9, p9 = snapshot(os.path.join(out, name), 9.0)
        ax.plot(p9["velocity"][:, 1] / V_SCALE, p9["points"][:, 1], ".", ms=2)
        ax.set_title(r"$t^+$ = %.2f, %s" % (t9, label), fontsize=9)
        res[name]["noise"] = noise(p9, used_dr(os.path.join(out, name)))
        res[name]["t9"] = t9
    for ax in axes:
        ax.set_xlabel(r"$v^+ = v_y / (c_0/10)$")
    axes[0].set_ylabel("y / H")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "inviscid_plates_velocity.png"), dpi=130)
    print("wrote %s/inviscid_plates_energy.png and inviscid_plates_velocity.png" % out)

    for name, label in RUNS:
        r = res[name]
        dm = np.max(np.abs(r["mass"] - r["mass"][0])) / r["mass"][0]
        print("%s: t+ reached %.3f, E+ in [%.3e, %.3e], E+(end) = %.3e, largest climb of E+ above "
              "its running minimum %.2e, max |v|/(c0/10) %.3f, "
              "mass drift %.1e, particles %d..%d; at t+ = %.2f: rms v_x %.1e, rms row deviation of "
              "v_y %.1e (units of c0/10)"
              % (label, r["tp"][-1], r["ep"].min(), r["ep"].max(), r["ep"][-1], r["rise"],
                 r["vmax"].max() / V_SCALE, dm, r["n"].min(), r["n"].max(), r["t9"],
                 r["noise"][0], r["noise"][1]))
    if not checking:
        return
    print("criteria (README.md):")
    none, fer = res["none"], res["ferrari"]
    for name, label in RUNS:
        r = res[name]
        require(r["tp"][-1] > 9.0 - 1e-9, "%s: reaches t+ = 9" % label)
        require(np.max(np.abs(r["mass"] - r["mass"][0])) <= 1e-12 * r["mass"][0],
                "%s: total mass constant to 1e-12" % label)
        require(r["n"].min() == r["n"].max() == r["n"][0], "%s: no particle lost" % label)
        require(np.max(np.abs(r["ep"])) < 5e-3, "%s: |E+| < 5e-3 (energy defect bounded)" % label)
    require(none["rise"] > 2e-4,
            "without diffusion: E+ climbs back above its running minimum by > 2e-4 (the wall terms "
            "put energy in, M §3.2)")
    require(fer["rise"] < none["rise"] / 5.0,
            "with diffusion: E+ climbs less than a fifth of that (nearly monotone dissipation)")
    require(fer["ep"][-1] < 0.0, "with diffusion: E+(9) < 0 (the diffusion term dissipates)")
    require(fer["ep"][-1] < none["ep"][-1] - 5e-4,
            "diffusion lowers E+(9) by more than 5e-4")
    require(fer["noise"][0] < 1e-10, "with diffusion: rms v_x at t+ = 9 stays at round-off (< 1e-10)")
    require(none["noise"][0] > 100.0 * max(fer["noise"][0], 1e-16),
            "without diffusion: rms v_x at t+ = 9 grows above 100x the diffused run (numerical "
            "turbulence, M Fig. 3)")
    require(fer["noise"][1] < none["noise"][1],
            "diffusion lowers the row deviation of v_y at t+ = 9")
    if failures:
        sys.exit("check failed: %d criterion(s)" % len(failures))
    print("all criteria hold")


if __name__ == "__main__":
    main()
