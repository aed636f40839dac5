#!/bin/sh
# A known failure, run as a test that can still fail: runs COMMAND, prints its output, and passes
# only when COMMAND exits non-zero AND its output contains every PATTERN (grep -F), i.e. when it
# fails in the documented way. A crash, a failure of another kind, or the case starting to hold
# all make this test fail, so that ctest reports the change (ctest's WILL_FAIL would pass on any
# non-zero exit, crashes included).
# usage: known_failure.sh PATTERN [PATTERN ...] -- COMMAND [ARG ...]
set -u
n=0
for a in "$@"; do
  [ "$a" = "--" ] && break
  n=$((n + 1))
done
if [ "$n" -eq 0 ] || [ "$n" -ge "$#" ]; then
  echo "usage: known_failure.sh PATTERN [PATTERN ...] -- COMMAND [ARG ...]" >&2
  exit 2
fi
log=$(mktemp) || exit 2
trap 'rm -f "$log" "$log.patterns"' EXIT
i=0
for a in "$@"; do  # the patterns, kept in order as positional parameters after the command
  i=$((i + 1))
  [ "$i" -gt "$n" ] && break
  printf '%s\n' "$a" >> "$log.patterns"
done
shift $((n + 1))
"$@" > "$log" 2>&1
status=$?
cat "$log"
ok=1
if [ "$status" -eq 0 ]; then
  echo "known_failure.sh: the command now succeeds: the known failure is gone, update its registration" >&2
  ok=0
fi
while IFS= read -r p; do
  if ! grep -qF -- "$p" "$log"; then
    echo "known_failure.sh: expected in the output, not found: $p" >&2
    ok=0
  fi
done < "$log.patterns"
rm -f "$log.patterns"
[ "$ok" -eq 1 ] && exit 0
exit 1
