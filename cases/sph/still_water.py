"""Analysis shared by the still-water plot scripts (cases/sph/still_water_2d, still_water_3d,
still_water_tank_3d): a tank of depth H at rest under gravity, run as committed (corrected/) and
without the gravity correction of the volume diffusion (uncorrected/, a shorter run). Imported
like sabre_output.py (the scripts add cases/sph to sys.path). Only the standard library is
needed; matplotlib for the figures.

    Tank(rho0, c0, xi, g, H, dr)       the case's constants; tank.hydrostatic(depth) [Pa]
    surface(run, prefix)               free surface from the level* (or eta*) gauges of probes.csv
    Criteria(check)                    prints one 'ok  '/'FAIL' line per criterion; done() exits
    check_rest(tank, run, axis, crit)  criteria mass, particles, rest, hydrostatic
    tail_max_speed(d), rms_speed(run, d)  largest max|u| of the last 10 %; mean fluid speed
    check_floor_force(tank, run, ...)  criterion floor force (force group `floor`)
    check_surface(tank, out, crit)     criteria surface and uncorrected detaches
    pyplot()                           matplotlib.pyplot on the Agg backend, or None
    plot_profile(ax, tank, ...)        the final pressure against the Tait column
    figure_rest(tank, ...)             the three panels (surface, max|u|, final pressure profile)
    figure_3d(tank, out, ...)          figure_rest for the 3D cases
"""
import glob
import math
import sys

from sabre_output import read_csv, read_vtu


class Tank:
    """Constants of a still-water case: rho0 [kg/m³], c0 [m/s], the Tait exponent xi, g [m/s²],
    the depth H [m] and the particle spacing dr [m]."""

    def __init__(self, rho0, c0, xi, g, H, dr):
        self.rho0, self.c0, self.xi, self.g, self.H, self.dr = rho0, c0, xi, g, H, dr
        self.B = rho0 * c0 * c0 / xi

    def hydrostatic(self, depth):
        """Exact hydrostatic pressure of the Tait EOS at a depth (as the initial state)."""
        if depth <= 0:
            return 0.0
        xi = self.xi
        return self.B * ((1 + (xi - 1) * self.g * depth / self.c0**2) ** (xi / (xi - 1)) - 1)


def surface(run, prefix="level"):
    """(times, mean elevation of the gauges) of the run directory `run`, from probes.csv: the
    kernel-sum levels (level*, where the particles' volume ends) or, with prefix "eta", the
    highest particle + dr/2 (eta*, the top row's height; docs/sph-solver.md §6)."""
    p = read_csv(f"{run}/probes.csv", lists=True)
    cols = [k for k in p if k.startswith(prefix)]
    return p["time"], [sum(p[k][i] for k in cols) / len(cols) for i in range(len(p["time"]))]


class Criteria:
    """The criteria of a check: crit(name, good, text) prints 'ok  ' or 'FAIL' with the name and
    the measured figures; done() exits with status 1 under --check (check=True) unless all held."""

    def __init__(self, check):
        self.check = check
        self.ok = True

    def __call__(self, name, good, text):
        self.ok &= good
        print(f"{'ok  ' if good else 'FAIL'} {name}: {text}")

    def done(self):
        if self.check and not self.ok:
            sys.exit(1)


def tail_max_speed(d):
    """The largest max_speed of diagnostics.csv (as lists, d) over the last 10 % of the run."""
    t_end = d["time"][-1]
    return max(u for t, u in zip(d["time"], d["max_speed"]) if t >= 0.9 * t_end)


def rms_speed(run, d):
    """sqrt(2 <kinetic>/M_fluid) over the second half of the run directory `run` (d: its
    diagnostics.csv as lists): the mean speed of the fluid [m/s]. M_fluid is summed from the
    first fluid VTU (diagnostics.csv's mass includes the vertex particles)."""
    t_end = d["time"][-1]
    ke = [k for t, k in zip(d["time"], d["kinetic"]) if t >= 0.5 * t_end]
    first = sorted(glob.glob(f"{run}/fluid_*.vtu"))[0]
    m_fluid = sum(m for (m,) in read_vtu(first, tuples=True)["mass"])
    return math.sqrt(2 * sum(ke) / len(ke) / m_fluid)


def check_rest(tank, run, axis, crit, rest=0.01, l2_max=0.02):
    """Criteria mass (to 1e-12), particles (constant), rest (max|u| < rest sqrt(gH), 1 % unless
    given, at the end, after at least 20 sqrt(H/g), and on every diagnostics row of the last 10 %
    of the run, so that a passing end value is not a lucky instant of a fluctuating speed) and
    hydrostatic (L2 error of the pressure of the last fluid VTU < l2_max rho0 g H, 2 % unless
    given) of the run directory `run`; `axis` is the vertical coordinate (1: y in 2D, 2: z in 3D).
    Returns diagnostics.csv as lists, the end time, and the heights and pressures of the particles
    of the last VTU."""
    H, G, RHO0 = tank.H, tank.g, tank.rho0
    d = read_csv(f"{run}/diagnostics.csv", lists=True)
    m0 = d["mass"][0]
    dm = max(abs(m / m0 - 1) for m in d["mass"])
    crit("mass", dm <= 1e-12, f"max |M/M0 - 1| = {dm:.2e} (<= 1e-12)")
    crit("particles", min(d["particles"]) == max(d["particles"]) == d["particles"][0],
         f"{int(d['particles'][0])} throughout")
    t_end = d["time"][-1]
    umax, ref = d["max_speed"][-1], rest * math.sqrt(G * H)
    utail = tail_max_speed(d)
    crit("rest", t_end >= 20 * math.sqrt(H / G) - 1e-9 and max(umax, utail) < ref,
         f"max|u| = {umax:.3e} m/s at t = {t_end:.3f} s = {t_end / math.sqrt(H / G):.1f} sqrt(H/g),"
         f" at most {utail:.3e} over the last 10 % of the run"
         f" (< {100 * rest:g}% sqrt(gH) = {ref:.3e})")
    last = sorted(glob.glob(f"{run}/fluid_*.vtu"))[-1]
    v = read_vtu(last, tuples=True)
    err2, n = 0.0, 0
    hs, ps = [], []
    for x, (p,) in zip(v["points"], v["pressure"]):
        err2 += (p - tank.hydrostatic(H - x[axis])) ** 2
        n += 1
        hs.append(x[axis]), ps.append(p)
    l2 = math.sqrt(err2 / n) / (RHO0 * G * H)
    crit("hydrostatic", l2 < l2_max,
         f"L2(p - p_hydro)/(rho0 g H) = {100 * l2:.2f} % (< {100 * l2_max:g} %) in {last}")
    return d, t_end, hs, ps


def check_floor_force(tank, run, column, area, crit):
    """Criterion floor force: the last row of the force group `floor` (column `column` of
    run/forces.csv, e.g. "floor_fy") pushes downwards within 2 % of the exact Tait column's floor
    pressure times the floor's area [m² in 3D, m in 2D]."""
    f_exact = tank.hydrostatic(tank.H) * area
    f = -read_csv(f"{run}/forces.csv", lists=True)[column][-1]
    crit("floor force", abs(f / f_exact - 1) < 0.02,
         f"{f:.1f} N downwards against p_hydro(H) x area = {f_exact:.1f} N "
         f"({100 * (f / f_exact - 1):+.2f} %, within 2 %)")


def check_surface(tank, out, crit):
    """Criteria surface (the corrected run's kernel-sum level within 0.5 dr of H throughout) and
    uncorrected detaches (M §7.1: without the gravity correction the free surface detaches; over
    out/uncorrected/ the top particles rise away from the fluid's level: eta - level grows by more
    than 0.1 dr, and by 0.1 dr more than in the corrected run over the same time). eta, the top
    row's height, is printed for reference. Returns the two runs' surfaces, (times, level, eta)
    each."""
    H, DR = tank.H, tank.dr
    runs = {}
    for key in ("corrected", "uncorrected"):
        t, level = surface(f"{out}/{key}")
        runs[key] = (t, level, surface(f"{out}/{key}", "eta")[1])
    ts, lev, eta = runs["corrected"]
    dev = max(abs(e - H) for e in lev)
    deta = max(abs(e - H) for e in eta)
    crit("surface", dev <= 0.5 * DR,
         f"corrected: max |level - H| = {dev:.4f} m = {dev / DR:.3f} dr (<= 0.5 dr); "
         f"top particle + dr/2: max |eta - H| = {deta / DR:.2f} dr")
    tu, levu, etau = runs["uncorrected"]
    t_cmp = tu[-1]
    k = [i for i, t in enumerate(ts) if t <= t_cmp + 1e-9][-1]
    grow_u = (etau[-1] - levu[-1]) - (etau[0] - levu[0])
    grow_c = (eta[k] - lev[k]) - (eta[0] - lev[0])
    crit("uncorrected detaches", grow_u > 0.1 * DR and grow_u > grow_c + 0.1 * DR,
         f"eta - level grows by {grow_u / DR:+.3f} dr over the uncorrected run to t = {t_cmp:.2f} s "
         f"({grow_c / DR:+.3f} dr corrected); uncorrected level - H = {(levu[-1] - H) / DR:+.3f} dr, "
         f"eta - H = {(etau[-1] - H) / DR:+.3f} dr")
    return runs["corrected"], runs["uncorrected"]


def pyplot():
    """matplotlib.pyplot with the Agg backend, or None (with a message) without matplotlib."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no figure")
        return None
    return plt


def plot_profile(ax, tank, hs, ps, t_end, grid, label):
    """The pressures ps at heights hs (time t_end) and the Tait column at the heights grid, both
    over rho0 g H; label names the vertical axis."""
    scale = tank.rho0 * tank.g * tank.H
    ax.plot([p / scale for p in ps], hs, ".", ms=3, label="SPH, t = %.2f s" % t_end)
    ax.plot([tank.hydrostatic(tank.H - h) / scale for h in grid], grid, "k--", lw=1,
            label="hydrostatic (Tait)")
    ax.set_xlabel("p / (ρ0 g H)")
    ax.set_ylabel(label)
    ax.legend(fontsize=8)


def surface_panel(ax, surfaces, c0, H, dr):
    """The free surface over t c0/H as in M Fig. 8: surfaces {label: (times, level, eta)}, the
    kernel-sum level solid and the top particle + dr/2 dashed in the same colour."""
    for lab, (t, level, eta) in surfaces.items():
        line, = ax.plot([ti * c0 / H for ti in t], [e / H for e in level], label=lab)
        ax.plot([ti * c0 / H for ti in t], [e / H for e in eta], "--", lw=0.8,
                color=line.get_color())
    ax.axhspan(1 - 0.5 * dr / H, 1 + 0.5 * dr / H, color="0.9", label="H ± Δr/2")
    ax.set_xlabel("t c0 / H")
    ax.set_ylabel("free surface / H (5 gauges: level —, top particle --)")
    ax.legend(fontsize=8)


def figure_rest(tank, surfaces, speeds, hs, ps, t_end, vertical, png):
    """The three-panel figure of the still-water cases, written to png: the free surface over
    t c0/H as in M Fig. 8 (surfaces: {label: (times, level, eta)}, surface_panel), max|u|/sqrt(gH)
    over t/sqrt(H/g) against the 1 % line (speeds: {label: diagnostics.csv as lists}), and the final pressures
    ps at heights hs (time t_end; vertical names that axis) against the Tait column. Returns
    False without matplotlib."""
    plt = pyplot()
    if plt is None:
        return False
    G, C0, H, DR = tank.g, tank.c0, tank.H, tank.dr
    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(15, 4.2))
    surface_panel(ax1, surfaces, C0, H, DR)
    for lab, dd in speeds.items():
        ax2.semilogy([ti / math.sqrt(H / G) for ti in dd["time"]],
                     [max(u, 1e-9) / math.sqrt(G * H) for u in dd["max_speed"]], label=lab)
    ax2.axhline(0.01, color="k", ls="--", lw=1, label="1 %")
    ax2.set_ylim(1e-5, 1)
    ax2.set_xlabel("t / sqrt(H/g)")
    ax2.set_ylabel("max|u| / sqrt(gH)")
    ax2.legend(fontsize=8)
    plot_profile(ax3, tank, hs, ps, t_end, [i * H / 100 for i in range(101)], vertical)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print(f"figure: {png}")
    return True


def figure_3d(tank, out, d, surfaces, zs, ps, t_end, png):
    """figure_rest for the 3D cases: surfaces as check_surface returns them, max|u| of
    out/corrected (d) and out/uncorrected."""
    labels = ("gravity-corrected (local)", "uncorrected M(49)")
    du = read_csv(f"{out}/uncorrected/diagnostics.csv", lists=True)
    return figure_rest(tank, dict(zip(labels, surfaces)), dict(zip(labels, (d, du))), zs, ps,
                       t_end, "z [m]", png)
