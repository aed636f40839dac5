#!/usr/bin/env bash
# The sabre-sph command line as a user meets it: --help/--version, the default thread count and
# wait policy, start-up and closing summaries, bounded inputs that stop at once instead of hanging
# (time.output_interval, dr, huge walls, h_over_dr, self-crossing polygons), time.max_steps (exit
# 3), messages that say why and where, the linear stability analysis (`stability`: summary, modes
# file, refused cases), the wave generators (`wave`: JSON lines, bad options), and stdout write
# errors.
# Usage: cli.sh PATH/TO/sabre-sph SOURCE_DIR
set -u
tool=$1 src=$2
. "$(dirname "$0")/../checklib.sh"
cat >"$tmp/case.yaml" <<'YAML'
geometry:
  dimension: 2
  dr: 0.025
  walls:
    - type: box
      lo: [0, 0]
      hi: [0.5, 0.4]
  fluid:
    - type: box
      lo: [0, 0]
      hi: [0.2, 0.2]
fluid:
  rho0: 1000
  c0: 15
gravity: [0, -9.81]
initial:
  pressure: hydrostatic
time:
  end: 0.01
YAML
# expect STATUS SECONDS CMD...: exit status within a time limit; stdout/stderr in $tmp/out, err
expect() {
  local want=$1 limit=$2; shift 2
  timeout -k 5 "$limit" "$@" >"$tmp/out" 2>"$tmp/err"; local rc=$?
  if [ $rc -eq 124 ] || [ $rc -eq 137 ]; then bad "still running after $limit s: $*"; return; fi
  if [ $rc -eq "$want" ]; then ok; else bad "exit $rc (want $want) for: $* :: $(tail -3 "$tmp/err")"; fi
}
has() { if grep -q -- "$1" "$tmp/$2"; then ok; else bad "'$1' not in $2: $(tail -3 "$tmp/$2")"; fi; }
hasnt() { if grep -q -- "$1" "$tmp/$2"; then bad "'$1' in $2: $(grep -- "$1" "$tmp/$2")"; else ok; fi; }
run() { expect "$@"; hasnt "$src/" err; } # no message names a source file by its absolute path

# --version, and --help on every command
run 0 10 "$tool" --version; has '^sabre-sph [0-9]*\.[0-9]*\.[0-9]*$' out
for c in run mesh scalar gamma stability wave; do run 0 10 "$tool" $c --help; has '^usage:' out; done
run 0 10 "$tool" --help; has 'sabre-sph <command> --help' out

# the default: one thread with a passive wait policy, without --threads or OMP_* variables;
# start-up summary (particles, vertices, segments, h, c0, dt) and closing summary
run 0 60 env -u OMP_NUM_THREADS -u OMP_WAIT_POLICY "$tool" run "$tmp/case.yaml" --output "$tmp/d"
has '72 vertices, 72 segments; dr = 0.025 m, h = 0.05 m, c0 = 15 m/s; dt about' err
has '1 thread (wait policy passive)' err
has 'done at t = 0.01 s: [0-9]* steps, [0-9]* outputs, .* particle-steps/s; outputs in' err
has 'about .* fluid particles and .* wall segments' err # the size estimate before meshing
run 0 60 env -u OMP_WAIT_POLICY OMP_NUM_THREADS=2 "$tool" run "$tmp/case.yaml" --output "$tmp/d2"
has '2 threads (wait policy passive)' err
run 2 10 "$tool" run "$tmp/case.yaml" --output "$tmp/d3" --threads 1 --threads 2
has 'given twice' err

# bounded inputs: errors within seconds, naming the key
run 2 20 "$tool" run "$tmp/case.yaml" --output "$tmp/e1" --set time.output_interval=1e-300
has 'time.output_interval: .*at most' err
run 2 20 "$tool" run "$tmp/case.yaml" --output "$tmp/e2" --set geometry.dr=1e-7
has 'geometry.dr: .*memory' err
run 2 20 "$tool" mesh "$tmp/case.yaml" --output "$tmp/e3" --set 'geometry.walls[0].hi=[10000, 10000]' \
  --set geometry.dr=0.0001
has 'geometry.dr: .*memory' err
# a 10 km STL box in 3D (a file in millimetres read as metres)
{
  echo "solid box"
  L=10000
  for f in "0 0 0;$L 0 0;$L $L 0" "0 0 0;$L $L 0;0 $L 0" "0 0 $L;$L $L $L;$L 0 $L" \
           "0 0 $L;0 $L $L;$L $L $L" "0 0 0;0 0 $L;$L 0 $L" "0 0 0;$L 0 $L;$L 0 0" \
           "0 $L 0;$L $L 0;$L $L $L" "0 $L 0;$L $L $L;0 $L $L" "0 0 0;0 $L 0;0 $L $L" \
           "0 0 0;0 $L $L;0 0 $L" "$L 0 0;$L 0 $L;$L $L $L" "$L 0 0;$L $L $L;$L $L 0"; do
    echo " facet normal 0 0 0"; echo "  outer loop"
    IFS=";" read -r a c b <<<"$f"; echo "   vertex $a"; echo "   vertex $b"; echo "   vertex $c"
    echo "  endloop"; echo " endfacet"
  done
  echo "endsolid box"
} >"$tmp/big.stl"
cat >"$tmp/stl.yaml" <<'YAML'
geometry:
  dimension: 3
  dr: 0.02
  walls:
    - type: stl
      file: big.stl
  fluid:
    - type: box
      lo: [0, 0, 0]
      hi: [0.1, 0.1, 0.1]
YAML
run 2 20 "$tool" mesh "$tmp/stl.yaml" --output "$tmp/e4"
has 'geometry.dr: .*wall segments.*memory.*unit' err
run 2 10 "$tool" run "$tmp/case.yaml" --output "$tmp/e5" --set geometry.h_over_dr=1e6
has 'geometry.h_over_dr: expected a number in \[1, 20\]' err
run 2 10 "$tool" run "$tmp/case.yaml" --output "$tmp/e6" \
  --set 'geometry.fluid[0]={type: polygon, points: [[0, 0], [0.2, 0.2], [0.2, 0], [0, 0.2]]}'
has 'geometry.fluid\[0\].points: the polygon crosses itself' err
run 2 10 "$tool" run "$tmp/case.yaml" --output "$tmp/e7" \
  --set 'geometry.walls[0]={type: polygon, points: [[0, 0], [0.5, 0.4], [0.5, 0], [0, 0.4]]}'
has 'geometry.walls\[0\].points: the polygon crosses itself' err

# time.max_steps: stopped before time.end with exit 3 (as sabre-fv1d), checkpoint written
run 3 60 "$tool" run "$tmp/case.yaml" --output "$tmp/m" --set time.max_steps=4
has 'time.max_steps = 4 reached' err
[ -f "$tmp/m/checkpoint.bin" ] && ok || bad "no checkpoint after time.max_steps"

# messages say why and where: a bad initial expression names file:line and the key; a time step
# that is not positive says which limit; output directories that cannot be created say why
sed 's/pressure: hydrostatic/pressure: "1000 * sqrt(x - 0.1)"/' "$tmp/case.yaml" >"$tmp/expr.yaml"
run 2 20 "$tool" run "$tmp/expr.yaml" --output "$tmp/x1"
has 'expr.yaml:17:[0-9]*: initial.pressure: .* at the fluid particle' err
[ -e "$tmp/x1" ] && bad "a run directory was created for bad input" || ok
run 1 20 "$tool" run "$tmp/case.yaml" --output "$tmp/x2" --set 'initial.velocity=[1e300, 0]'
has 'time step 0 s is not positive: fluid particle id .* non-finite state' err
run 2 10 "$tool" run "$tmp/case.yaml" --output /dev/null/out
has "cannot create the output directory '/dev/null/out': Not a directory" err

# stability: the summary on stdout, every mode in DIR/stability.csv (fastest first), the counts
# consistent with the file; a lid box (no free surface, p > 0 at the lid) has no static
# instability; open boundaries, too many unknowns and bad options are refused before any output
py=/usr/bin/python3
run 0 60 "$tool" stability "$tmp/case.yaml" --output "$tmp/st" --modes 3
has '^unknowns: 128 (64 fluid particles x 2)' out
has '^static instabilities (real lambda > 0, growth above 0.001 1/s): [1-9]' out # docs §7.1
if $py - "$tmp/st/stability.csv" "$tmp/out" <<'PY'; then ok; else bad "stability.csv: $(head -3 "$tmp/st/stability.csv")"; fi
import csv, re, sys
rows = list(csv.DictReader(open(sys.argv[1])))
rates = [float(r["rate"]) for r in rows]
nstatic = sum(float(r["lambda_im"]) == 0 and float(r["rate"]) > 1e-3 for r in rows)
want = int(re.search(r"growth above 0.001 1/s\): (\d+)", open(sys.argv[2]).read()).group(1))
ok = (len(rows) == 128 and rates == sorted(rates, reverse=True) and nstatic == want
      and all(0 < float(r["share"]) <= 1 and 1 <= float(r["participation"]) <= 64 for r in rows)
      and all(abs(sum(float(r[k]) ** 2 for k in ("dir_x", "dir_y", "dir_z")) - 1) < 1e-12 for r in rows))
sys.exit(0 if ok else 1)
PY
cat >"$tmp/lid.yaml" <<'YAML'
geometry:
  dimension: 2
  dr: 0.025
  h_over_dr: 2
  first_row: 1
  walls: [{type: box, lo: [0, 0], hi: [0.3, 0.2]}]
  fluid: [{type: box, lo: [0, 0], hi: [0.3, 0.2]}]
fluid: {rho0: 1000, c0: 20}
gravity: [0, -9.81]
initial: {pressure: hydrostatic, free_surface: 0.5}
numerics: {vertex_volume: geometric}
repack: {steps: 1000}
time: {end: 1}
YAML
run 0 60 "$tool" stability "$tmp/lid.yaml" --output "$tmp/st2" --modes 0
has '^static instabilities (real lambda > 0, growth above 0.001 1/s): 0$' out
has '^largest growth rate: 0\.0[0-4]' out # as tests/sph/test_linear_stability.c (0.012 1/s)
# about a run's state: the checkpoint of the first run above (t = 0.01 s)
run 0 60 "$tool" stability "$tmp/case.yaml" --output "$tmp/stf" --modes 0 --from "$tmp/d/checkpoint.bin"
has '^state at t = 0.01 s (step [1-9][0-9]*): largest speed' out
run 2 20 "$tool" stability "$tmp/case.yaml" --output "$tmp/stg" --from "$tmp/d/checkpoint.bin" \
  --set fluid.c0=20
has 'stability: --from: .*differs' err
run 2 20 "$tool" stability "$tmp/case.yaml" --output "$tmp/sth" --from "$tmp/nothing.bin"
has 'stability: --from: .*nothing.bin: cannot open' err
cp "$src/cases/sph/open_channel_2d/case.yaml" "$tmp/open.yaml"
run 2 20 "$tool" stability "$tmp/open.yaml" --output "$tmp/st3"
has 'open_boundaries: stability is for closed domains' err
[ -e "$tmp/st3" ] && bad "a stability directory was created for a refused case" || ok
# repack.settle: the set-up's settling run, summarised; refused with open boundaries
run 0 60 "$tool" run "$tmp/case.yaml" --output "$tmp/sett" --set repack.settle=0.02
has "settling: 0.02 s of the case's dynamics in [1-9][0-9]* steps" err
run 2 20 "$tool" run "$tmp/open.yaml" --output "$tmp/sett2" --set repack.settle=0.1
has 'repack.settle: a settling run is for closed domains at rest: not with open_boundaries' err
# repack.layer_equilibrium: summarised; refused with open boundaries
run 0 60 "$tool" run "$tmp/case.yaml" --output "$tmp/lay" --set repack.layer_equilibrium=true
has 'layer equilibrium: 8 layers moved up by [-+][0-9.]*, .*largest mean vertical acceleration of a layer [0-9.e-]* g' err
run 2 20 "$tool" run "$tmp/open.yaml" --output "$tmp/lay2" --set repack.layer_equilibrium=true
has 'repack.layer_equilibrium: the layer equilibrium of water at rest needs no open_boundaries' err
[ -e "$tmp/lay2" ] && bad "an output directory was created for a refused case" || ok
cp "$src/cases/sph/stokes_waves/periodic.yaml" "$tmp/wave.yaml"
run 2 20 "$tool" run "$tmp/wave.yaml" --output "$tmp/lay3" --set repack.layer_equilibrium=true
has 'repack.layer_equilibrium: the layer equilibrium of water at rest needs no initial.wave' err
run 2 20 "$tool" stability "$tmp/case.yaml" --output "$tmp/st4" --max-unknowns 100
has '128 unknowns, more than the 100 of stability' err
run 2 10 "$tool" stability "$tmp/case.yaml" --output "$tmp/st5" --modes -1
has '\--modes: expected a whole number >= 0' err
run 2 10 "$tool" stability "$tmp/case.yaml" --output "$tmp/st5" --eps 0
has '\--eps: expected a number in (0, 0.01\]' err
run 2 10 "$tool" stability "$tmp/case.yaml" --output "$tmp/st5" --min-rate -1
has '\--min-rate: expected a number >= 0' err

# wave generators: one JSON object per --at point (parsed by Python, as tests/riemann/cli.sh does),
# with the documented keys; values checked for consistency (the crest of J IV.B's wave at x = ct,
# the period given back as a length, the solitary crest D + A with p = 0 on it)
# wave_json 'python expression over the list of objects d' args...
wave_json() {
  local expr=$1; shift
  run 0 10 "$tool" wave "$@"
  if $py -c "import json,sys; d=[json.loads(l) for l in open(sys.argv[1])]; sys.exit(0 if ($expr) else 1)" \
       "$tmp/out" 2>>"$tmp/err"; then ok
  else bad "wave $*: '$expr' fails on: $(head -c 600 "$tmp/out")"; fi
}
S5=(stokes5 --depth 0.5 --height 0.1 --length 2.5)
wave_json 'len(d) == 3 and all(set(o) == {"x","z","t","eta","u","w","p","c","k","L","T","in_water"} for o in d)
  and d[0]["in_water"] and abs(d[0]["eta"] - d[1]["eta"]) < 1e-12 and d[1]["x"] == d[1]["c"] * 0.7
  and abs(d[1]["T"] - 2.5 / d[1]["c"]) < 1e-12 and d[2]["eta"] < 0.5 and d[0]["w"] == 0' \
  "${S5[@]}" --at 0,0.3,0 --at "$($py -c 'print(1.8440565949008831*0.7)')",0.3,0.7 --at 1.25,0.2,0
wave_json 'abs(d[0]["L"] - 2.5) < 1e-9 and abs(d[0]["eta"] - 0.5559024446561869) < 1e-9' \
  stokes5 --depth 0.5 --amplitude 0.05 --period 1.3557067645932925 --at 0,0.2,0
wave_json 'not d[0]["in_water"] and d[0]["p"] < 0 and d[1]["u"] is None' "${S5[@]}" --at 0,0.6,0 --at 0,9,0
has 'above the free surface' err
wave_json 'set(d[0]) == {"x","y","z","t","eta","u","v","w","p","c","k","in_water"}
  and abs(d[0]["eta"] - 0.9) < 1e-12 and abs(d[0]["p"]) < 1e-9 and abs(d[0]["v"] - d[0]["u"]) < 1e-12
  and abs(d[1]["p"] - 1000 * 9.81 * d[1]["eta"]) < 1e-9' \
  solitary --depth 0.6 --amplitude 0.3 --angle 45 --x0 -1 --at "$($py -c 'import math; s=-1+math.sqrt(9.81*0.9)*0.4; print(f"{s/math.sqrt(2)!r},{s/math.sqrt(2)!r}")')",0.9,0.4 --at 0.2,0.1,0,0.4
# bad input: exit 2, a message naming the option
run 2 10 "$tool" wave; has 'wave needs a kind' err
run 2 10 "$tool" wave cnoidal --depth 1; has "unknown kind 'cnoidal'" err
run 2 10 "$tool" wave "${S5[@]}" --depth 0.6 --at 0,0,0; has '--depth given twice' err
run 2 10 "$tool" wave "${S5[@]}" --at 0,0,0 --at 1,0,0 --colour red; has "unknown option '--colour'" err
run 2 10 "$tool" wave "${S5[@]}" --current 1x --at 0,0,0; has "--current '1x': expected a number" err
run 2 10 "$tool" wave "${S5[@]}" --at 0,0; has "--at '0,0': expected X,Z,T" err
run 2 10 "$tool" wave "${S5[@]}"; has 'needs at least one --at' err
run 2 10 "$tool" wave stokes5 --height 0.1 --length 2.5 --at 0,0,0; has 'needs --depth' err
run 2 10 "$tool" wave stokes5 --depth 0.5 --length 2.5 --at 0,0,0; has '--height H or --amplitude' err
run 2 10 "$tool" wave "${S5[@]}" --period 1 --at 0,0,0; has '--length L or --period T, not both' err
run 2 10 "$tool" wave stokes5 --depth 0.5 --height 0.5 --length 2.5 --at 0,0,0
has '--height: H/L = 0.2 exceeds the breaking limit' err
run 2 10 "$tool" wave stokes5 --depth 0.5 --height 0.05 --length 10 --at 0,0,0
has '--length: the wave is too long for the depth: Ursell number' err
run 2 10 "$tool" wave stokes5 --depth 0.5 --height 0.05 --period 10 --at 0,0,0
has '--period: T = 10 s gives a wave too long' err
run 2 10 "$tool" wave "${S5[@]}" --current -3 --at 0,0,0; has '--current: .* not positive' err
run 2 10 "$tool" wave solitary --depth 0.6 --amplitude 0.5 --at 0,0,0,0; has '--amplitude: A/D' err
run 2 10 "$tool" wave solitary --depth 0 --amplitude 0.1 --at 0,0,0,0; has "--depth '0'" err
run 2 10 "$tool" wave solitary --depth 0.6 --amplitude 0.3 --at 0,0,0; has 'expected X,Y,Z,T' err
run 0 10 "$tool" wave stokes5 --help; has 'Fenton' out

# results on stdout that cannot be written are a failure
if [ -w /dev/full ]; then
  timeout 20 "$tool" gamma --dim 2 --dr 0.1 --h-over-dr 2 --box 0,0:1,1 --at 0.5,0.5 \
    >/dev/full 2>"$tmp/err"; rc=$?
  [ $rc -eq 1 ] && ok || bad "gamma > /dev/full: exit $rc (want 1)"
  has 'cannot write the output' err
  timeout 20 "$tool" --help >/dev/full 2>/dev/null; rc=$?
  [ $rc -eq 1 ] && ok || bad "--help > /dev/full: exit $rc (want 1)"
fi
finish
