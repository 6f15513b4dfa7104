#!/usr/bin/env bash
# The scene check must fail on a physics change: a scene run with one parameter changed (--set)
# against its answer file must exit 1 and list the expected quantities as outside their tolerance.
#
#   detects_change.sh CASE RACEWAY SOURCE_DIR SCENE KEY=VALUE QUANTITY [QUANTITY ...]
set -u
case_name=${1:?case}
raceway=${2:?raceway}
source_dir=${3:?source dir}
scene=${4:?scene}
change=${5:?KEY=VALUE}
shift 5
log=$(/usr/bin/python3 "$source_dir/scripts/scene_answers.py" --raceway "$raceway" --set "$change" \
  "$source_dir/jobs/scenes/$scene.toml" 2>&1)
rc=$?
echo "$log"
[[ $rc -eq 77 ]] && exit 77
failures=0
[[ $rc -eq 1 ]] || { echo "FAIL: --set $change: exit code $rc, expected 1 (quantities outside their tolerance)"; failures=1; }
for quantity in "$@"; do
  grep -Eq "^$quantity +.*FAIL" <<<"$log" || { echo "FAIL: --set $change: $quantity not reported outside its tolerance"; failures=1; }
done
[[ $failures -eq 0 ]] && echo "$case_name: passed"
exit $failures
