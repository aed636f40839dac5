#!/usr/bin/python3
"""cases/compare/compare.py on bad problem files: each must exit non-zero with a message naming
the key and what was expected, before anything is written (no output directory).

usage: compare_input.py SOURCE_DIR WORK_DIR"""
import os
import shutil
import subprocess
import sys

import yaml

BAD = [  # (sph key, bad value, part of the message)
    ("no_pull", "sideways", "sph.no_pull: expected one of radial, normal, not 'sideways'"),
    ("wall_vertex_mass", "heavy",
     "sph.wall_vertex_mass: expected one of constant, density, not 'heavy'"),
    ("open_gradient", "upwind",
     "sph.open_gradient: expected one of symmetric, difference, not 'upwind'"),
    ("diffusion", "magic", "sph.diffusion: expected one of none, ferrari, brezzi, not 'magic'"),
    ("diffusion_speed", "fast", "sph.diffusion_speed: expected one of max, eta, not 'fast'"),
    ("width", -1, "sph.width: expected a width > 0 (m), got -1"),
    ("repack", -3, "sph.repack: expected a number of steps >= 0, got -3"),
    ("colour", "blue", "sph: unknown key(s) colour"),
]


def main(src, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(os.path.join(src, "cases", "compare", "water_hammer_2d", "problem.yaml")) as f:
        base = yaml.safe_load(f)
    fails = 0
    for key, value, want in BAD:
        prob = dict(base, sph=dict(base["sph"], **{key: value}))
        path = os.path.join(work, f"{key}.yaml")
        with open(path, "w") as f:
            yaml.safe_dump(prob, f)
        out = os.path.join(work, f"out_{key}")
        r = subprocess.run([sys.executable, os.path.join(src, "cases", "compare", "compare.py"),
                            path, "--build", os.path.join(work, "nobuild"), "--output", out],
                           capture_output=True, text=True)
        msg = (r.stdout + r.stderr).strip()
        if r.returncode == 0:
            print(f"FAIL sph.{key} = {value!r}: exit status 0")
        elif want not in msg:
            print(f"FAIL sph.{key} = {value!r}: message {msg!r} lacks {want!r}")
        elif os.path.exists(out):
            print(f"FAIL sph.{key} = {value!r}: {out} was written")
        else:
            print(f"ok   sph.{key} = {value!r}: {msg}")
            continue
        fails += 1
    return 1 if fails else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
