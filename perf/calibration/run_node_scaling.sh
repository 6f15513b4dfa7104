#!/usr/bin/env bash
# Scaling measured on one many-core node: what the replay model (perf/calibration/replay_model.py)
# predicts beyond two ranks, timed. Prepared to run from the bundle (scripts/bundle.sh) on a
# machine that has no raceway installed; nothing has been measured with it yet.
#
#   perf/calibration/run_node_scaling.sh BUNDLE_DIR OUT_DIR
#
# BUNDLE_DIR: an unpacked bundle (raceway-bundle/, with bin/mpirun and bin/raceway; bin/pingpong
#   when the bundle was made from a build with perf/bench). OUT_DIR: new or empty; everything lands
#   there, to be carried back:
#   node.txt                the machine: lscpu, the NUMA layout, the kernel, the load, the bundle's version
#   pingpong_near.txt       MPI latency and bandwidth between ranks on neighbouring cores
#   pingpong_far.txt        the same between ranks on different sockets (--map-by socket)
#   runs.tsv                scene, ranks, run, wall seconds (the run summary's wall_time_s),
#                           CVODE steps and rhs (they must be the same at every rank count), exit code
#   <scene>_np<P>_r<R>.{json,log}   each run's summary and log
#   <scene>_np1.h5          the least disturbed one-rank run with --scheduler-log: the recording the
#                           replay model predicts from (copy it back and run replay_model.py on it)
#   summary.txt             per scene and rank count: the median wall time, speed-up and efficiency
#                           against the median one-rank time, min-max of the runs
# Scenes: SCENES (default: the heavy traction scene jobs/scenes/6309_R3_fine_traction.toml of this
# repository; add a heavy roller scene there when one exists), each shortened to END_TIME
# (default "20 ms": one revolution, about 5 s at one rank on a current core, so 5 rank counts x
# RUNS=3 runs take about a minute). RANKS (default "1 2 4 8 16"). The runs go round-robin over the
# rank counts (1 2 4 8 16 1 2 4 ...), so a drift of the machine spreads over all of them; each is
# bound to cores (--bind-to core) with the output on the run's thread (--output-thread off).
#
# Back home (a machine with h5py):
#   /usr/bin/python3 perf/calibration/replay_model.py OUT_DIR/6309_R3_fine_traction_np1.h5 \
#       --latency-us L --bandwidth-gbs B --measured-np2 S2   # L, B: pingpong_near.txt's 8 B and 8 KiB rows
# and set its predictions beside summary.txt in perf/calibration/results/ (the model's error at each
# count); where they differ, correct the model and restate README's parallel claims from the
# measurements.
set -uo pipefail
bundle=$(cd "${1:?bundle folder (raceway-bundle/)}" && pwd) || exit 2
out=${2:?output folder}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
[[ -x $bundle/bin/mpirun && -x $bundle/bin/raceway ]] || { echo "$bundle: no bin/mpirun, bin/raceway (scripts/bundle.sh)" >&2; exit 2; }
if [[ -e $out && -n $(ls -A "$out" 2>/dev/null) ]]; then echo "$out: not empty (results are never overwritten)" >&2; exit 2; fi
mkdir -p "$out" && out=$(cd "$out" && pwd)
runs=${RUNS:-3}
read -r -a ranks <<<"${RANKS:-1 2 4 8 16}"
read -r -a scenes <<<"${SCENES:-$root/jobs/scenes/6309_R3_fine_traction.toml}"
end_time=${END_TIME:-20 ms}
# As every timing of perf/ was made (a container refuses Open MPI's single-copy transfers);
# OMPI_MCA_btl_vader_single_copy_mechanism=cma in the environment times with them.
export OMPI_MCA_btl_vader_single_copy_mechanism=${OMPI_MCA_btl_vader_single_copy_mechanism:-none}
mpirun=("$bundle/bin/mpirun" --bind-to core)
[[ $(id -u) -eq 0 ]] && mpirun+=(--allow-run-as-root)
cores=$(nproc)

{
  echo "# $(date -u +%Y-%m-%dT%H:%M:%SZ) $(uname -srm), $cores cores online"
  echo "# load: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "# bundle: $(head -1 "$bundle/VERSION" 2>/dev/null)"
  lscpu 2>/dev/null
  command -v numactl >/dev/null && numactl --hardware
} >"$out/node.txt" 2>&1
for p in "${ranks[@]}"; do
  [[ $p -le $cores ]] || echo "warning: $p ranks on $cores cores (oversubscribed: not a timing)" | tee -a "$out/node.txt"
done

if [[ -x $bundle/bin/pingpong ]]; then
  { echo "# $(date -u +%FT%TZ) near (cores 0, 1); load $(cut -d' ' -f1-3 /proc/loadavg)"
    "${mpirun[@]}" -np 2 "$bundle/bin/pingpong"; } >"$out/pingpong_near.txt" 2>&1
  { echo "# $(date -u +%FT%TZ) far (--map-by socket); load $(cut -d' ' -f1-3 /proc/loadavg)"
    "$bundle/bin/mpirun" --map-by socket --bind-to core $([[ $(id -u) -eq 0 ]] && echo --allow-run-as-root) \
      -np 2 "$bundle/bin/pingpong"; } >"$out/pingpong_far.txt" 2>&1
else
  echo "no bin/pingpong in the bundle (build perf/bench before scripts/bundle.sh): no network measured" |
    tee "$out/pingpong_near.txt"
fi

json_field() { sed -n "s/.*\"$2\": *\\([0-9.eE+-]*\\).*/\\1/p" "$1" | head -1; }
printf 'scene\tranks\trun\twall_s\tsteps\trhs\texit\n' >"$out/runs.tsv"
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .toml)
  sed -e "s/^end_time = .*/end_time = \"$end_time\"/" "$scene" >"$out/$name.toml"
  best=""
  for r in $(seq "$runs"); do
    for p in "${ranks[@]}"; do
      stem="$out/${name}_np${p}_r$r"
      extra=()
      [[ $p -eq 1 ]] && extra=(--scheduler-log -o "$stem.h5") || extra=(-o "$stem.h5")
      "${mpirun[@]}" -np "$p" "$bundle/bin/raceway" run "$out/$name.toml" "${extra[@]}" \
        --summary-json "$stem.json" --output-thread off >"$stem.log" 2>&1
      rc=$?
      wall=$(json_field "$stem.json" wall_time_s 2>/dev/null)
      printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$p" "$r" "${wall:-NA}" "$(json_field "$stem.json" steps 2>/dev/null)" \
        "$(json_field "$stem.json" rhs_evaluations 2>/dev/null)" "$rc" >>"$out/runs.tsv"
      echo "$name np $p run $r: ${wall:-no summary} s (exit $rc, load $(cut -d' ' -f1 /proc/loadavg))"
      if [[ $p -eq 1 && -n $wall ]] && { [[ -z $best ]] || awk -v a="$wall" -v b="$best" 'BEGIN {exit !(a < b)}'; }; then
        best=$wall
        mv "$stem.h5" "$out/${name}_np1.h5"
      else
        rm -f "$stem.h5"
      fi
    done
  done
done

# Medians, speed-up and efficiency against the one-rank median.
awk -F'\t' 'NR > 1 && $4 != "NA" && $7 == 0 { key = $1 "\t" $2; n[key]++; w[key, n[key]] = $4; scenes[$1] = 1; p[$2] = 1 }
  function median(key,   i, j, t, a, m) {
    m = n[key]; for (i = 1; i <= m; i++) a[i] = w[key, i]
    for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
    lo[key] = a[1]; hi[key] = a[m]
    return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2 }
  END {
    print "# scene  ranks  runs  median_wall_s  min-max  speedup  efficiency (against the median one-rank wall time)"
    for (s in scenes) {
      base = median(s "\t1")
      for (q = 1; q <= 1024; q++) if ((s "\t" q) in n) {
        m = median(s "\t" q)
        printf "%s  %3d  %d  %.3f  %.3f-%.3f  %.3f  %.3f\n", s, q, n[s "\t" q], m, lo[s "\t" q], hi[s "\t" q], base / m, base / m / q
      }
    } }' "$out/runs.tsv" | tee "$out/summary.txt"
failed=$(awk -F'\t' 'NR > 1 && $7 != 0' "$out/runs.tsv" | wc -l)
steps=$(awk -F'\t' 'NR > 1 && $7 == 0 {print $1, $5, $6}' "$out/runs.tsv" | sort -u | awk '{print $1}' | uniq -d)
[[ -z $steps ]] || echo "warning: CVODE counters differ between runs of: $steps (results must not depend on the rank count)" | tee -a "$out/summary.txt"
echo "$failed failed run(s); results in $out"
[[ $failed -eq 0 ]]
