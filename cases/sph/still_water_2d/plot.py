#!/usr/bin/python3
"""Still water (M §7.1, Fig. 8): free-surface elevation, energies and the final hydrostatic
pressure for the gravity-corrected diffusion (default, local form of M 81), the paper's linear M(81)
and the uncorrected Ferrari term M(49).
usage: plot.py OUTPUT_DIR [--check]
  OUTPUT_DIR holds the runs of ./check: corrected/ (the case as committed), linear/, uncorrected/.
  Writes OUTPUT_DIR/still_water_2d.png and prints the measured figures; --check: exit status 1
  unless every criterion of README.md holds."""
import glob
import math
import os
import sys

# the shared readers of sabre-sph output: cases/sph/sabre_output.py
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from sabre_output import read_csv, read_vtu  # noqa: E402

RHO0, C0, XI, G, H, DR = 1000.0, 20.0, 7.0, 9.81, 1.025, 0.05
B = RHO0 * C0 * C0 / XI


def hydrostatic(depth):
    """Exact hydrostatic pressure of the Tait EOS at a depth (as the initial state)."""
    if depth <= 0:
        return 0.0
    return B * ((1 + (XI - 1) * G * depth / C0**2) ** (XI / (XI - 1)) - 1)


def surface(run):
    p = read_csv(f"{run}/probes.csv", lists=True)
    etas = [k for k in p if k.startswith("eta")]
    return p["time"], [sum(p[k][i] for k in etas) / len(etas) for i in range(len(p["time"]))]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    check = "--check" in sys.argv
    ok = True

    def crit(name, good, text):
        nonlocal ok
        ok &= good
        print(f"{'ok  ' if good else 'FAIL'} {name}: {text}")

    runs = {"corrected": "gravity-corrected, local (default)", "linear": "M(81) as printed",
            "uncorrected": "uncorrected M(49)"}
    d = read_csv(f"{out}/corrected/diagnostics.csv", lists=True)
    m0 = d["mass"][0]
    dm = max(abs(m / m0 - 1) for m in d["mass"])
    crit("mass", dm <= 1e-12, f"max |M/M0 - 1| = {dm:.2e} (<= 1e-12)")
    crit("particles", min(d["particles"]) == max(d["particles"]) == d["particles"][0],
         f"{int(d['particles'][0])} throughout")
    t_end = d["time"][-1]
    umax, ref = d["max_speed"][-1], 0.01 * math.sqrt(G * H)
    crit("rest", t_end >= 20 * math.sqrt(H / G) - 1e-9 and umax < ref,
         f"max|u| = {umax:.3e} m/s at t = {t_end:.3f} s = {t_end / math.sqrt(H / G):.1f} sqrt(H/g)"
         f" (< 1% sqrt(gH) = {ref:.3e})")
    last = sorted(glob.glob(f"{out}/corrected/fluid_*.vtu"))[-1]
    v = read_vtu(last, tuples=True)
    err2, n = 0.0, 0
    ys, ps, pe = [], [], []
    for (x, y, _), (p,) in zip(v["points"], v["pressure"]):
        ph = hydrostatic(H - y)
        err2 += (p - ph) ** 2
        n += 1
        ys.append(y), ps.append(p), pe.append(ph)
    l2 = math.sqrt(err2 / n) / (RHO0 * G * H)
    crit("hydrostatic", l2 < 0.02, f"L2(p - p_hydro)/(rho0 g H) = {100 * l2:.2f} % (< 2 %) in {last}")
    f_exact = hydrostatic(H) * 1.0  # floor pressure of the exact Tait column times the width
    fy = read_csv(f"{out}/corrected/forces.csv", lists=True)["floor_fy"][-1]
    crit("floor force", abs(-fy / f_exact - 1) < 0.02,
         f"{-fy:.1f} N downwards against p_hydro(H) x width = {f_exact:.1f} N "
         f"({100 * (-fy / f_exact - 1):+.2f} %, within 2 %)")
    ts, eta = surface(f"{out}/corrected")
    dev = max(abs(e - H) for e in eta)
    crit("surface", dev <= 0.5 * DR,
         f"corrected: max |eta - H| = {dev:.4f} m = {dev / DR:.2f} dr (<= 0.5 dr)")
    tu, etau = surface(f"{out}/uncorrected")
    tl, etal = surface(f"{out}/linear")
    t_cmp = tu[-1]
    eta_c = [e for t, e in zip(ts, eta) if t <= t_cmp + 1e-9][-1]
    rise = etau[-1] - H
    crit("uncorrected rises", rise > 0.1 * DR and etau[-1] > eta_c + 0.1 * DR,
         f"uncorrected: eta - H = {rise:+.4f} m = {rise / DR:+.2f} dr at t = {t_cmp:.2f} s "
         f"(corrected {(eta_c - H) / DR:+.2f} dr)")
    print(f"     linear M(81): max |eta - H| = {max(abs(e - H) for e in etal) / DR:.2f} dr")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no figure")
        if check and not ok:
            sys.exit(1)
        return
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for key, (t, e) in {"corrected": (ts, eta), "linear": (tl, etal),
                        "uncorrected": (tu, etau)}.items():
        ax1.plot([ti * C0 / H for ti in t], [ei / H for ei in e], label=runs[key])
    ax1.axhspan(1 - 0.5 * DR, 1 + 0.5 * DR, color="0.9", label="H ± Δr/2")
    ax1.set_xlabel("t c0 / H")
    ax1.set_ylabel("free surface / H (mean of 5 gauges)")
    ax1.legend(fontsize=8)
    ax2.plot([p / (RHO0 * G * H) for p in ps], ys, ".", ms=3, label="SPH, t = %.2f s" % t_end)
    yy = [i / 100 for i in range(101)]
    ax2.plot([hydrostatic(H - y) / (RHO0 * G * H) for y in yy], yy, "k--", lw=1,
             label="hydrostatic (Tait)")
    ax2.set_xlabel("p / (ρ0 g H)")
    ax2.set_ylabel("y [m]")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/still_water_2d.png", dpi=120)
    print(f"figure: {out}/still_water_2d.png")
    if check and not ok:
        sys.exit(1)


main()
