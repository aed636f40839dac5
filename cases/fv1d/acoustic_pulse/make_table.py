#!/usr/bin/python3
"""Write outlet_pressure.csv, the exact pressure at the right end x = L for t in [0, 0.08] s every
0.1 ms, imposed there as a time table so that the pulse leaves without reflection."""
import sys

sys.dont_write_bytecode = True
from pulse import L, pressure  # noqa: E402

with open("outlet_pressure.csv", "w") as f:
    f.write("t,value\n")
    for k in range(801):
        t = k * 1e-4
        f.write(f"{t:.6g},{pressure(L, t):.17g}\n")
