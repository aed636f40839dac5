#!/usr/bin/env bash
# The sabre-riemann command-line interface: JSON keys and values, CSV sweep, and one-line errors
# with exit code 2 for bad input. Usage: cli.sh PATH/TO/sabre-riemann
set -u
tool=$1
. "$(dirname "$0")/../checklib.sh"
py=/usr/bin/python3

# json_check 'python expression over d' args...: runs the tool, parses stdout as JSON
json_check() {
  local expr=$1; shift
  local out
  if ! out=$("$tool" "$@" 2>/tmp/cli_err.$$); then bad "exit status for: $*"; return; fi
  if echo "$out" | $py -c "import json,sys; d=json.load(sys.stdin); sys.exit(0 if ($expr) else 1)"; then ok
  else bad "$expr for: $*  ->  $out"; fi
}

# error_check args...: exit 2, exactly one line on stderr starting with the program name, no stdout
error_check() {
  local out err rc
  out=$("$tool" "$@" 2>/tmp/cli_err.$$); rc=$?
  err=$(cat /tmp/cli_err.$$)
  if [ $rc -ne 2 ]; then bad "exit $rc (want 2) for: $*"; return; fi
  if [ -n "$out" ]; then bad "stdout not empty for: $*"; return; fi
  if [ "$(printf '%s\n' "$err" | wc -l)" -ne 1 ] || [[ "$err" != "sabre-riemann: error: "* ]]; then
    bad "stderr not one 'sabre-riemann: error:' line for: $*: $err"; return; fi
  ok
}

W=(--xi 7 --rho0 1000 --c0 20)
# boundary: keys and types
json_check 'set(d)=={"wave","flow","rho","p","un","ut","shock_speed"} and d["wave"]=="shock" and d["flow"]=="inflow" and d["ut"]==[0] and d["un"]==0 and d["shock_speed"]>20' \
  boundary "${W[@]}" --interior 1000,-0.5,0.3 --velocity 0
# water hammer: Δp = ρ_int (S − u_int)(u2 − u_int) exactly (mass+momentum), ≈ ρ c Δu
json_check 'abs(d["p"] - 1000*(d["shock_speed"]+0.5)*0.5) < 1e-9*d["p"] and abs(d["p"]/(1000*20*0.5)-1) < 0.06' \
  boundary "${W[@]}" --interior 1000,-0.5 --velocity 0
json_check 'd["wave"]=="expansion" and d["shock_speed"] is None and d["p"]==-2000 and d["ut"]==[]' \
  boundary "${W[@]}" --interior 1000,0.5 --pressure -2000
json_check 'd["wave"]=="contact" and abs(d["rho"]-1000)<1e-12 and d["un"]==0.5' \
  boundary "${W[@]}" --interior 1000,0.5 --pressure 0
# tangential: imposed on inflow, interior on outflow (3D)
json_check 'd["flow"]=="inflow" and d["ut"]==[0.25,-0.5]' \
  boundary "${W[@]}" --interior 1000,1,7,8 --pressure 100 --tangential 0.25,-0.5
json_check 'd["flow"]=="outflow" and d["ut"]==[7,8]' \
  boundary "${W[@]}" --interior 1000,-1,7,8 --pressure 100 --tangential 0.25,-0.5
json_check 'd["shock_speed"]==0 and d["wave"]=="shock"' \
  boundary "${W[@]}" --interior 1000,-0.5 --velocity 0 --shock linearised
# exact: keys, Ritter dry-bed values for ξ = 2 (h = (2c_L − s)²/(9g), g = c0²/ρ0 = 1)
json_check 'set(d)>={"rho_star","u_star","p_star","waves","vacuum","samples"} and d["vacuum"] is True and d["u_star"] is None and abs(d["samples"][1]["rho"]-4/9)<1e-14 and abs(d["samples"][1]["u"]-2/3)<1e-14 and d["samples"][2]["rho"]==0' \
  exact --xi 2 --rho0 1 --c0 1 --left 1,0 --right 0,0 --at -1 --at 0 --at 2.5
json_check 'd["waves"]==["rarefaction","shock"] and d["vacuum"] is False and len(d["samples"])==0 and 0.5<d["rho_star"]<1' \
  exact --xi 2 --rho0 1 --c0 1 --left 1,0 --right 0.5,0
json_check 'd["waves"]==["shock","shock"] and d["rho_star"]>1000' \
  exact "${W[@]}" --left 1000,1 --right 1000,-1 --at 0

# sweep: header and one row per grid point
out=$("$tool" sweep "${W[@]}" --rho-int 1000 --un-int -1:1:3 --pressure -100:100:5)
if [ "$(echo "$out" | head -1)" = "imposed,value,rho_int,un_int,status,wave,flow,rho,p,un,shock_speed" ] \
   && [ "$(echo "$out" | wc -l)" -eq 16 ] && echo "$out" | grep -q ",RMN_SUCCESS,shock,"; then ok
else bad "sweep output"; fi

# errors: unknown flag/command, missing value, non-numeric, non-physical, supersonic, cavitation
error_check
error_check frobnicate
error_check boundary "${W[@]}" --interior 1000,0 --pressure 0 --bogus 1
error_check boundary "${W[@]}" --interior 1000,0 --pressure
error_check boundary "${W[@]}" --interior 1000,abc --pressure 0
error_check boundary "${W[@]}" --interior 1000,0 --pressure 1e999
error_check boundary "${W[@]}" --interior 1000,0
error_check boundary "${W[@]}" --interior 1000,0 --pressure 0 --velocity 0
error_check boundary --xi 0.5 --rho0 1000 --c0 20 --interior 1000,0 --pressure 0
error_check boundary --xi 7 --rho0 -1 --c0 20 --interior 1000,0 --pressure 0
error_check boundary --rho0 1000 --c0 20 --interior 1000,0 --pressure 0
error_check boundary "${W[@]}" --interior -3,0 --pressure 0
error_check boundary "${W[@]}" --interior 1000,0,1 --pressure 0 --tangential 1,2
error_check boundary "${W[@]}" --interior 1000,0,1,2,3 --pressure 0
error_check boundary "${W[@]}" --interior 1000,25 --pressure 0
error_check boundary "${W[@]}" --interior 1000,0 --pressure -1e9
error_check boundary "${W[@]}" --interior 1000,0 --pressure 0 --shock maybe
error_check exact "${W[@]}" --left 0,0 --right 0,0
error_check exact "${W[@]}" --left 1000 --right 1000,0
error_check exact "${W[@]}" --left -1,0 --right 1000,0
error_check sweep "${W[@]}" --rho-int 1000 --un-int 0:1 --pressure 0:1:2
error_check sweep "${W[@]}" --rho-int 1000 --un-int 0:1:0 --pressure 0:1:2
# strict input: empty list items, repeated options, xi beyond fv1d's range, absurd magnitudes
# are input errors (exit 2), never read loosely nor reported as solver failures
error_check boundary "${W[@]}" --interior 1000,,5 --pressure 0
error_check boundary "${W[@]}" --interior ,1000,5 --pressure 0
error_check boundary "${W[@]}" --interior 1000,0 --pressure 0 --xi 7
error_check boundary "${W[@]}" --interior 1000,0 --interior 1000,1 --pressure 0
error_check exact "${W[@]}" --left 1000,0 --right 1000,0 --left 1000,1
error_check boundary --xi 1e6 --rho0 1000 --c0 20 --interior 1000,0 --pressure 0
error_check boundary "${W[@]}" --interior 1000,0 --pressure 1e300
error_check boundary "${W[@]}" --interior 1e300,0 --pressure 0
error_check boundary "${W[@]}" --interior 1000,0 --velocity 1e300
error_check sweep "${W[@]}" --rho-int 1000 --un-int 0:1:2 --pressure 0:1e300:2
# --help after a command and --version print on stdout, exit 0
for c in boundary exact sweep; do
  if "$tool" $c --help | grep -q "^usage:"; then ok; else bad "$c --help"; fi
done
if [ "$("$tool" --version)" = "sabre-riemann $("$tool" --version | cut -d' ' -f2)" ] \
   && "$tool" --version | grep -Eq '^sabre-riemann [0-9]+\.[0-9]+\.[0-9]+$'; then ok; else bad "--version"; fi
# a write error on stdout is a failure (exit 1), not a silent success
if [ -w /dev/full ]; then
  "$tool" boundary "${W[@]}" --interior 1000,0 --pressure 0 >/dev/full 2>/dev/null
  rc=$?; [ $rc -eq 1 ] && ok || bad "boundary > /dev/full: exit $rc (want 1)"
  "$tool" exact "${W[@]}" --left 1000,0 --right 1000,0 >/dev/full 2>/dev/null
  rc=$?; [ $rc -eq 1 ] && ok || bad "exact > /dev/full: exit $rc (want 1)"
  "$tool" --help >/dev/full 2>/dev/null
  rc=$?; [ $rc -eq 1 ] && ok || bad "--help > /dev/full: exit $rc (want 1)"
fi
rm -f /tmp/cli_err.$$
finish
