"""Linear-acoustics solution of the acoustic-pulse case, shared by make_table.py and plot.py.
Initial pressure P(x) = A exp(-((x - x0)/sigma)^2), u = 0, on [0, L]; the left end (imposed p = 0)
reflects pressure with coefficient -1; the right end imposes the exact pressure, so nothing
reflects there:
    p(x, t) = P(x - ct)/2 + P(x + ct)/2 - P(ct - x)/2
    u(x, t) = (P(x - ct)/2 - P(x + ct)/2 - P(ct - x)/2) / (rho0 c0)"""
import math

RHO0, C0, A, X0, SIGMA, L = 1000.0, 20.0, 400.0, 0.5, 0.05, 1.0


def P(x):
    return A * math.exp(-(((x - X0) / SIGMA) ** 2))


def pressure(x, t):
    return 0.5 * P(x - C0 * t) + 0.5 * P(x + C0 * t) - 0.5 * P(C0 * t - x)


def velocity(x, t):
    return (0.5 * P(x - C0 * t) - 0.5 * P(x + C0 * t) - 0.5 * P(C0 * t - x)) / (RHO0 * C0)
