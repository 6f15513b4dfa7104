#!/usr/bin/env bash
# Instructions per revolution by component (callgrind: independent of the machine's load), for one or
# more raceway executables:
#
#   [SCENE=jobs/scenes/6309_R3.toml] [FIRST=0.02] [SECOND=0.04] perf/studies/revolution_instructions.sh RACEWAY...
#
# Runs each executable twice under callgrind, with scene.end_time = FIRST and = SECOND seconds (the
# scene's own solver and output settings), and prints the difference of the two runs: what the span
# FIRST..SECOND costs without the start-up, seating and file set-up both runs share. Give a span of
# one inner-ring revolution (6309 R3: 20 ms; QJ215: 60 ms; seed 002: 25 ms) to read instructions per
# revolution. Components are inclusive costs of every thread (the run's, the output thread, the chunk
# compressor): the integrator's right-hand sides, Jacobians, linear setups (less the Jacobians) and
# solves, CVODE's own work (the rest of the integrator), the output thread's samples (a right-hand
# side for the diagnostics and the rows) and the compressor's shuffle and deflate.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
scene=${SCENE:-$root/jobs/scenes/6309_R3.toml}
first=${FIRST:-0.02}
second=${SECOND:-0.04}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
[[ $# -gt 0 ]] || { echo "usage: $0 RACEWAY..." >&2; exit 2; }
echo "# $(basename "$scene"), end_time $first s against $second s; instructions (millions) of the difference"
printf "%-48s" "build"
printf " %9s" total integrator rhs jacobian setup solve cvode outthread compress steps rhs_n
echo
for bin in "$@"; do
  for end in "$first" "$second"; do
    valgrind --tool=callgrind --callgrind-out-file="$work/$end.out" "$bin" run "$scene" \
      --set scene.end_time="$end s" -o "$work/$end.h5" --summary-json "$work/$end.json" >/dev/null 2>&1
    callgrind_annotate --inclusive=yes --threshold=100 "$work/$end.out" >"$work/$end.txt" 2>/dev/null
  done
  /usr/bin/python3 - "$work" "$first" "$second" "$bin" <<'PY'
import json, re, sys
work, first, second, binary = sys.argv[1:]
# Inclusive costs by the function's name (the first line that holds it).
names = {
    "total": "PROGRAM TOTALS",
    "integrator": ":raceway::numerics::Integrator::advance_to(",
    "rhs": ":raceway::numerics::Integrator::Impl::rhs(",
    "jacobian": ":raceway::numerics::Integrator::Impl::jacobian(",
    "setup": ":cvLsSetup ",
    "solve": ":cvLsSolve ",
    "outthread": ":raceway::run::OutputThread::loop(",
    "compress": ":raceway::h5::ChunkCompressor::work(",
}
def costs(end):
    text = open(f"{work}/{end}.txt").read().splitlines()
    out = {}
    for key, name in names.items():
        for line in text:
            if name in line:
                out[key] = int(re.match(r"\s*([\d,]+)", line).group(1).replace(",", ""))
                break
        else:
            out[key] = 0
    return out
a, b = costs(first), costs(second)
d = {k: (b[k] - a[k]) / 1e6 for k in names}
d["setup"] -= d["jacobian"]  # the linear setups less the Jacobians they call
d["cvode"] = d["integrator"] - d["rhs"] - d["jacobian"] - d["setup"] - d["solve"]
ja, jb = (json.load(open(f"{work}/{e}.json")) for e in (first, second))
cols = ["total", "integrator", "rhs", "jacobian", "setup", "solve", "cvode", "outthread", "compress"]
row = f"{binary[-48:]:48s}" + "".join(f" {d[c]:9.1f}" for c in cols)
row += f" {jb['steps'] - ja['steps']:9d} {jb['rhs_evaluations'] - ja['rhs_evaluations']:9d}"
print(row)
PY
done
