#!/usr/bin/env bash
# The documentation as a new user reads it: it cites what the repository ships (docs/theory.md,
# full references for "J" and "M", no notes kept elsewhere), carries no internal process words,
# its case-file example runs, and a case's `check` works as the case READMEs say after `make run`
# (it finds the built program and writes under the build directory, not into the sources).
# Usage: docs.sh SOURCE_DIR BUILD_DIR PATH/TO/sabre-sph
set -u
src=$1 build=$2 sph=$3
. "$(dirname "$0")/checklib.sh"
cd "$src" || exit 1
user_docs=(README.md docs/*.md cases/*/*/README.md riemann/include/sabre/*.h fv1d/include/sabre/*.h
           sph/include/sabre/*.h common/include/sabre/*.h)

# 1. references resolve inside the repository
if grep -n -E 'THEORY\.md|shared/THEORY|shared/papers|papers/0|"THEORY"|THEORY §' "${user_docs[@]}"; then
  bad "documents cite theory notes or papers that are not in the repository"
else ok; fi
[ -s docs/theory.md ] && ok || bad "docs/theory.md missing"
for f in README.md docs/README.md docs/theory.md; do
  t=$(tr '\n' ' ' <"$f" | tr -s ' ')
  if grep -q -E 'Joly, (D\. )?Violeau, (A\. )?Leroy, (M\. )?Ferrand' <<<"$t" && grep -q 'SPHERIC' <<<"$t" &&
     grep -q -E 'Mayrhofer, (B\. D\. )?Rogers, (D\. )?Violeau, (M\. )?Ferrand' <<<"$t" &&
     grep -q -E 'Comput(er)?\.? Phys(ics)?\.? Commun(ications)?\.? 184 \(2013\) 2515–2527' <<<"$t"; then ok
  else bad "$f: no full citation of J (Joly et al., SPHERIC 2016) and M (Mayrhofer et al., CPC 2013)"; fi
done
# markdown links to local files exist
for f in README.md docs/*.md; do
  d=$(dirname "$f")
  for l in $(grep -o -E '\]\([^)#: ]+\)' "$f" | sed -E 's/^\]\(//; s/\)$//'); do
    [ -e "$d/$l" ] && ok || bad "$f: broken link $l"
  done
done

# 2. no internal process words ("issue 5", "session 2") in user documents
if grep -n -i -E '\b(issue|session)s? #?[0-9]' "${user_docs[@]}" | grep -v 'LLNL/sundials issue'; then
  bad "internal process words in user documents"
else ok; fi

# 3. the example of docs/case-files.md is a case that runs
awk '/^```yaml/{f=1; next} /^```/{if (f) exit} f' docs/case-files.md >"$tmp/dam.yaml"
if [ -s "$tmp/dam.yaml" ] &&
   "$sph" run "$tmp/dam.yaml" --output "$tmp/ex" --set time.end=0.005 >"$tmp/log" 2>&1; then ok
else bad "the example of docs/case-files.md does not run: $(tail -2 "$tmp/log")"; fi

# 4. a case check with no arguments, run from its directory after a build (the build directory
# given as `make run` would leave it): it finds the program, writes under the build directory
touch "$tmp/marker"
sleep 1
if (cd cases/fv1d/dam_break_stoker && PATH=/usr/bin:/bin SABRE_BUILD=$build ./check) \
     >"$tmp/check.log" 2>&1; then ok
else bad "cases/fv1d/dam_break_stoker/check: $(tail -3 "$tmp/check.log")"; fi
[ -f "$build/cases/fv1d/dam_break_stoker/summary.yaml" ] && ok ||
  bad "check did not write into $build/cases/fv1d/dam_break_stoker"
new=$(find cases -newer "$tmp/marker" -print)
[ -z "$new" ] && ok || bad "check wrote into the source tree: $new"
finish
