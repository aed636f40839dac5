#!/usr/bin/python3
"""SPH against fv1d on the same pipe problem: the design's own cross-check.

One problem file (problem.yaml in each directory next to this script) gives the fluid, the pipe,
the initial state, the two ends and the times to compare. This script writes from it a case file
for each program (sph/ at every resolution of `sph.dr`, fv1d/ on a fine grid), runs `sabre-sph`
first, then `sabre-fv1d` with its profiles at the times SPH wrote (so that both are compared at
the same instants), and prints, for each compare time and SPH resolution, the L1 differences of
p and u along the pipe,

    L1(f) = (1/L) Σ_a |f_a − f_fv1d(x_a)| Δx_a       (Δx_a: the particle's share of the pipe)

(in a 2D channel, `sph.width`, Δx_a = L V_a / Σ_b V_b with V = m/ρ: the L1 difference over the
whole channel, across its width as well as along it)

as fractions of the problem's jump (`jump.p`, `jump.u`), and their order between consecutive
resolutions, log2(L1(Δr) / L1(Δr/2)). With `reflection` in the problem it also prints the largest
difference of the left-running part p_L = (p − ρ0 c0 u)/2 between SPH and fv1d over
reflection.x_min ≤ x ≤ L − 2h at the given times, as a fraction of reflection.amplitude: what an
outlet on the right sends back into the pipe. A figure `<name>.png` shows p and u along the pipe
(fv1d line, SPH points at the finest resolution) and the L1 histories.

usage: compare.py PROBLEM.yaml [--build DIR] [--output DIR] [--check]
  --build   the build directory holding sph/sabre-sph and fv1d/sabre-fv1d (default: ../../build
            from this script, or $SABRE_BUILD)
  --output  where the runs and the figure go (default: <build>/cases/compare/<name>)
  --check   exit 1 unless the problem's `criteria` hold (printed ok/FAIL per criterion)

Problem keys (all required unless a default is given):
  name                      output name
  fluid: rho0, c0, xi       as both programs' `fluid` sections
  pipe: length              [m], the pipe is [0, length]
  initial: p, u             numbers or expressions of x (Pa, m/s); u along +x
  left, right               each {type: open, impose: pressure|velocity, signal: constant|ramp|table,
                            value, start (0), t_start (0), duration, table} or {type: wall};
                            velocities along +x (fv1d's convention); table: a CSV file `t,value`
                            next to the problem file
  time: end, interval       [s]; SPH writes its particles every `interval`
  compare: [t...]           compare times, each a multiple of time.interval
  jump: p, u                the scales of the L1 differences [Pa, m/s]
  sph: dr [list], h_over_dr (2), diffusion (ferrari), and sabre-sph's numerics.open_gradient,
                            numerics.diffusion_speed, numerics.eta, numerics.no_pull and
                            numerics.wall_vertex_mass (their defaults when
                            absent; a value not among sabre-sph's choices is an
                            error naming this key); width [m] (absent: SPH in 1D): SPH in a 2D channel of that
                            width between free-slip walls at y = 0 and y = width, its x faces
                            open; repack (0): sabre-sph's repack.steps
  fv1d: cells, flux (godunov), reconstruction (mc)
  reflection (optional): x_min, times, amplitude
  criteria: l1 (fraction of the jump at the finest Δr, every compare time), falling (true: the
            mean of L1(p) + L1(u) over the compare times falls as Δr halves), reflection (fraction)
"""
import math
import os
import shutil
import subprocess
import sys

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "sph"))
import sabre_output  # noqa: E402


def fail(msg):
    sys.exit(f"compare.py: {msg}")


def need(d, key, where):
    if not isinstance(d, dict) or key not in d:
        fail(f"{where}: missing key '{key}'")
    return d[key]


def num(x):
    return repr(float(x))


def sph_signal(end, sign, problem_dir, run_dir, side):
    """The SPH value of one open end: (key, value) for sph's open_boundaries entry. sign = +1 on
    the left (normal +x), -1 on the right, for velocities (SPH imposes u·n into the fluid)."""
    imp = end["impose"]
    sig = end.get("signal", "constant")
    s = sign if imp == "velocity" else 1.0
    if sig == "constant":
        val = float(need(end, "value", side)) * s
        return ("pressure" if imp == "pressure" else "normal_velocity"), val
    if sig == "ramp":
        v1 = float(need(end, "value", side))
        v0 = float(end.get("start", 0.0))
        t0 = float(end.get("t_start", 0.0))
        dur = float(need(end, "duration", side))
        if dur <= 0.0:
            fail(f"{side}.duration: expected > 0 for a ramp in SPH")
        # clamp((t - t0)/dur, 0, 1) = (|q| - |q - 1| + 1)/2
        q = f"((t - {num(t0)})/{num(dur)})"
        expr = f"{num(s)}*({num(v0)} + ({num(v1 - v0)})*(abs({q}) - abs({q} - 1) + 1)/2)"
        return ("pressure" if imp == "pressure" else "normal_velocity"), expr
    if sig == "table":
        src = os.path.join(problem_dir, need(end, "table", side))
        col = "p" if imp == "pressure" else "un"
        dst = os.path.join(run_dir, f"{side}_table.csv")
        with open(src) as fi, open(dst, "w") as fo:
            header = fi.readline().strip()
            if header != "t,value":
                fail(f"{src}: expected the header 't,value'")
            fo.write(f"t,{col}\n")
            for line in fi:
                t, v = line.strip().split(",")
                fo.write(f"{t},{float(v) * s!r}\n")
        return "table", os.path.basename(dst)
    fail(f"{side}.signal: expected constant, ramp or table for SPH, not '{sig}'")


def write_sph(prob, problem_dir, run_dir, dr):
    L = float(prob["pipe"]["length"])
    fl = prob["fluid"]
    sph = prob.get("sph", {})
    opens = [n for n, side in (("x-", "left"), ("x+", "right"))
             if prob[side]["type"] == "open"]
    width = channel_width(prob)
    if width is None:  # a 1D pipe
        lo, hi, walls = [0.0], [L], {"type": "interval", "lo": [0.0], "hi": [L], "open": opens}
    else:  # a 2D channel between free-slip walls at y = 0 and y = width
        lo, hi = [0.0, 0.0], [L, width]
        walls = {"type": "box", "lo": list(lo), "hi": list(hi), "open": opens}
    case = {
        "geometry": {
            "dimension": len(lo), "dr": dr, "h_over_dr": float(sph.get("h_over_dr", 2)),
            "first_row": 1,
            "walls": [walls],
            "fluid": [{"type": "box", "lo": lo, "hi": hi}],
        },
        "fluid": {"rho0": float(fl["rho0"]), "c0": float(fl["c0"]), "xi": float(fl["xi"]),
                  "nu": 0.0},
        "initial": {"pressure": str(prob["initial"]["p"]),
                    "velocity": [str(prob["initial"]["u"])] + ["0"] * (len(lo) - 1)},
        "numerics": {"diffusion": sph.get("diffusion", "ferrari")},
        "time": {"end": float(prob["time"]["end"]),
                 "output_interval": float(prob["time"]["interval"])},
    }
    for key in ("open_gradient", "diffusion_speed", "no_pull", "wall_vertex_mass"):
        if key in sph:
            case["numerics"][key] = str(sph[key])
    if "eta" in sph:
        case["numerics"]["eta"] = float(sph["eta"])
    steps = repack_steps(prob)
    if steps > 0:
        case["repack"] = {"steps": steps}
    groups = []
    for edge, face, side, sign in ((1, "x-", "left", 1.0), (2, "x+", "right", -1.0)):
        end = prob[side]
        if end["type"] != "open":
            continue
        key, val = sph_signal(end, sign, problem_dir, run_dir, side)
        where = {"edges": [edge]} if width is None else {"faces": [face]}
        groups.append({"name": side, "wall": 0, **where, "impose": end["impose"], key: val})
    if groups:
        case["open_boundaries"] = groups
    path = os.path.join(run_dir, "sph.yaml")
    with open(path, "w") as f:
        f.write(f"# written by cases/compare/compare.py from {prob['name']}'s problem.yaml\n")
        yaml.safe_dump(case, f, sort_keys=False)
    return path


def write_fv1d(prob, problem_dir, run_dir, times):
    L = float(prob["pipe"]["length"])
    fv = prob.get("fv1d", {})
    bnd = {}
    for side in ("left", "right"):
        end = dict(prob[side])
        if end.get("signal") == "table":
            shutil.copy(os.path.join(problem_dir, end["table"]),
                        os.path.join(run_dir, f"{side}_fv1d_table.csv"))
            end["table"] = f"{side}_fv1d_table.csv"
        bnd[side] = end
    case = {
        "domain": {"x_min": 0.0, "x_max": L, "cells": int(need(fv, "cells", "fv1d"))},
        "fluid": {k: float(prob["fluid"][k]) for k in ("rho0", "c0", "xi")},
        "initial": {"p": prob["initial"]["p"], "u": prob["initial"]["u"]},
        "boundaries": bnd,
        "numerics": {"flux": fv.get("flux", "godunov"),
                     "reconstruction": fv.get("reconstruction", "mc")},
        "time": {"end": max(times)},
        "output": {"times": sorted(times)},
    }
    path = os.path.join(run_dir, "fv1d.yaml")
    with open(path, "w") as f:
        f.write(f"# written by cases/compare/compare.py from {prob['name']}'s problem.yaml\n")
        yaml.safe_dump(case, f, sort_keys=False)
    return path


def run(cmd, log):
    with open(log, "w") as f:
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        with open(log) as f:
            tail = f.read()[-2000:]
        fail(f"{' '.join(cmd)} failed (exit {r.returncode}); end of {log}:\n{tail}")


def channel_width(prob, where="problem"):
    """The width of the 2D channel of `sph.width` [m], or None for a 1D pipe (where: the problem
    file, for the error)."""
    w = (prob.get("sph") or {}).get("width")
    if w is None:
        return None
    if not isinstance(w, (int, float)) or isinstance(w, bool) or not w > 0.0:
        fail(f"{where}: sph.width: expected a width > 0 (m), got {w!r}")
    return float(w)


def repack_steps(prob, where="problem"):
    """sabre-sph's repack.steps from `sph.repack` (0 when absent; where: the problem file, for the
    error)."""
    n = (prob.get("sph") or {}).get("repack", 0)
    if not isinstance(n, int) or isinstance(n, bool) or n < 0:
        fail(f"{where}: sph.repack: expected a number of steps >= 0, got {n!r}")
    return n


def sph_profiles(run_dir, L, width):
    """{time: (x, p, u, s)} of the fluid particles, sorted by x; s is each particle's share of the
    length L: in 1D half the gaps to its neighbours (the ends to the walls), in 2D L times its
    volume m/rho over the fluid's, so that (1/L) sum s |f - f_ref(x)| is the L1 difference over
    the channel's cross-section as well as along it."""
    import numpy as np
    out = {}
    for t, path in sabre_output.read_pvd(os.path.join(run_dir, "particles.pvd"), 0):
        d = sabre_output.read_vtu(path)
        x = np.asarray(d["points"]).reshape(-1, 3)[:, 0]
        p = np.asarray(d["pressure"])
        u = np.asarray(d["velocity"]).reshape(-1, 3)[:, 0]
        o = np.argsort(x)
        x, p, u = x[o], p[o], u[o]
        if width is None:
            s = shares(x, L)
        else:
            vol = (np.asarray(d["mass"]) / np.asarray(d["density"]))[o]
            s = L * vol / np.sum(vol)
        out[t] = (x, p, u, s)
    return out


def fv1d_profiles(run_dir):
    """[(time, x, p, u)] of the profiles after the initial one (profiles.csv lists their times)."""
    idx = sabre_output.read_csv(os.path.join(run_dir, "profiles.csv"))
    res = []
    for k, t in zip(idx["index"], idx["t"]):
        if int(k) == 0:
            continue
        d = sabre_output.read_csv(os.path.join(run_dir, f"profile_{int(k):04d}.csv"))
        res.append((float(t), d["x"], d["p"], d["u"]))
    return res


def shares(x, L):
    """The particle's share of [0, L]: half the gaps to its neighbours (the ends to the walls)."""
    import numpy as np
    edges = np.concatenate(([0.0], 0.5 * (x[1:] + x[:-1]), [L]))
    return np.diff(edges)


def main(argv):
    import numpy as np
    args = argv[1:]
    if not args or args[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if args else 2
    problem = os.path.abspath(args[0])
    opts = {"--build": None, "--output": None}
    check = False
    i = 1
    while i < len(args):
        if args[i] == "--check":
            check = True
        elif args[i] in opts and i + 1 < len(args):
            opts[args[i]] = args[i + 1]
            i += 1
        else:
            fail(f"unexpected argument '{args[i]}' (see --help)")
        i += 1
    with open(problem) as f:
        prob = yaml.safe_load(f)
    for key in ("name", "fluid", "pipe", "initial", "left", "right", "time", "compare", "jump",
                "sph", "fv1d"):
        need(prob, key, problem)
    known = {"name", "fluid", "pipe", "initial", "left", "right", "time", "compare", "jump", "sph",
             "fv1d", "reflection", "criteria"}
    unknown = sorted(set(prob) - known)
    if unknown:
        fail(f"{problem}: unknown key(s) {', '.join(unknown)} (expected: {', '.join(sorted(known))})")
    for key, allowed in (("criteria", {"l1", "falling", "reflection"}),
                         ("sph", {"dr", "h_over_dr", "diffusion", "open_gradient", "diffusion_speed",
                                  "eta", "width", "repack", "no_pull", "wall_vertex_mass"}),
                         ("fv1d", {"cells", "flux", "reconstruction"}),
                         ("reflection", {"x_min", "times", "amplitude"})):
        extra = sorted(set(prob.get(key) or {}) - allowed)
        if extra:
            fail(f"{problem}: {key}: unknown key(s) {', '.join(extra)} "
                 f"(expected: {', '.join(sorted(allowed))})")
    # sabre-sph's choices, checked here so that a bad value names the problem file's key
    for key, choices in (("diffusion", ("none", "ferrari", "brezzi")),
                         ("open_gradient", ("symmetric", "difference")),
                         ("diffusion_speed", ("max", "eta")),
                         ("no_pull", ("radial", "normal")),
                         ("wall_vertex_mass", ("constant", "density"))):
        value = (prob.get("sph") or {}).get(key)
        if value is not None and value not in choices:
            fail(f"{problem}: sph.{key}: expected one of {', '.join(choices)}, not {value!r}")
    width = channel_width(prob, problem)
    repack_steps(prob, problem)  # checked before anything is written
    name = prob["name"]
    build = opts["--build"] or os.environ.get("SABRE_BUILD") or \
        os.path.join(os.path.dirname(os.path.dirname(HERE)), "build")
    sph_exe = os.path.join(build, "sph", "sabre-sph")
    fv_exe = os.path.join(build, "fv1d", "sabre-fv1d")
    for exe in (sph_exe, fv_exe):
        if not os.access(exe, os.X_OK):
            fail(f"{exe}: not found (build first, or give --build DIR)")
    out = os.path.abspath(opts["--output"] or os.path.join(build, "cases", "compare", name))
    os.makedirs(out, exist_ok=True)
    problem_dir = os.path.dirname(problem)
    L = float(prob["pipe"]["length"])
    interval = float(prob["time"]["interval"])
    compare = [float(t) for t in prob["compare"]]
    for t in compare:
        k = round(t / interval)
        if k < 1 or abs(k * interval - t) > 1e-9 * max(1.0, t):
            fail(f"compare: {t} is not a positive multiple of time.interval = {interval}")
    drs = sorted((float(d) for d in prob["sph"]["dr"]), reverse=True)
    jp, ju = float(prob["jump"]["p"]), float(prob["jump"]["u"])

    # SPH at each resolution, then fv1d at the times SPH wrote (the first output at or after each
    # compare time: SPH does not shorten a step to land on an output time).
    sph = {}
    want = set()
    for dr in drs:
        rd = os.path.join(out, f"sph_dr{dr:g}")
        os.makedirs(rd, exist_ok=True)
        case = write_sph(prob, problem_dir, rd, dr)
        shutil.rmtree(os.path.join(rd, "run"), ignore_errors=True)
        run([sph_exe, "run", case, "--output", os.path.join(rd, "run"), "--threads", "1"],
            os.path.join(rd, "sph.log"))
        prof = sph_profiles(os.path.join(rd, "run"), L, width)
        picked = {}
        for t in compare:
            ts = min((s for s in prof if s >= t - 1e-12), default=None)
            if ts is None:
                fail(f"SPH Δr = {dr:g}: no output at or after t = {t}")
            picked[t] = ts
            want.add(ts)
        sph[dr] = (prof, picked)
    fd = os.path.join(out, "fv1d")
    os.makedirs(fd, exist_ok=True)
    case = write_fv1d(prob, problem_dir, fd, sorted(want))
    shutil.rmtree(os.path.join(fd, "run"), ignore_errors=True)
    run([fv_exe, case, "--quiet", "--output", os.path.join(fd, "run")], os.path.join(fd, "fv1d.log"))
    ref = {}
    for t, x, p, u in fv1d_profiles(os.path.join(fd, "run")):
        ref[min(want, key=lambda s: abs(s - t))] = (x, p, u)

    # L1 differences
    rows = []
    geom = "1D" if width is None else f"2D channel {width:g} m wide, free-slip walls"
    print(f"{name}: SPH ({geom}, h = {float(prob['sph'].get('h_over_dr', 2)):g} dr) against fv1d "
          f"({int(prob['fv1d']['cells'])} cells); L1 of p and u as fractions of the jump "
          f"(p {jp:g} Pa, u {ju:g} m/s)")
    print(f"{'t [s]':>8} {'dr [m]':>9} {'t_SPH [s]':>10} {'L1(p)':>9} {'L1(u)':>9} "
          f"{'order p':>8} {'order u':>8}")
    l1 = {}
    for t in compare:
        prev = None
        for dr in drs:
            prof, picked = sph[dr]
            ts = picked[t]
            x, p, u, w = prof[ts]
            rx, rp, ru = ref[ts]
            ep = float(np.sum(w * np.abs(p - np.interp(x, rx, rp))) / L / jp)
            eu = float(np.sum(w * np.abs(u - np.interp(x, rx, ru))) / L / ju)
            l1[(t, dr)] = (ep, eu)
            op = ou = float("nan")
            if prev is not None:
                op = math.log2(prev[0] / ep) if ep > 0 else float("inf")
                ou = math.log2(prev[1] / eu) if eu > 0 else float("inf")
            print(f"{t:8.4g} {dr:9.4g} {ts:10.5g} {ep:9.4f} {eu:9.4f} {op:8.2f} {ou:8.2f}")
            rows.append((t, dr, ts, ep, eu))
            prev = (ep, eu)
    with open(os.path.join(out, "l1.csv"), "w") as f:
        f.write("t,dr,t_sph,l1_p,l1_u\n")
        for r in rows:
            f.write(",".join(repr(v) for v in r) + "\n")
    mean = {dr: float(np.mean([sum(l1[(t, dr)]) / 2 for t in compare])) for dr in drs}
    print("mean of (L1(p) + L1(u))/2 over the compare times: " +
          ", ".join(f"{mean[dr]:.4f} at dr = {dr:g}" for dr in drs) +
          ("" if len(drs) < 2 else
           f"; order {math.log2(mean[drs[-2]] / mean[drs[-1]]):.2f}"))

    refl = None
    if "reflection" in prob:
        # What the outlet sends back travels left: the left-running part of the acoustic field,
        # p_L = (p − ρ0 c0 u)/2, against fv1d's, over x_min ≤ x ≤ L − 2h (the particles within 2h of
        # the outlet, where they are created and deleted, are left out: what matters is what
        # propagates back into the pipe).
        rf = prob["reflection"]
        xm, amp = float(rf["x_min"]), float(rf["amplitude"])
        z = float(prob["fluid"]["rho0"]) * float(prob["fluid"]["c0"])
        for dr in drs:
            h = float(prob["sph"].get("h_over_dr", 2)) * dr
            prof, picked = sph[dr]
            worst = 0.0
            for t in rf["times"]:
                t = float(t)
                if t not in picked:
                    fail(f"reflection.times: {t} must be among the compare times")
                ts = picked[t]
                x, p, u, _ = prof[ts]
                rx, rp, ru = ref[ts]
                k = (x >= xm) & (x <= L - 2.0 * h)
                pl = 0.5 * (p[k] - z * u[k])
                rl = 0.5 * (np.interp(x[k], rx, rp) - z * np.interp(x[k], rx, ru))
                worst = max(worst, float(np.max(np.abs(pl - rl))))
            refl = worst / amp
            print(f"reflection at the outlet, dr = {dr:g}: largest |p_L,SPH - p_L,fv1d| "
                  f"(p_L = (p - rho0 c0 u)/2, the left-running part) for {xm:g} m <= x <= L - 2h "
                  f"at t = {', '.join(str(t) for t in rf['times'])} s: {worst:.4g} Pa = "
                  f"{refl:.4f} of {amp:g} Pa")

    plot(prob, out, sph, ref, compare, drs, l1)

    if not check:
        return 0
    crit = prob.get("criteria", {})
    ok = True

    def require(cond, what):
        nonlocal ok
        print(("ok   " if cond else "FAIL ") + what)
        ok = ok and cond

    fine = drs[-1]
    if "l1" in crit:
        lim = float(crit["l1"])
        worst = max(max(l1[(t, fine)]) for t in compare)
        require(worst <= lim, f"L1 of p and u at dr = {fine:g}: largest {worst:.4f} <= {lim:g} "
                f"of the jump at every compare time")
    if crit.get("falling", False) and len(drs) >= 2:
        require(all(mean[drs[i + 1]] < mean[drs[i]] for i in range(len(drs) - 1)),
                "mean L1 falls as dr halves: " +
                " > ".join(f"{mean[dr]:.4f}" for dr in drs))
    if "reflection" in crit:
        lim = float(crit["reflection"])
        require(refl is not None and refl <= lim,
                f"outlet reflection {refl if refl is not None else float('nan'):.4f} <= {lim:g} "
                f"of the amplitude")
    return 0 if ok else 1


def plot(prob, out, sph, ref, compare, drs, l1):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
    fine = drs[-1]
    prof, picked = sph[fine]
    colours = plt.cm.viridis([i / max(1, len(compare) - 1) for i in range(len(compare))])
    for t, c in zip(compare, colours):
        ts = picked[t]
        x, p, u, _ = prof[ts]
        rx, rp, ru = ref[ts]
        ax[0].plot(rx, rp, color=c, lw=1.2, label=f"t = {t:g} s")
        ax[0].plot(x, p, ".", color=c, ms=2.5)
        ax[1].plot(rx, ru, color=c, lw=1.2)
        ax[1].plot(x, u, ".", color=c, ms=2.5)
    ax[0].set_xlabel("x [m]")
    ax[0].set_ylabel("p [Pa]")
    ax[0].legend(fontsize=7)
    ax[1].set_xlabel("x [m]")
    ax[1].set_ylabel("u [m/s]")
    ax[0].set_title(f"lines: fv1d; points: SPH, dr = {fine:g} m", fontsize=9)
    for dr, ls in zip(drs, ("-", "--", ":", "-.")):
        ax[2].plot(compare, [l1[(t, dr)][0] for t in compare], "o" + ls, label=f"p, dr = {dr:g}")
        ax[2].plot(compare, [l1[(t, dr)][1] for t in compare], "s" + ls, label=f"u, dr = {dr:g}")
    crit = prob.get("criteria", {})
    if "l1" in crit:
        ax[2].axhline(float(crit["l1"]), color="k", lw=0.8)
    ax[2].set_xlabel("t [s]")
    ax[2].set_ylabel("L1 difference / jump")
    ax[2].set_yscale("log")
    ax[2].legend(fontsize=7)
    fig.suptitle(f"{prob['name']}: SPH against fv1d", fontsize=10)
    fig.tight_layout()
    path = os.path.join(out, f"{prob['name']}.png")
    fig.savefig(path, dpi=120)
    print(f"figure: {path}")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
