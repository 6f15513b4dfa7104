#!/usr/bin/env bash
# What `raceway run` prints on a terminal and in a log, one case per ctest.
#
#   terminal_test.sh CASE RACEWAY_EXECUTABLE SOURCE_DIR
#
# progress_tty   on a terminal (a pseudo-terminal from script(1)) a spatial run's progress bar is
#                redrawn at most 5 times a second, reaches 100 %, and its line ends before "done"
# progress_log   without a terminal: one progress line per 10 % at most, no carriage returns
# log_levels     errors and warnings name their level: "[raceway] error: ..."
# petsc_options  PETSC_OPTIONS from the environment reaches PETSc: -log_view prints PETSc's
#                performance summary; a misspelt option in it is an error naming PETSC_OPTIONS (exit 2);
#                PETSc's information flags (-help, -h, -version) are refused in a line, exit 2, from
#                the command line, the scene and the environment
set -u

case_name=${1:?case}
raceway=${2:?raceway executable}
source_dir=${3:?source dir}

source "$source_dir/tests/system/test_lib.sh"

# A copy of a job scene with another end time (and optionally another linear solver).
short_scene() {  # SCENE END_TIME OUT [LINEAR_SOLVER]
  sed "s/^end_time = .*/end_time = \"$2\"/" "$source_dir/jobs/scenes/$1.toml" >"$3"
  [[ -n "${4:-}" ]] && sed -i "s/^linear_solver = .*/linear_solver = \"$4\"/" "$3"
  return 0
}

case "$case_name" in

progress_tty)
  command -v script >/dev/null || { echo "SKIP: no script(1)"; echo "$case_name: passed"; exit 0; }
  short_scene 6309_R3 "0.04 s" "$work/r3.toml"
  script -qec "'$raceway' run '$work/r3.toml' -o '$work/r3.h5'" /dev/null >"$work/tty" 2>&1
  rc=$?
  [[ $rc -eq 0 ]] || fail "run on a terminal: exit code $rc"
  seconds=$(/usr/bin/python3 -c "import json,h5py; print(json.loads(h5py.File('$work/r3.h5')['/'].attrs['summary_json'])['wall_time_s'])")
  draws=$(grep -o $'\r\[' "$work/tty" | wc -l)
  # 5 per second of wall time, plus the first and the last draw.
  allowed=$(/usr/bin/python3 -c "import math; print(int(5 * $seconds) + 3)")
  [[ $draws -ge 1 && $draws -le $allowed ]] || fail "the bar was drawn $draws times in $seconds s (at most $allowed)"
  bytes=$(wc -c <"$work/tty")
  [[ $bytes -lt 20000 ]] || fail "$bytes bytes on the terminal for a 2001-sample run"
  # The last bar says 100 % and its line ends: "done" starts a line of its own.
  tr '\r' '\n' <"$work/tty" | grep -q '100.0%' || fail "the bar never shows 100 %"
  tr '\r' '\n' <"$work/tty" | grep -q '^\[raceway\] done: ' || fail "'done' does not start its own line"
  tr '\r' '\n' <"$work/tty" | grep -q '%.*\[raceway\] done' && fail "the bar's line is glued to 'done'"
  ;;

progress_log)
  short_scene 6309_R3 "0.04 s" "$work/r3.toml"
  "$raceway" run "$work/r3.toml" -o "$work/r3.h5" >"$work/out" 2>"$work/err" || fail "run: exit code $?"
  lines=$(grep -c ' s of .* s (.* %)' "$work/err")
  [[ $lines -ge 5 && $lines -le 10 ]] || fail "$lines progress lines in the log, expected one per 10 %"
  grep -q $'\r' "$work/err" && fail "carriage returns in a log"
  ;;

log_levels)
  "$raceway" run "$work/missing.toml" >"$work/out" 2>"$work/err"
  [[ $? -eq 2 ]] || fail "missing scene: exit code not 2"
  grep -q '^\[raceway\] error: .*missing.toml' "$work/err" || fail "no '[raceway] error: ' line: $(cat "$work/err")"
  "$raceway" report "$work/missing.h5" >"$work/out" 2>"$work/err"
  [[ $? -eq 2 ]] || fail "report of a missing file: exit code not 2"
  grep -q '^\[raceway\] error: report: .*missing.h5' "$work/err" || fail "report: no error line: $(cat "$work/err")"
  # Information carries no level word.
  short_scene default "0.002 s" "$work/d.toml"
  "$raceway" run "$work/d.toml" -o "$work/d.h5" >"$work/out" 2>"$work/err" || fail "short run failed"
  grep -q '^\[raceway\] done: ' "$work/err" || fail "info lines are not '[raceway] text'"
  ;;

petsc_options)
  short_scene default "0.002 s" "$work/p.toml" petsc-bordered
  PETSC_OPTIONS="-log_view" "$raceway" run "$work/p.toml" -o "$work/p.h5" >"$work/out" 2>"$work/err"
  rc=$?
  [[ $rc -eq 0 ]] || fail "PETSC_OPTIONS=-log_view: exit code $rc: $(cat "$work/err")"
  grep -q 'PETSc Performance Summary' "$work/out" "$work/err" || fail "-log_view printed no performance summary"
  PETSC_OPTIONS="-fieldsplit_1_pc_typo lu" "$raceway" run "$work/p.toml" -o "$work/q.h5" >"$work/out" 2>"$work/err"
  rc=$?
  [[ $rc -eq 2 ]] || fail "a misspelt PETSC_OPTIONS: exit code $rc, expected 2"
  grep -q 'error: PETSC_OPTIONS (environment): .*-fieldsplit_1_pc_typo' "$work/err" ||
    fail "the error does not name PETSC_OPTIONS and the option: $(cat "$work/err")"
  [[ -e "$work/q.h5" ]] && fail "a refused run wrote its output"
  # PETSc's information flags are refused in a line or two (not PETSc's 434-line help), exit 2,
  # from the command line, the scene and the environment alike.
  for flag in -help -h -version; do
    "$raceway" run "$work/p.toml" -o "$work/h.h5" --petsc-options "$flag" >"$work/out" 2>"$work/err"
    rc=$?
    lines=$(cat "$work/out" "$work/err" | wc -l)
    [[ $rc -eq 2 ]] || fail "--petsc-options $flag: exit code $rc, expected 2"
    [[ $lines -le 3 ]] || fail "--petsc-options $flag: $lines lines printed"
    grep -q -- "error: --petsc-options: '$flag' is PETSc's information flag" "$work/err" ||
      fail "--petsc-options $flag: not named: $(cat "$work/err")"
  done
  PETSC_OPTIONS="-help" "$raceway" check "$work/p.toml" >"$work/out" 2>"$work/err"
  rc=$?
  [[ $rc -eq 2 ]] || fail "PETSC_OPTIONS=-help: exit code $rc, expected 2"
  grep -q "PETSC_OPTIONS (environment): '-help'" "$work/err" || fail "PETSC_OPTIONS=-help: $(tail -3 "$work/err")"
  "$raceway" check "$work/p.toml" --set 'solver.petsc_options="-ksp_view -help"' >"$work/out" 2>"$work/err"
  rc=$?
  [[ $rc -eq 2 ]] || fail "solver.petsc_options with -help: exit code $rc, expected 2"
  grep -q "solver.petsc_options.*'-help'" "$work/err" || fail "scene -help: $(tail -3 "$work/err")"
  [[ -e "$work/h.h5" || -e "$work/h.h5.partial" ]] && fail "a refused run wrote its output"
  ;;

*)
  echo "unknown case $case_name" >&2
  exit 2
  ;;
esac
finish
