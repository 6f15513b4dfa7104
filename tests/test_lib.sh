# Shared by the shell tests (tests/cli, tests/parallel): a scratch folder removed on exit, and a
# failure counter. Source it after setting case_name.
work=$(mktemp -d "${TMPDIR:-/tmp}/raceway_${case_name}.XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}
