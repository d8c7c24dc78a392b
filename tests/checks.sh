# Sourced by the shell tests (tests/mpi, tests/viewer): a scratch folder removed at exit, and
# failed checks counted — fail MESSAGE records one, finish exits 1 if any failed and otherwise
# prints "all checks passed" (what ctest's PASS_REGULAR_EXPRESSION looks for).
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
failures=0

fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

finish() {
  if [ "$failures" -gt 0 ]; then
    echo "$failures check(s) failed"
    exit 1
  fi
  echo "all checks passed"
}
