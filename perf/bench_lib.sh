# Shell helpers of the perf/ benchmark scripts (sourced by run_parallel_benchmarks.sh,
# run_scaling_benchmarks.sh and the spatial roller timings), and the MPI environment they all run
# under.
#
# mpirun as root (this machine); Open MPI's shared-memory single-copy transfers (CMA) need ptrace
# rights that containers and some VMs lack, plain copies work everywhere; waiting ranks yield the
# core (sched_yield) instead of spinning: on a shared 2-core machine a spinning rank otherwise steals
# the time slice its partner needs (measured here: np=2 3.4x slower than np=1 next to two busy
# neighbours without it, 1.3x with it). Costs nothing when the cores are free. MPI_YIELD=0 measures
# plain busy polling.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_mpi_yield_when_idle=${MPI_YIELD:-1}
header() { echo "# $(date -u +%FT%TZ) $(uname -srm), $(nproc) cores,$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"; }
load() { uptime | sed 's/.*load average: /load /'; }
# A run summary's wall time (--summary-json FILE).
wall() { "${py:-/usr/bin/python3}" -c "import json,sys; print(json.load(open(sys.argv[1]))['wall_time_s'])" "$1"; }
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
# This machine's MPI latency and bandwidth by message size (build/perf/bench/pingpong under ROOT), the
# replay model's "here" network, as pingpong.txt holds them: measure_network ROOT > pingpong.txt
measure_network() { { header; echo "# $(load)"; mpirun -np 2 "$1/build/perf/bench/pingpong"; } 2>&1; }
