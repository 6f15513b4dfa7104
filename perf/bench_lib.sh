# Shell helpers of the perf/ benchmark scripts (sourced by run_parallel_benchmarks.sh and
# run_scaling_benchmarks.sh).
header() { echo "# $(date -u +%FT%TZ) $(uname -srm), $(nproc) cores,$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"; }
load() { uptime | sed 's/.*load average: /load /'; }
# A run summary's wall time (--summary-json FILE).
wall() { "${py:-/usr/bin/python3}" -c "import json,sys; print(json.load(open(sys.argv[1]))['wall_time_s'])" "$1"; }
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
# This machine's MPI latency and bandwidth by message size (build/perf/bench/pingpong under ROOT), the
# replay model's "here" network, as pingpong.txt holds them: measure_network ROOT > pingpong.txt
measure_network() { { header; echo "# $(load)"; mpirun -np 2 "$1/build/perf/bench/pingpong"; } 2>&1; }
