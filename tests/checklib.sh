# Shared by the shell tests (tests/docs.sh, tests/*/cli.sh): pass/fail counters, a scratch
# directory removed on exit, and the closing line that ctest's log reads. Source it, call ok or
# bad "what failed" per check, and end with `finish`.
fails=0 passes=0
ok() { passes=$((passes + 1)); }
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Print "N passed, N failed"; exit status 0 when nothing failed.
finish() {
  echo "$passes passed, $fails failed"
  [ "$fails" -eq 0 ]
}
