#!/usr/bin/python3
"""Rapidly expanding pipe (J §IV.A): the head along the axis as J Fig. 5, the head gradients of the
two Poiseuille flows against J(37), the head loss against J(40), the velocity profiles against
J(36), and the mass balance of the open boundaries.

usage: plot.py OUTPUT_DIR [OUTPUT_DIR ...] [--check]
  Writes expanding_pipe.png into the first OUTPUT_DIR and prints the figures quoted in README.md
  for each run (finest first is not required: runs are told apart by their dr).
  --check: exit status 1 unless every criterion of README.md holds for every run given.

The head H(x) = Û²/(2g) + P/(ρ g), J(39), with P and Û² the means of p and |u|² over the fluid
particles of a slice dr wide, averaged over the outputs from T_AVG to the end (the inflow's ramp is
over by then; the average spans several acoustic periods). ρ is the mean fluid density over the same
outputs (the outlet's pressure level compresses the fluid a little; the viscous pressure drops are
proportional to it, the head drops are not). Theory, with U1 the inlet's centre-line speed and the
plates' Poiseuille flows (U2 = U1 R1/R2 by continuity):
  dH/dx = -2 nu U / (g R^2)   in each pipe, J(37)
  H1 - H2 = (Û1 - Û2)^2/(2g) + 2 nu U1 L1/(g R1^2) + 2 nu U2 L2/(g R2^2), J(40) with the
  Poiseuille drops over the whole lengths, Û = sqrt(8/15) U the root mean square of the profile.
The measured loss is the difference of the straight lines fitted to H in the developed parts of
pipe 1 and pipe 2, taken at the inlet (x = -L1) and at the outlet (x = L2). reference_head.csv
(reference.py: the steady Navier-Stokes flow of the same problem on a fine grid) gets the same
fits. Two more measures of the gradients: the head on the axis from the time-mean pressure of the
probes (probes.csv, every other step; the outputs alias pressure waves of 7-26 s periods whose
gradient is ±40 % of the viscous one), and the viscous balance nu u''/g from the curvature of the
velocity profiles over the fit ranges (what the pressure gradient must balance where the flow is
developed).
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import yaml  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import (Checks, mass_balance, read_csv, read_pvd, read_vtu,  # noqa: E402
                          beyond_flux_rate, time_mean, used_dr)

G = 9.81                      # for the head only (the flow has no gravity)
NU = 3.19e-5                  # as in case.yaml
R1, R2 = 0.13, 0.26
L1, L2 = 3 * R1, 4 * R2
U1 = 0.0025274                # inlet centre-line speed, nu Re / (2 R1), Re = 20.6
U2 = U1 * R1 / R2
T_AVG = 900.0                 # start of the averaging window [s] (the ramp ends at 600 s)
FIT1 = (-0.30, -0.08)         # developed Poiseuille flow in pipe 1 (x range of the fit)
FIT2 = (0.60, 0.95)           # and in pipe 2, downstream of the recirculation zones
PROFILE_X = (-0.20, 0.80)     # where the velocity profiles are compared with J(36)


def slope_theory(u, r):
    return -2.0 * NU * u / (G * r * r)


def borda():
    return (math.sqrt(8.0 / 15.0) * (U1 - U2)) ** 2 / (2.0 * G)


def loss_theory():
    return -slope_theory(U1, R1) * L1 - slope_theory(U2, R2) * L2 + borda()


def fits(x, head):
    """Straight lines fitted to the head over FIT1 (pipe 1) and FIT2 (pipe 2)."""
    m1 = (x > FIT1[0]) & (x < FIT1[1])
    m2 = (x > FIT2[0]) & (x < FIT2[1])
    return np.polyfit(x[m1], head[m1], 1), np.polyfit(x[m2], head[m2], 1)


def reference():
    """The Navier-Stokes head of reference_head.csv, its fits and its loss."""
    ref = read_csv(os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference_head.csv"))
    a1, a2 = fits(ref["x"], ref["H"])
    return dict(x=ref["x"], head=ref["H"], a1=a1, a2=a2,
                loss=float(np.polyval(a1, -L1) - np.polyval(a2, L2)))


def analyse(out):
    """Head profile and figures of one run."""
    dr = used_dr(out)
    edges = np.arange(-L1, L2 + 0.5 * dr, dr)
    nbin = len(edges) - 1
    psum, u2sum, count = np.zeros(nbin), np.zeros(nbin), np.zeros(nbin)
    rho, prof, curv = [], {x: ([], []) for x in PROFILE_X}, ([], [])
    frames = [(t, f) for t, f in read_pvd(os.path.join(out, "particles.pvd"), part="0")
              if t >= T_AVG - 1e-9]
    for _, f in frames:
        d = read_vtu(f)
        x, y = d["points"][:, 0], d["points"][:, 1]
        u, p = d["velocity"], d["pressure"]
        rho.append(d["density"].mean())
        k = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, nbin - 1)
        np.add.at(psum, k, p)
        np.add.at(u2sum, k, (u ** 2).sum(axis=1))
        np.add.at(count, k, 1)
        # the curvature of the velocity profile over each fit range: u = c0 + c2 y², whose viscous
        # head gradient ν u''/g = 2 ν c2 / g is what the pressure must balance in developed flow
        for k, (lo, hi) in enumerate((FIT1, FIT2)):
            m = (x > lo) & (x < hi)
            curv[k].append(2.0 * NU * np.polyfit(y[m] ** 2, u[m, 0], 1)[0] / G)
        for x0 in PROFILE_X:
            m = np.abs(x - x0) < 0.5 * dr + 1e-12
            prof[x0][0].extend(y[m])
            prof[x0][1].extend(u[m, 0])
    rho = float(np.mean(rho))
    xc = 0.5 * (edges[1:] + edges[:-1])
    seen = count > 0
    xc, u2 = xc[seen], u2sum[seen] / count[seen]
    head = u2 / (2 * G) + (psum[seen] / count[seen]) / (rho * G)
    a1, a2 = fits(xc, head)
    # the head on the axis: the probes' time-mean pressure (every other step, dt-weighted) and the
    # slices' Û²
    with open(os.path.join(out, "used_case.yaml")) as fh:
        px = np.array([pt[0] for pt in yaml.safe_load(fh)["probes"]["pressure"]])
    pr = read_csv(os.path.join(out, "probes.csv"))
    pmean = np.array([time_mean(pr["time"], pr["p%d" % i], T_AVG) for i in range(len(px))])
    phead = np.interp(px, xc, u2) / (2 * G) + pmean / (rho * G)
    b1, b2 = fits(px, phead)
    errs = {}
    for x0, (ys, us) in prof.items():
        ys, us = np.array(ys), np.array(us)
        r, umax = (R1, U1) if x0 < 0 else (R2, U2)
        errs[x0] = float(np.mean(np.abs(us - umax * (1 - (ys / r) ** 2))) / umax)
    fin = read_csv(os.path.join(out, "open_inlet.csv"))
    fout = read_csv(os.path.join(out, "open_outlet.csv"))
    # time means of the mass fluxes over the window; the outlet's with the mass its deleted
    # particles took out beyond what its vertices took back, less what its vertices did not take
    # (docs/sph-solver.md §10)
    qin = time_mean(fin["time"], fin["mass_flux"], T_AVG)
    qout = -time_mean(fout["time"], fout["mass_flux"], T_AVG) + beyond_flux_rate(fout, T_AVG)
    diag = read_csv(os.path.join(out, "diagnostics.csv"))
    wd = diag["time"] >= T_AVG
    mass = diag["mass"][wd]
    return dict(out=out, dr=dr, x=xc, head=head, px=px, phead=phead, a1=a1, a2=a2, b1=b1, b2=b2,
                visc=(float(np.mean(curv[0])), float(np.mean(curv[1]))), rho=rho, nframes=len(frames),
                loss=float(np.polyval(a1, -L1) - np.polyval(a2, L2)),
                jump=float(np.polyval(a1, 0.0) - np.polyval(a2, 0.0)), prof=prof, errs=errs,
                qin=qin, qout=qout, mass_drift=float(mass[-1] / mass[0] - 1),
                t_end=float(diag["time"][-1]))


def report(r):
    s1, s2 = slope_theory(U1, R1), slope_theory(U2, R2)
    print("dr = %g m (R1/%.0f): %d outputs from t = %g s to %g s; mean density %.4f rho0"
          % (r["dr"], R1 / r["dr"], r["nframes"], T_AVG, r["t_end"], r["rho"] / 1190.0))
    print("  head gradient pipe 1 %.4e (J37 %.4e, %+.1f %%), pipe 2 %.4e (J37 %.4e, %+.1f %%)"
          % (r["a1"][0], s1, 100 * (r["a1"][0] / s1 - 1), r["a2"][0], s2, 100 * (r["a2"][0] / s2 - 1)))
    print("  head loss inlet to outlet %.4e m (J40 %.4e m, %+.1f %%; J's simulation 5.04e-7, its "
          "J40 5.00e-7); jump of the fits at x = 0 %.3e m (Borda-Carnot %.3e m)"
          % (r["loss"], loss_theory(), 100 * (r["loss"] / loss_theory() - 1), r["jump"], borda()))
    ref = reference()
    print("  the same fits on the Navier-Stokes reference: gradients %+.1f %% and %+.1f %%, loss %+.1f %%"
          % (100 * (r["a1"][0] / ref["a1"][0] - 1), 100 * (r["a2"][0] / ref["a2"][0] - 1),
             100 * (r["loss"] / ref["loss"] - 1)))
    print("  on the axis (time-mean probes): head gradients %+.1f %% and %+.1f %% of J37"
          % (100 * (r["b1"][0] / s1 - 1), 100 * (r["b2"][0] / s2 - 1)))
    print("  the viscous balance (nu u''/g of the profiles' curvature over the fit ranges): %+.1f %% "
          "and %+.1f %% of J37" % (100 * (r["visc"][0] / s1 - 1), 100 * (r["visc"][1] / s2 - 1)))
    print("  velocity profiles, mean |u - J36| / U_max: x = %g m %.4f, x = %g m %.4f"
          % (PROFILE_X[0], r["errs"][PROFILE_X[0]], PROFILE_X[1], r["errs"][PROFILE_X[1]]))
    print("  mass flux in %.5f kg/(m s), out %.5f (%+.2f %%); mass in the pipe (fluid and "
          "vertices) %+.2f %% over the window" % (r["qin"], r["qout"], 100 * (r["qout"] / r["qin"] - 1),
                                                 100 * r["mass_drift"]))


def plot(runs, path):
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.6), gridspec_kw={"width_ratios": [1.6, 1]})
    ref = reference()
    # the reference's level is p = 0 at the outlet: drawn through the finest run's outlet head
    lift = np.polyval(runs[0]["a2"], L2) - np.polyval(ref["a2"], L2)
    ax.plot(ref["x"], (ref["head"] + lift) * 1e6, "-", color="0.5", lw=2.5, alpha=0.6,
            label="Navier-Stokes reference (through the outlet head)")
    for r in runs:
        line, = ax.plot(r["x"], r["head"] * 1e6, ".-", ms=3, lw=0.8,
                        label="SPH, dr = R1/%.0f" % (R1 / r["dr"]))
        ax.plot(r["px"], r["phead"] * 1e6, "x", color=line.get_color(), ms=3,
                label="SPH, dr = R1/%.0f, axis (probes)" % (R1 / r["dr"]))
    r = runs[0]
    # J Fig. 5: the theoretical gradients through the fitted heads at the inlet and at the outlet,
    # and the Borda-Carnot loss at the expansion
    x1, x2 = np.array([-L1, 0.0]), np.array([0.0, L2])
    h_in, h_out = np.polyval(r["a1"], -L1), np.polyval(r["a2"], L2)
    ax.plot(x1, 1e6 * (h_in + slope_theory(U1, R1) * (x1 + L1)), "k--", lw=1,
            label="Poiseuille gradients J(37)")
    ax.plot(x2, 1e6 * (h_out + slope_theory(U2, R2) * (x2 - L2)), "k--", lw=1)
    h0 = h_in + slope_theory(U1, R1) * L1
    ax.annotate("", xy=(0.02, 1e6 * (h0 - borda())), xytext=(0.02, 1e6 * h0),
                arrowprops=dict(arrowstyle="<->", color="r"))
    ax.text(0.04, 1e6 * (h0 - 0.5 * borda()), "Borda-Carnot", color="r", fontsize=8)
    ax.axvline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("x [m]")
    ax.set_ylabel(r"head $H = \hat U^2/2g + P/\rho g$ [$\mu$m]")
    ax.set_title("Expanding pipe (J Fig. 5): loss %.3g m, J(40) %.3g m" % (r["loss"], loss_theory()))
    ax.legend(fontsize=8)
    for x0, (ys, us) in r["prof"].items():
        rr, umax = (R1, U1) if x0 < 0 else (R2, U2)
        bx.plot(np.array(us) * 1e3, ys, ".", ms=2, label="SPH x = %g m" % x0)
        yy = np.linspace(-rr, rr, 101)
        bx.plot(umax * (1 - (yy / rr) ** 2) * 1e3, yy, "k-", lw=0.8)
    bx.set_xlabel("u [mm/s]")
    bx.set_ylabel("y [m]")
    bx.set_title("profiles against J(36) (black)")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    dirs = [a for a in sys.argv[1:] if not a.startswith("--")]
    if not dirs:
        sys.exit(__doc__)
    runs = sorted((analyse(d) for d in dirs), key=lambda r: r["dr"])
    ref = reference()
    print("Navier-Stokes reference (reference_head.csv): gradients %.4e and %.4e (J37 %+.1f %% and "
          "%+.1f %%), loss %.4e m (J40 %+.1f %%)"
          % (ref["a1"][0], ref["a2"][0], 100 * (ref["a1"][0] / slope_theory(U1, R1) - 1),
             100 * (ref["a2"][0] / slope_theory(U2, R2) - 1), ref["loss"],
             100 * (ref["loss"] / loss_theory() - 1)))
    for r in runs:
        report(r)
    plot(runs, os.path.join(dirs[0], "expanding_pipe.png"))
    if "--check" not in sys.argv:
        return
    checks = Checks()
    for r in runs:
        tag = "dr = R1/%.0f: " % (R1 / r["dr"])
        checks.require(r["t_end"] >= 1500 - 1e-6, tag + "the run reaches t = 1500 s")
        checks.require(abs(r["qout"] / r["qin"] - 1) <= 0.01,
                       tag + "mean outflow within 1 % of the inflow over the window")
        checks.require(max(r["errs"].values()) <= 0.03,
                       tag + "velocity profiles within 3 % (mean |u - J36| / U_max) in both pipes")
        checks.require(abs(r["visc"][0] / slope_theory(U1, R1) - 1) <= 0.06,
                       tag + "viscous balance of pipe 1 (nu u''/g) within 6 % of J(37)")
        checks.require(abs(r["a1"][0] / slope_theory(U1, R1) - 1) <= 0.10,
                       tag + "head gradient of pipe 1 within 10 % of J(37)")
        checks.require(abs(r["loss"] / loss_theory() - 1) <= 0.20,
                       tag + "head loss within 20 % of J(40)")
        balance = mass_balance(r["out"])
        checks.require(balance <= 1e-12, tag + "mass - entered + released constant to 1e-12 (%.1e)"
                       % balance)
    checks.done()


if __name__ == "__main__":
    main()
