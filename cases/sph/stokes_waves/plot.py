#!/usr/bin/python3
"""Stokes waves through open boundaries (J §IV.B): the free-surface error eps_eta of J(41) over
time (J Fig. 8) and the free surface at the last output against Fenton's fifth-order wave (J Fig. 7).

usage: plot.py OUTPUT_DIR [OTHER_DIR ...] [--sabre SABRE_SPH] [--check]
  Each directory is a run of case.yaml or periodic.yaml (any dr: read from its used_case.yaml).
  Writes FIRST_DIR/stokes_waves.png and prints the figures of README.md. --check: exit status 1
  unless every criterion of README.md holds for every run given (the run reaches the end time of
  its used_case.yaml, and eps_eta <= dr/A at every sample). --sabre: the sabre-sph that evaluates
  the analytical wave (`sabre-sph wave stokes5`; default: build/sph/sabre-sph beside cases/, then
  the PATH).

eps_eta(t) = sqrt(mean over the gauges of (eta_sim - eta)^2) / A, with eta_sim the gauges' level
(probes.csv: the highest fluid particle within h of the gauge's vertical + dr/2) and eta Fenton's
wave at the gauge and time (J(41) takes the free-surface particles; the gauges sample the same
surface at fixed x, every probes row).
"""
import json
import os
import re
import shutil
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import Checks, mass_balance, read_csv, used_dr  # noqa: E402

DEPTH, AMPLITUDE, LENGTH = 0.5, 0.05, 2.5   # J §IV.B [m]


def sabre_exe(argv):
    if "--sabre" in argv:
        return argv[argv.index("--sabre") + 1]
    here = os.path.dirname(os.path.abspath(__file__))
    build = os.environ.get("SABRE_BUILD", os.path.join(here, "..", "..", "..", "build"))
    exe = os.path.join(build, "sph", "sabre-sph")
    return exe if os.access(exe, os.X_OK) else shutil.which("sabre-sph")


def wave_profile(exe, n=1000):
    """Fenton's surface over one wave length at t = 0 (crest at x = 0), and the phase speed c."""
    xs = np.linspace(0.0, LENGTH, n, endpoint=False)
    args = [exe, "wave", "stokes5", "--depth", str(DEPTH), "--amplitude", str(AMPLITUDE),
            "--length", str(LENGTH)]
    for x in xs:
        args += ["--at", "%.17g,0,0" % x]
    rows = [json.loads(line) for line in subprocess.run(
        args, check=True, capture_output=True, text=True).stdout.splitlines()]
    return xs, np.array([r["eta"] for r in rows]), rows[0]["c"], rows[0]["T"]


def eta_exact(profile, x, t):
    xs, eta, c, _ = profile
    xi = np.mod(np.asarray(x) - c * t, LENGTH)
    return np.interp(xi, np.append(xs, LENGTH), np.append(eta, eta[0]))


def run_info(out):
    text = open(os.path.join(out, "used_case.yaml")).read()
    end = float(re.search(r"^\s*end:\s*([0-9.eE+-]+)", text, re.M).group(1))
    block = re.search(r"^(\s*)gauges:(.*?)(?=^\1?[A-Za-z_]+:|\Z)", text, re.M | re.S).group(2)
    xs = [float(m.group(1)) for m in
          re.finditer(r"\[\s*([0-9.eE+-]+)\s*,\s*[0-9.eE+-]+\s*\]", block)]
    label = "periodic" if re.search(r"^\s*periodic:", text, re.M) else "open"
    return end, np.array(xs), label


def main():
    argv = sys.argv[1:]
    exe = sabre_exe(argv)
    dirs = [a for i, a in enumerate(argv)
            if not a.startswith("--") and (i == 0 or argv[i - 1] != "--sabre")]
    if not dirs or not exe:
        sys.exit(__doc__)
    profile = wave_profile(exe)
    period = profile[3]
    print("Fenton's wave: d = %g m, A = %g m, L = %g m: c = %.5f m/s, T = %.5f s"
          % (DEPTH, AMPLITUDE, LENGTH, profile[2], period))
    checks = Checks() if "--check" in argv else None
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7))
    for k, out in enumerate(dirs):
        dr = used_dr(out)
        end, gx, label = run_info(out)
        g = read_csv(os.path.join(out, "probes.csv"))
        t = g["time"]
        sim = np.array([g["eta%d" % i] for i in range(len(gx))])        # [gauge, row]
        exact = np.array([eta_exact(profile, gx, ti) for ti in t]).T
        eps = np.sqrt(np.mean((sim - exact) ** 2, axis=0)) / AMPLITUDE
        t_end = float(t[-1])
        worst = int(np.argmax(eps))
        periods = t_end / period
        print("%s, dr = %g m (A/dr = %g): run to t = %g s (%.2f periods; end %g s)"
              % (label, dr, AMPLITUDE / dr, t_end, periods, end))
        print("  eps_eta: largest %.4f at t = %.3f s, mean %.4f, last %.4f (dr/A = %.4f)"
              % (eps[worst], t[worst], np.mean(eps), eps[-1], dr / AMPLITUDE))
        for p in range(1, int(periods) + 1):
            sel = (t > (p - 1) * period) & (t <= p * period)
            print("  period %d: largest eps_eta %.4f, mean level error %+.2f mm"
                  % (p, np.max(eps[sel]), 1e3 * np.mean(sim[:, sel] - exact[:, sel])))
        color = "C%d" % k
        ax1.plot(t / period, eps, color=color, label="%s, A/dr = %g" % (label, AMPLITUDE / dr))
        ax1.axhline(dr / AMPLITUDE, color=color, ls="--", lw=0.8)
        ax2.plot(gx, sim[:, -1], "o", ms=3, color=color,
                 label="%s, A/dr = %g, t = %.2f s" % (label, AMPLITUDE / dr, t_end))
        xf = np.linspace(gx.min(), gx.max(), 400)
        ax2.plot(xf, eta_exact(profile, xf, t_end), "-", color=color, lw=1,
                 label="Fenton (1985) at t = %.2f s" % t_end)
        if checks:
            checks.require(t_end >= end - 1e-9 * max(end, 1.0),
                           "%s, A/dr = %g: the run reaches t = %g s" % (label, AMPLITUDE / dr, end))
            checks.require(np.max(eps) <= dr / AMPLITUDE,
                           "%s, A/dr = %g: eps_eta <= dr/A = %.3f at every sample (largest %.4f)"
                           % (label, AMPLITUDE / dr, dr / AMPLITUDE, np.max(eps)))
            balance = mass_balance(out)
            if balance is not None:
                checks.require(balance <= 1e-12,
                               "%s, A/dr = %g: mass - entered + released constant to 1e-12 (%.1e)"
                               % (label, AMPLITUDE / dr, balance))
    ax1.set_xlabel("t / T")
    ax1.set_ylabel(r"$\varepsilon_\eta$, J(41)")
    ax1.set_title("Free-surface error (J Fig. 8); dashed: dr/A")
    ax1.legend(fontsize=8)
    ax2.set_xlabel("x [m]")
    ax2.set_ylabel(r"$\eta$ [m]")
    ax2.set_title("Free surface at the last sample (J Fig. 7)")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    png = os.path.join(dirs[0], "stokes_waves.png")
    fig.savefig(png, dpi=120)
    print("wrote %s" % png)
    if checks:
        checks.done()


if __name__ == "__main__":
    main()
