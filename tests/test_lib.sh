# Shared by the shell tests (tests/cli, tests/parallel): a scratch folder removed on exit, and a
# failure counter. Source it after setting case_name.
work=$(mktemp -d "${TMPDIR:-/tmp}/raceway_${case_name}.XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}
# The last lines of a case: its verdict ("CASE: passed", which ctest looks for) and exit code.
finish() {
  if [[ $failures -gt 0 ]]; then
    echo "$case_name: $failures failure(s)" >&2
    exit 1
  fi
  echo "$case_name: passed"
}
