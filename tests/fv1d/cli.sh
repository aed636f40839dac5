#!/usr/bin/env bash
# The sabre-fv1d command line: --help/--version, strict options (each once, xi in [1, 100]), the
# fixed-step CFL warning, time.max_steps (exit 3, outputs complete), error messages that say why
# and never name the machine's source paths, and `cmake --install` installing the program.
# Usage: cli.sh PATH/TO/sabre-fv1d BUILD_DIR SOURCE_DIR
set -u
tool=$1 build=$2 src=$3
. "$(dirname "$0")/../checklib.sh"
cat >"$tmp/case.yaml" <<'YAML'
domain: {x_min: -1.0, x_max: 1.0, cells: 40}
fluid: {rho0: 1.0, c0: 3.13, xi: 2}
initial:
  rho: 0.35
  u: 0
  regions: [{from: -1.0, to: 0.0, rho: 1.0, u: 0}]
boundaries: {left: {type: transmissive}, right: {type: transmissive}}
time: {end: 0.05}
output: {times: [0.05]}
YAML
R=(riemann --xi 7 --rho0 1000 --c0 20 --left 1010,0 --right 1000,0 --cells 50 --time 0.005)

# expect STATUS CMD...: exit status, stderr kept in $tmp/err
expect() {
  local want=$1; shift
  "$@" >"$tmp/out" 2>"$tmp/err"; local rc=$?
  if [ $rc -eq "$want" ]; then ok; else bad "exit $rc (want $want) for: $* :: $(cat "$tmp/err")"; fi
}
has() { if grep -q -- "$1" "$tmp/$2"; then ok; else bad "'$1' not in $2: $(cat "$tmp/$2")"; fi; }
hasnt() { if grep -q -- "$1" "$tmp/$2"; then bad "'$1' in $2: $(cat "$tmp/$2")"; else ok; fi; }

expect 0 "$tool" --version; has '^sabre-fv1d [0-9]*\.[0-9]*\.[0-9]*$' out
expect 0 "$tool" --help; has '^usage:' out
expect 0 "$tool" riemann --help; has '^usage:' out
# each option once
expect 2 "$tool" "$tmp/case.yaml" --output "$tmp/a" --output "$tmp/b"; has 'given twice' err
expect 2 "$tool" "$tmp/case.yaml" --quiet --quiet --output "$tmp/a"; has 'given twice' err
expect 2 "$tool" "${R[@]}" --cells 60 --output "$tmp/r.csv"; has 'given twice' err
# xi in [1, 100] as in case files
expect 2 "$tool" riemann --xi 1e6 --rho0 1000 --c0 20 --left 1010,0 --right 1000,0 --cells 50 \
  --time 0.005 --output "$tmp/r.csv"; has 'xi <= 100' err
# the fixed step beyond CFL 1 warns (case file and riemann mode)
expect 0 "$tool" "$tmp/case.yaml" --quiet --output "$tmp/cfl" --set time.cfl=2 --set time.end=0.001 \
  --set output.times=[0.001]
has 'warning: .*case.yaml:.*time.cfl = 2' err
expect 0 "$tool" "${R[@]}" --cfl 1.5 --output "$tmp/r.csv"; has 'warning: --cfl 1.5' err
expect 0 "$tool" "$tmp/case.yaml" --quiet --output "$tmp/cfl1" --set time.cfl=0.9
hasnt 'warning' err
# time.max_steps: the run stops with exit 3 and complete outputs (same meaning as sabre-sph)
expect 3 "$tool" "$tmp/case.yaml" --quiet --output "$tmp/steps" --set time.max_steps=5
has 'time.max_steps = 5 reached' err
if grep -q '^status: stopped at time.max_steps' "$tmp/steps/summary.yaml" &&
   grep -q '^steps: 5$' "$tmp/steps/summary.yaml"; then ok; else bad "summary.yaml after max_steps"; fi
# errors say why, and never print the absolute path of a source file
expect 2 "$tool" "$tmp/case.yaml" --output /dev/null/out; has 'Not a directory' err
expect 1 "$tool" "${R[@]}" --output "$tmp/missing/r.csv"; has 'No such file' err
hasnt "$src" err
hasnt 'error: /' err
# cmake --install installs sabre-fv1d next to sabre-riemann
if cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log" 2>&1 &&
   [ -x "$tmp/prefix/bin/sabre-fv1d" ] && "$tmp/prefix/bin/sabre-fv1d" --version >/dev/null; then ok
else bad "cmake --install does not install a working bin/sabre-fv1d"; fi
finish
