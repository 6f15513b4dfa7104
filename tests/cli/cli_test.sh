#!/usr/bin/env bash
# Behaviour tests of the `raceway` command line (exit codes, messages, files), one case per ctest.
#
#   cli_test.sh CASE RACEWAY_EXECUTABLE SOURCE_DIR [VERSION]
#
# VERSION is project(VERSION) of the top-level CMakeLists.txt (the version case needs it).
#
# Exit codes of raceway (solver/driver/main.cpp): 0 success, 2 bad scene, 3 integration failure, 1 other.
set -u

case_name=${1:?case}
raceway=${2:?raceway executable}
source_dir=${3:?source dir}
version=${4:-}

source "$source_dir/tests/test_lib.sh"

# Runs raceway with stdout and stderr captured in $work/out and $work/err; sets $rc.
run() {
  "$raceway" "$@" >"$work/out" 2>"$work/err"
  rc=$?
}

case "$case_name" in

bad_scenes)
  # (a) every broken scene: exit code 2, and stderr names the file and the offending key (the key
  # is given by the scene's "# key:" line; empty for TOML syntax errors).
  count=0
  for scene in "$source_dir"/tests/bad_scenes/*.toml; do
    count=$((count + 1))
    name=$(basename "$scene")
    key=$(sed -n 's/^# key: *//p' "$scene" | head -n 1)
    run run "$scene" -o "$work/out.h5"
    [[ $rc -eq 2 ]] || fail "$name: exit code $rc, expected 2"
    grep -qF "$name" "$work/err" || fail "$name: stderr does not name the file$(grep -qF "$name" "$work/out" && echo ' (the message went to stdout)')"
    if [[ -n "$key" ]]; then
      grep -qF "$key" "$work/err" || fail "$name: stderr does not name the key '$key'$(grep -qF "$key" "$work/out" && echo ' (the message went to stdout)')"
    fi
    [[ -e "$work/out.h5" || -e "$work/out.h5.partial" ]] && fail "$name: a bad scene created an output file"
    rm -f "$work/out.h5" "$work/out.h5.partial"
  done
  [[ $count -ge 20 ]] || fail "only $count bad scenes found in $source_dir/tests/bad_scenes"
  ;;

keep_existing_output)
  # (b) a failing run leaves an existing output file byte for byte as it was.
  head -c 4096 /dev/urandom >"$work/OUT.h5"
  cp "$work/OUT.h5" "$work/before.h5"
  run run "$source_dir/tests/bad_scenes/unknown_key.toml" -o "$work/OUT.h5"
  [[ $rc -ne 0 ]] || fail "bad scene: exit code 0"
  cmp -s "$work/OUT.h5" "$work/before.h5" || fail "OUT.h5 changed after a failed run (bad scene)"
  # ... also when the failure comes during the integration (the partial output is kept beside it).
  sed 's/^\[solver\]/[solver]\nmax_steps = 50/' "$source_dir/jobs/scenes/default.toml" >"$work/fails.toml"
  run run "$work/fails.toml" -o "$work/OUT.h5"
  [[ $rc -eq 3 ]] || fail "integration failure: exit code $rc, expected 3"
  cmp -s "$work/OUT.h5" "$work/before.h5" || fail "OUT.h5 changed after a failed run (integration failure)"
  [[ -e "$work/OUT.h5.partial" ]] || fail "no OUT.h5.partial after an integration failure"
  ;;

run_default)
  # (c) the built-in default scene: exit 0, an HDF5 file with /time, and the JSON summary.
  (cd "$work" && "$raceway" run -o x.h5 --summary-json s.json >"$work/out" 2>"$work/err")
  rc=$?
  [[ $rc -eq 0 ]] || { fail "exit code $rc"; cat "$work/out" "$work/err" >&2; }
  [[ -s "$work/x.h5" ]] || fail "x.h5 not written"
  [[ -e "$work/x.h5.partial" ]] && fail "x.h5.partial left behind after a successful run"
  if command -v h5dump >/dev/null; then
    h5dump -H "$work/x.h5" >"$work/dump" 2>&1 || fail "h5dump -H x.h5 failed"
    grep -q 'DATASET "time"' "$work/dump" || fail "x.h5 has no /time dataset"
    grep -q 'GROUP "rollers"' "$work/dump" || fail "x.h5 has no /rollers group"
  else
    fail "h5dump not found (apt-get install hdf5-tools)"
  fi
  [[ -s "$work/s.json" ]] || fail "s.json not written"
  for key in simulated_time_s wall_time_s steps rhs_evaluations jacobian_evaluations newton_failures \
    error_test_failures cage_speed_rpm epicyclic_cage_speed_rpm; do
    grep -qE "\"$key\"[[:space:]]*:[[:space:]]*[-0-9.eE+]+" "$work/s.json" || fail "s.json lacks a numeric \"$key\""
  done
  # The run reached the scene's end time (0.1 s).
  grep -qE '"simulated_time_s"[[:space:]]*:[[:space:]]*0\.1[0-9]*[,}]?' "$work/s.json" || fail "simulated_time_s is not 0.1"
  ;;

check_seed002)
  # (d) `raceway check` validates a scene and prints the model: bodies and segments.
  run check "$source_dir/jobs/scenes/seed002_40hz.toml"
  [[ $rc -eq 0 ]] || { fail "exit code $rc"; cat "$work/out" "$work/err" >&2; }
  for word in "bodies" "inner_ring" "outer_ring" "cage" "roller[0]" "roller[12]" "segments" "roller_inner_race x13" \
    "roller_outer_race x13" "cage_bar_front x13" "cage_bar_rear x13" "cage_land x1" "scene OK"; do
    grep -qF "$word" "$work/out" || fail "check output lacks '$word'"
  done
  ls "$work" | grep -q '\.h5' && fail "check wrote an output file"
  ;;

integration_failure)
  # (e) a scene whose integration must fail (a step budget of 50): exit 3 within seconds, with a
  # diagnosis naming the time and a contact.
  sed 's/^\[solver\]/[solver]\nmax_steps = 50/' "$source_dir/jobs/scenes/default.toml" >"$work/fails.toml"
  start=$(date +%s%N)
  run run "$work/fails.toml" -o "$work/f.h5"
  elapsed_ms=$((($(date +%s%N) - start) / 1000000))
  [[ $rc -eq 3 ]] || fail "exit code $rc, expected 3"
  # The message may be on either stream here; the stream is checked by the bad_scenes case.
  cat "$work/out" "$work/err" >"$work/all"
  grep -q "integration failed at t = " "$work/all" || fail "no 'integration failed at t = ' in the message"
  grep -qE "roller\[[0-9]+\]/(inner_race|outer_race|cage_bar_front|cage_bar_rear)|cage/(inner|outer)_ring_land" "$work/all" ||
    fail "the message names no contact"
  [[ $elapsed_ms -lt 10000 ]] || fail "took $elapsed_ms ms"
  [[ -e "$work/f.h5" ]] && fail "f.h5 written by a failed run"
  ;;

version)
  # (f) `raceway --version` prints "raceway VERSION (commit ...)" with CMake's project version, exit 0.
  [[ -n "$version" ]] || { echo "the version case needs VERSION (4th argument)" >&2; exit 2; }
  run --version
  [[ $rc -eq 0 ]] || fail "exit code $rc, expected 0"
  line=$(head -n 1 "$work/out")
  pattern='^raceway ([^ ]+) \(commit ([^ )]+)\)$'
  [[ "$line" =~ $pattern ]] || fail "stdout '$line' is not 'raceway VERSION (commit ID)'"
  [[ "${BASH_REMATCH[1]:-}" == "$version" ]] || fail "version '${BASH_REMATCH[1]:-}', CMake says '$version'"
  # The same version in a run's output file (root attributes raceway_version, raceway_commit).
  if command -v h5dump >/dev/null; then
    sed 's/^end_time *=.*/end_time = "2 ms"/' "$source_dir/jobs/scenes/default.toml" >"$work/short.toml"
    run run "$work/short.toml" -o "$work/v.h5"
    [[ $rc -eq 0 ]] || { fail "run: exit code $rc"; cat "$work/err" >&2; }
    h5dump -a /raceway_version "$work/v.h5" >"$work/dump" 2>&1 || fail "no raceway_version attribute"
    grep -qF "\"$version\"" "$work/dump" || fail "raceway_version is not \"$version\""
    h5dump -a /raceway_commit "$work/v.h5" >/dev/null 2>&1 || fail "no raceway_commit attribute"
  else
    fail "h5dump not found (apt-get install hdf5-tools)"
  fi
  ;;

*)
  echo "unknown case '$case_name'" >&2
  exit 2
  ;;
esac

if [[ $failures -gt 0 ]]; then
  echo "$case_name: $failures failure(s)" >&2
  exit 1
fi
echo "$case_name: passed"
