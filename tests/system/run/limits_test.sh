#!/usr/bin/env bash
# Limits that hold, one case per ctest:
#
#   limits_test.sh CASE RACEWAY MPIEXEC SOURCE_DIR
#
#   max_size_np1, max_size_np2: the default scene with [output] max_size set 3 % above what
#     `raceway check` estimates and the scheduler's log on (np 1: --scheduler-log; np 2: always),
#     every evaluation sampled: the whole file, /scheduler included, stays within max_size; the
#     log's arrays were thinned to fit and /scheduler says so (left_out_for_max_size), while the
#     series are complete. With max_size 10 % below the estimate the run is refused (exit 2).
#   spin_up_warning: the default scene driven from 0 to 900,000 r/min in 1 us: the run ends (exit
#     0) with a warning naming the cage slip as its last lines and in the summary's "warnings"; the
#     same scene at its own speed has no warning.
set -u
case_name=${1:?case}
raceway=${2:?raceway}
mpiexec=${3:?mpiexec}
source_dir=${4:?source dir}
source "$source_dir/tests/system/test_lib.sh"
python=/usr/bin/python3

# estimate SCENE: the total bytes `raceway check` estimates (series + names, attributes, indexes).
estimate() {
  "$raceway" check "$1" 2>/dev/null | "$python" -c '
import re, sys
units = {"B": 1, "kB": 1e3, "MB": 1e6, "GB": 1e9, "TB": 1e12}
for line in sys.stdin:
    m = re.match(r"output: \d+ samples x \d+ values = ([\d.e+]+) (\w+) \+ ([\d.e+]+) (\w+) of names", line)
    if m:
        print(int(float(m[1]) * units[m[2]] + float(m[3]) * units[m[4]]))
'
}

max_size() {
  local np=$1
  sed -e 's/^end_time = .*/end_time = "5 ms"/' "$source_dir/jobs/scenes/default.toml" >"$work/base.toml"
  local total
  total=$(estimate "$work/base.toml")
  [[ "$total" =~ ^[0-9]+$ ]] || { fail "no estimate from raceway check: '$total'"; return; }
  local limit=$((total * 103 / 100))
  sed "s/^\[output\]/[output]\nmax_size = \"$limit B\"/" "$work/base.toml" >"$work/limit.toml"
  grep -q "^max_size = \"$limit B\"" "$work/limit.toml" || printf '[output]\nmax_size = "%s B"\n' "$limit" >>"$work/limit.toml"
  local command=("$raceway" run "$work/limit.toml" -o "$work/l.h5" --schedule-sample-every 1)
  [[ $np -eq 1 ]] && command+=(--scheduler-log)
  [[ $np -gt 1 ]] && command=("$mpiexec" --oversubscribe -np "$np" "${command[@]}")
  "${command[@]}" >"$work/log" 2>&1 || { fail "np $np: the run failed: $(tail -3 "$work/log")"; return; }
  local size
  size=$(stat -c %s "$work/l.h5")
  echo "np $np: estimate $total B, max_size $limit B, file $size B"
  [[ $size -le $limit ]] || fail "np $np: the file ($size B) is larger than max_size ($limit B)"
  local verdict
  verdict=$("$python" - "$work/l.h5" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    s = f["scheduler"]
    left = s.attrs.get("left_out_for_max_size", "")
    samples = s["imbalance"].shape[0] if "imbalance" in s else 0
    print("thinned" if left else "whole", s.attrs["sample_every"], samples, f["time"].shape[0], "|", left)
PY
)
  echo "np $np: /scheduler $verdict"
  [[ $verdict == thinned* ]] || fail "np $np: /scheduler was not thinned although its arrays could not fit: $verdict"
  local samples
  samples=$("$raceway" check "$work/limit.toml" 2>/dev/null | sed -n 's/^output: \([0-9]*\) samples.*/\1/p')
  [[ $(awk '{print $4}' <<<"$verdict") == "$samples" ]] || fail "np $np: the series are not complete ($samples): $verdict"
  # Below the estimate: refused before any work.
  sed -i "s/^max_size = .*/max_size = \"$((total * 90 / 100)) B\"/" "$work/limit.toml"
  "$raceway" run "$work/limit.toml" -o "$work/r.h5" >"$work/log" 2>&1
  local rc=$?
  [[ $rc -eq 2 ]] || fail "np $np: max_size below the estimate: exit $rc, expected 2"
  grep -q "more than \[output\] max_size" "$work/log" || fail "np $np: no reason given: $(tail -2 "$work/log")"
  [[ -e "$work/r.h5" || -e "$work/r.h5.partial" ]] && fail "np $np: a refused run wrote a file"
}

spin_up_warning() {
  sed -e 's/^end_time = .*/end_time = "2 ms"/' "$source_dir/jobs/scenes/default.toml" >"$work/spin.toml"
  "$raceway" run "$work/spin.toml" -o "$work/n.h5" --summary-json "$work/n.json" >"$work/log" 2>&1 ||
    fail "the scene at its own speed failed: $(tail -3 "$work/log")"
  grep -q "warning: the cage slips" "$work/log" && fail "a warning for the scene at its own speed"
  "$raceway" run "$work/spin.toml" -o "$work/s.h5" --summary-json "$work/s.json" \
    --set 'inner_ring.speed={ time = ["0 s", "1 us"], value = ["0 rpm", "900000 rpm"] }' >"$work/log" 2>&1
  local rc=$?
  [[ $rc -eq 0 ]] || { fail "the spin-up run: exit $rc: $(tail -3 "$work/log")"; return; }
  tail -1 "$work/log" | grep -q "^\[raceway\] warning: the cage slips [0-9.]* % against its epicyclic speed" ||
    fail "the run's last line is not the warning: $(tail -2 "$work/log")"
  local verdict
  verdict=$("$python" - "$work/s.json" "$work/n.json" "$work/s.h5" <<'PY'
import json, sys, h5py
s, n = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
with h5py.File(sys.argv[3], "r") as f:
    stored = json.loads(f.attrs["summary_json"])
print(sorted(s["warnings"]), n["warnings"] == {}, stored["warnings"] == s["warnings"], round(100 * s["cage_slip"], 1))
PY
)
  echo "spin-up to 900000 rpm in 1 us: warnings, none at the scene's own speed, the file's the same, slip %: $verdict"
  [[ $verdict == "['cage_slip'] True True "* ]] || fail "the summary's warnings: $verdict"
}

case "$case_name" in
max_size_np1) max_size 1 ;;
max_size_np2) max_size 2 ;;
spin_up_warning) spin_up_warning ;;
*)
  echo "unknown case '$case_name'" >&2
  exit 2
  ;;
esac
finish
