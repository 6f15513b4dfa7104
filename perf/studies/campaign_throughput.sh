#!/bin/bash
# Throughput of `raceway campaign` on this machine: the same 8 scenes (perf/studies/campaign_throughput.toml)
# in 1 group of 1 rank (one after another) and in 2 groups of 1 rank, wall time and CPU time of
# each, and the dispatcher's accounting (DIR/campaign_status_0.json: the groups' waiting for the
# dispatcher and their idle time at the end). Appends to perf/studies/results/campaign_throughput.md.
#   perf/studies/campaign_throughput.sh build/raceway
set -eu
raceway=$(realpath "$1")
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
out="$here/results/campaign_throughput.md"
{
  echo
  echo "## $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo
  echo "| groups x ranks | wall s | CPU s (user+sys, all ranks) | scenes' summed wall s | waiting for the dispatcher s | idle at the end s |"
  echo "|---|---|---|---|---|---|"
} >> "$out"
for np in 1 2; do
  /usr/bin/time -f "%e %U %S" -o "$work/time_$np" mpirun -np $np "$raceway" campaign "$here/campaign_throughput.toml" \
    -o "$work/c$np" > "$work/log_$np" 2>&1
  read -r wall user sys < "$work/time_$np"
  /usr/bin/python3 - "$work/c$np/campaign_status_0.json" "$np" "$wall" "$user" "$sys" >> "$out" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
busy = sum(v["wall_time_s"] for v in s["scenes_this_call"].values())
np_, wall, user, system = sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
print(f"| {np_} x 1 | {wall:.1f} | {user + system:.1f} | {busy:.1f} | {s['group_waiting_for_dispatch_s']:.3f} | "
      f"{s['group_idle_at_end_s']:.1f} |")
PY
done
w1=$(cut -d' ' -f1 "$work/time_1"); w2=$(cut -d' ' -f1 "$work/time_2")
echo "" >> "$out"
echo "Throughput of 2 groups against 1: $(echo "scale=2; $w1 / $w2" | bc)x (wall time, same 8 scenes, table and plots included)." >> "$out"
tail -8 "$out"
