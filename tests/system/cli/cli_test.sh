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

source "$source_dir/tests/system/test_lib.sh"

# Runs raceway with stdout and stderr captured in $work/out and $work/err; sets $rc.
run() {
  "$raceway" "$@" >"$work/out" 2>"$work/err"
  rc=$?
}

case "$case_name" in

bad_scenes)
  # (a) every broken scene: exit code 2, and stderr names the file and the offending key (the key
  # is given by the scene's "# key:" line; empty for TOML syntax errors). Four scenes at a time:
  # a refusal costs little CPU, most of its wall time is MPI's start-up.
  check_bad_scene() {  # SCENE DIR: a failure's reason in DIR/failed
    local scene=$1 dir=$2 name key rc
    name=$(basename "$scene")
    key=$(sed -n 's/^# key: *//p' "$scene" | head -n 1)
    mkdir -p "$dir"
    "$raceway" run "$scene" -o "$dir/out.h5" >"$dir/out" 2>"$dir/err"
    rc=$?
    local why=""
    if [[ $rc -ne 2 ]]; then why="exit code $rc, expected 2"
    elif ! grep -qF "$name" "$dir/err"; then
      why="stderr does not name the file$(grep -qF "$name" "$dir/out" && echo ' (the message went to stdout)')"
    elif [[ -n "$key" ]] && ! grep -qF "$key" "$dir/err"; then
      why="stderr does not name the key '$key'$(grep -qF "$key" "$dir/out" && echo ' (the message went to stdout)')"
    elif [[ -e "$dir/out.h5" || -e "$dir/out.h5.partial" ]]; then why="a bad scene created an output file"
    fi
    [[ -z $why ]] || echo "$name: $why" >"$dir/failed"
  }
  count=0
  for scene in "$source_dir"/tests/io/scene/bad_scenes/*.toml; do
    count=$((count + 1))
    (( count > 4 )) && wait -n
    check_bad_scene "$scene" "$work/bad_$count" &
  done
  wait
  [[ $count -ge 20 ]] || fail "only $count bad scenes found in $source_dir/tests/io/scene/bad_scenes"
  failed=$(cat "$work"/bad_*/failed 2>/dev/null)
  [[ -z $failed ]] || fail "$failed"
  ;;

keep_existing_output)
  # (b) a failing run leaves an existing output file byte for byte as it was.
  head -c 4096 /dev/urandom >"$work/OUT.h5"
  cp "$work/OUT.h5" "$work/before.h5"
  run run "$source_dir/tests/io/scene/bad_scenes/unknown_key.toml" -o "$work/OUT.h5"
  [[ $rc -ne 0 ]] || fail "bad scene: exit code 0"
  cmp -s "$work/OUT.h5" "$work/before.h5" || fail "OUT.h5 changed after a failed run (bad scene)"
  # ... also when the failure comes during the integration (the partial output is kept beside it).
  sed 's/^\[solver\]/[solver]\nmax_steps = 50/' "$source_dir/jobs/scenes/default.toml" >"$work/fails.toml"
  run run "$work/fails.toml" -o "$work/OUT.h5"
  [[ $rc -eq 3 ]] || fail "integration failure: exit code $rc, expected 3"
  cmp -s "$work/OUT.h5" "$work/before.h5" || fail "OUT.h5 changed after a failed run (integration failure)"
  [[ -e "$work/OUT.h5.partial" ]] || fail "no OUT.h5.partial after an integration failure"
  ;;

output_thread)
  # (k) --output-thread: the log names the decision; on and off give the same file; a bad value is
  # refused. Under mpirun: the case output_thread_bound.
  sed 's/^end_time = .*/end_time = "20 ms"/' "$source_dir/jobs/scenes/default.toml" >"$work/s.toml"
  for mode in on off; do
    run run "$work/s.toml" -o "$work/$mode.h5" --output-thread "$mode"
    [[ $rc -eq 0 ]] || fail "--output-thread $mode: exit code $rc"
    cat "$work/out" "$work/err" | grep -q "output thread $mode (--output-thread $mode" ||
      fail "--output-thread $mode: the log does not say 'output thread $mode'"
  done
  /usr/bin/python3 "$source_dir/tests/system/parallel/compare_outputs.py" "$work/on.h5" "$work/off.h5" >"$work/cmp" 2>&1 ||
    fail "files with and without the output thread differ: $(tail -3 "$work/cmp")"
  run run "$work/s.toml" -o "$work/bad.h5" --output-thread sometimes
  [[ $rc -ne 0 && ! -e "$work/bad.h5" && ! -e "$work/bad.h5.partial" ]] || fail "--output-thread sometimes: exit $rc"
  ;;

output_thread_bound)
  # (k2) auto under mpirun, which binds each rank to a core: rank 0's output thread goes to a core
  # of the node that no rank is bound to, if there is one, bound there alone (its affinity read back
  # in the log), with the same file as without the thread; with no such core it stays off.
  sed 's/^end_time = .*/end_time = "20 ms"/' "$source_dir/jobs/scenes/default.toml" >"$work/s.toml"
  run run "$work/s.toml" -o "$work/off.h5" --output-thread off
  [[ $rc -eq 0 ]] || fail "--output-thread off: exit code $rc"
  for np in 1 2; do
    mpirun -np $np "$raceway" run "$work/s.toml" -o "$work/np$np.h5" >"$work/out" 2>"$work/err"
    [[ $? -eq 0 ]] || fail "np $np: exit code not 0: $(tail -3 "$work/err")"
    cat "$work/out" "$work/err" >"$work/log$np"
    line=$(grep -o "output thread [a-z]* (auto: [0-9]* core(s) on this node, $np rank(s) on it, this rank may use [0-9]*[^)]*)" "$work/log$np")
    [[ -n "$line" ]] || fail "np $np: the log does not state the auto decision: $(grep 'output thread' "$work/log$np")"
    read -r decided cores mine < <(sed -E 's/output thread ([a-z]+) \(auto: ([0-9]+) core.* may use ([0-9]+).*/\1 \2 \3/' <<<"$line")
    if [[ $mine -ge $cores ]]; then  # mpirun did not bind (a site setting): the rule without binding
      expected=off
      [[ $mine -gt 1 && $cores -gt $np ]] && expected=on
      [[ $decided == "$expected" ]] || fail "np $np, not bound: '$line' (expected $expected)"
      continue
    fi
    if [[ $cores -gt $((np * mine)) ]]; then  # a core no rank is bound to: the thread is bound there
      core=$(sed -nE 's/.*; core ([0-9]+) is free of ranks: the thread is bound there\)$/\1/p' <<<"$line")
      [[ $decided == on && -n "$core" ]] || fail "np $np: a core is free, but: '$line'"
      grep -q "output thread bound to core $core (its affinity read back: $core)$" "$work/log$np" ||
        fail "np $np: no 'output thread bound to core $core (its affinity read back: $core)' in the log"
    else
      [[ $decided == off && $line == *"every core the job may use here has a rank bound to it"* ]] ||
        fail "np $np: no core is free, but: '$line'"
      grep -q "output thread bound" "$work/log$np" && fail "np $np: a thread was bound with no free core"
    fi
    /usr/bin/python3 "$source_dir/tests/system/parallel/compare_outputs.py" "$work/np$np.h5" "$work/off.h5" >"$work/cmp" 2>&1 ||
      fail "np $np: the file differs from --output-thread off: $(tail -3 "$work/cmp")"
  done
  # On this test's 2-core machine: np 1 binds the thread to the other core, np 2 leaves it off.
  if [[ $(nproc) -eq 2 ]]; then
    grep -q "output thread bound to core" "$work/log1" || fail "np 1 on 2 cores: the output thread was not bound"
    grep -q "output thread off (auto" "$work/log2" || fail "np 2 on 2 cores: the output thread is not off"
  fi
  ;;

output_share_note)
  # (k3) a run whose output takes more than 5 % of its wall time (6309 R3 samples every 20 us; the
  # output on the run's thread) ends with one info line giving the share, as in its summary, and
  # naming the two levers; with few samples and no segment diagnostics it does not; under mpirun
  # only rank 0 says it.
  sed 's/^end_time = .*/end_time = "20 ms"/' "$source_dir/jobs/scenes/6309_R3.toml" >"$work/r3.toml"
  run run "$work/r3.toml" -o "$work/r3.h5" --output-thread off --summary-json "$work/r3.json"
  [[ $rc -eq 0 ]] || fail "6309 R3, 20 ms: exit code $rc"
  cat "$work/out" "$work/err" >"$work/all"
  last=$(grep '^\[raceway\]' "$work/all" | tail -1)
  share=$(sed -nE 's/^\[raceway\] the output took ([0-9.]+) % of the run .*/\1/p' <<<"$last")
  [[ -n "$share" ]] || fail "the run does not end with the output's share: '$last'"
  [[ $last == *"[scene] output_interval"* && $last == *"[output] segments = false"* ]] ||
    fail "the line does not name output_interval and segments = false: '$last'"
  expected=$(/usr/bin/python3 -c "import json; j = json.load(open('$work/r3.json')); print(f\"{100 * j['output_time_s'] / j['wall_time_s']:.1f}\")")
  [[ $share == "$expected" ]] || fail "the line says $share %, the summary $expected %"
  [[ $(grep -c "the output took" "$work/all") -eq 1 ]] || fail "the share is said more than once"
  run run "$work/r3.toml" -o "$work/few.h5" --output-thread off --set scene.output_interval="2 ms" --set output.segments=false \
    --summary-json "$work/few.json"
  [[ $rc -eq 0 ]] || fail "11 samples without segments: exit code $rc"
  small=$(/usr/bin/python3 -c "import json; j = json.load(open('$work/few.json')); print(int(j['output_time_s'] <= 0.05 * j['wall_time_s']))")
  if [[ $small -eq 1 ]]; then
    grep -q "the output took" "$work/out" "$work/err" && fail "a share of 5 % or less is mentioned"
  else
    grep -q "the output took" "$work/out" "$work/err" || fail "11 samples: above 5 % but not mentioned"
  fi
  mpirun -np 2 "$raceway" run "$work/r3.toml" -o "$work/np2.h5" --summary-json "$work/np2.json" >"$work/out" 2>"$work/err"
  [[ $? -eq 0 ]] || fail "np 2: exit code not 0"
  said=$(cat "$work/out" "$work/err" | grep -c "the output took")
  big=$(/usr/bin/python3 -c "import json; j = json.load(open('$work/np2.json')); print(int(j['output_time_s'] > 0.05 * j['wall_time_s']))")
  [[ $said -eq $big ]] || fail "np 2: the share said $said time(s), expected $big (rank 0 only)"
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

output_size)
  # (g) `raceway check` prints the output's size, from the writer's own tables: the file a run
  # writes has exactly that many samples and values per sample (its series, /scheduler aside).
  sed 's/^end_time *=.*/end_time = "2 ms"/' "$source_dir/jobs/scenes/default.toml" >"$work/short.toml"
  run check "$work/short.toml"
  [[ $rc -eq 0 ]] || { fail "check: exit code $rc"; cat "$work/err" >&2; }
  pattern='^output: ([0-9]+) samples x ([0-9]+) values = .* \+ .* of names, attributes and indexes \(limit 4 GB, \[output\] max_size\)$'
  line=$(grep '^output: ' "$work/out")
  [[ "$line" =~ $pattern ]] || fail "check prints no output estimate: '$line'"
  samples=${BASH_REMATCH[1]:-0} values=${BASH_REMATCH[2]:-0}
  run run "$work/short.toml" -o "$work/s.h5"
  [[ $rc -eq 0 ]] || fail "run: exit code $rc"
  /usr/bin/python3 - "$work/s.h5" "$samples" "$values" <<'PY' || fail "the estimate differs from the file"
import sys, h5py
path, samples, values = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
with h5py.File(path, "r") as f:
    t = f["time"].shape[0]
    found = []
    f.visititems(lambda name, o: found.append(o.size // t) if isinstance(o, h5py.Dataset) and
                 not name.startswith("scheduler") and o.maxshape and o.maxshape[0] is None else None)
print(f"file: {t} samples x {sum(found)} values; estimate: {samples} x {values}")
sys.exit(0 if (t, sum(found)) == (samples, values) else 1)
PY
  # Over the limit: refused at check and at run (exit 2, no file), naming the key and the numbers.
  sed 's/^output_interval *=.*/output_interval = "1 us"/; s/^end_time *=.*/end_time = "20 s"/' \
    "$source_dir/jobs/scenes/default.toml" >"$work/huge.toml"
  for command in check run; do
    if [[ $command == run ]]; then run run "$work/huge.toml" -o "$work/huge.h5"; else run check "$work/huge.toml"; fi
    [[ $rc -eq 2 ]] || fail "$command of a 61 GB output: exit code $rc, expected 2"
    grep -qE "huge.toml:[0-9]+: key 'scene.output_interval': the output would be 6[01].[0-9] GB \(2e\+07 samples.*x 378 values x 8 bytes, \+ [0-9.]+ [kMG]?B of names, attributes and indexes\), more than \[output\] max_size = 4 GB" "$work/err" ||
      fail "$command: no size, key and limit in: $(cat "$work/err")"
  done
  [[ -e "$work/huge.h5" || -e "$work/huge.h5.partial" ]] && fail "a refused run created an output file"
  # The limit is the scene's: 100 kB refuses the default scene's 585 kB, 1 MB lets it run.
  sed 's/^segments = true.*/segments = true\nmax_size = "100 kB"/' "$source_dir/jobs/scenes/default.toml" >"$work/small.toml"
  run check "$work/small.toml"
  [[ $rc -eq 2 ]] && grep -q "more than \[output\] max_size = 100 kB" "$work/err" || fail "max_size = 100 kB: exit $rc"
  sed -i 's/max_size = "100 kB"/max_size = "1 MB"/' "$work/small.toml"
  run check "$work/small.toml"
  [[ $rc -eq 0 ]] || fail "max_size = 1 MB: exit $rc: $(cat "$work/err")"
  ;;

wall_time)
  # (h) [solver] max_wall_time ends a run that would take longer with a diagnosis (exit 3), soon.
  sed 's/^\[solver\]/[solver]\nmax_wall_time = "0.3 s"/; s/^end_time *=.*/end_time = "10 s"/; s/^output_interval *=.*/output_interval = "10 ms"/' \
    "$source_dir/jobs/scenes/default.toml" >"$work/slow.toml"
  start=$(date +%s%N)
  run run "$work/slow.toml" -o "$work/w.h5"
  elapsed_ms=$((($(date +%s%N) - start) / 1000000))
  [[ $rc -eq 3 ]] || fail "exit code $rc, expected 3"
  grep -qE "integration failed at t = [0-9.e-]+ s( \([^)]*\))?: wall-time budget exhausted \(0\.3[0-9]* s of \[solver\] max_wall_time = 0\.3 s\)" "$work/err" ||
    fail "no wall-time diagnosis: $(tail -2 "$work/err")"
  echo "ended after $elapsed_ms ms"
  [[ $elapsed_ms -lt 10000 ]] || fail "took $elapsed_ms ms"
  [[ -e "$work/w.h5" ]] && fail "w.h5 written by a failed run"
  ;;

startup_keys)
  # (i) a start-up that cannot seat the bearing (1 GN on 6 mm rollers) says so with the keys
  # that set it and their lines; bad input, exit 2, no output.
  sed 's/fy = "-500 N"/fy = "-1e9 N"/' "$source_dir/jobs/scenes/default.toml" >"$work/crushed.toml"
  run run "$work/crushed.toml" -o "$work/c.h5"
  [[ $rc -eq 2 ]] || fail "exit code $rc, expected 2"
  line=$(grep -n 'fy = "-1e9 N"' "$work/crushed.toml" | cut -d: -f1)
  grep -q "crushed.toml: start-up: .*; the keys that set the start-up: .*inner_ring.load.fy (line $line)" "$work/err" ||
    fail "the start-up failure names no keys: $(cat "$work/err")"
  [[ -e "$work/c.h5" || -e "$work/c.h5.partial" ]] && fail "a failed start-up created an output file"
  ;;

bad_options)
  # (j) every bad option or argument: exit 2 and one line on stderr that names it (never CLI11's
  # own codes 105, 106, 109, an abort on a non-finite value, or a 309-digit range).
  while IFS='|' read -r args expected; do
    read -ra argv <<<"$args"
    run "${argv[@]}"
    [[ $rc -eq 2 ]] || fail "raceway $args: exit code $rc, expected 2"
    [[ $(wc -l <"$work/err") -eq 1 ]] || fail "raceway $args: not one line on stderr: $(cat "$work/err")"
    grep -qF -- "$expected" "$work/err" || fail "raceway $args: '$expected' not in: $(cat "$work/err")"
    [[ $(wc -c <"$work/err") -lt 200 ]] || fail "raceway $args: a long message: $(cat "$work/err")"
    [[ -s "$work/out" ]] && fail "raceway $args: wrote to stdout"
  done <<'CASES'
run --master-share nan|--master-share: expected a finite number >= 0, got 'nan'
run --master-share inf|--master-share: expected a finite number >= 0, got 'inf'
run --master-share -1|--master-share: expected a finite number >= 0, got '-1'
run --master-share 1e400|got '1e400'
run --master-share 2x|got '2x'
run --schedule-sample-every 0|--schedule-sample-every: expected a whole number > 0
run --schedule-sample-every 2.5|--schedule-sample-every: expected a whole number > 0
run --schedule-sample-every 1e400|--schedule-sample-every: expected a whole number > 0
run --schedule sometimes|--schedule: sometimes not in {adaptive,static}
run --method rk4|--method: rk4 not in {bdf,adams,erk,ark}
run --rank-timeout nan|--rank-timeout: expected a finite number > 0, got 'nan'
run --rank-timeout 0|--rank-timeout: expected a finite number > 0, got '0'
run --inject-failure 1|--inject-failure expects RANK:EVALUATION
run -o|--output
run --no-such-option|--no-such-option
check one.toml two.toml|two.toml
report|output_file is required
report x.h5 --bin-width nan|--bin-width: expected a finite number > 0, got 'nan'
report x.h5 --bin-width -5|--bin-width: expected a finite number > 0, got '-5'
report x.h5 --window-start inf|--window-start: expected a finite number >= 0, got 'inf'
simulate|simulate
|A subcommand is required
CASES
  # --help and --version are not errors.
  run --help
  [[ $rc -eq 0 ]] || fail "--help: exit code $rc"
  run run --help
  [[ $rc -eq 0 ]] || fail "run --help: exit code $rc"
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
