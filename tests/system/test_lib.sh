# Shared by the shell tests (tests/cli, tests/parallel, tests/run, tests/system/campaign): a scratch folder
# removed on exit, a failure counter, and Open MPI's settings for mpirun as root in a container (no
# single-copy transfers, which a container's ptrace limits refuse). Source it after setting case_name.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
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
