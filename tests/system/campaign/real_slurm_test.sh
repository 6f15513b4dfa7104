#!/bin/bash
# The Slurm recipes of jobs/campaigns on a real Slurm: a one-node cluster on localhost (munge,
# slurmctld, slurmd; tests/system/campaign/slurm_cluster.sh), skipped (exit 77) where Debian's slurm-wlm
# and munge are not installed or the test is not root (slurmd must be). Every wait is bounded; the daemons and the jobs' processes end with
# the test on every path (a trap, and a guard process for a test killed outright).
#   campaign: jobs/campaigns/slurm_campaign.sh submitted with the user's options (2 tasks, a time
#             limit, a partition that is not the default) runs a campaign with the default launcher
#             (srun --mpi=pmix); Slurm's SIGUSR1 to the batch script (scancel --batch) stops it with
#             checkpoints (exit 4); the job requeues itself and runs again with every option it was
#             submitted with and the environment it was submitted from (its SLURM_* variables are
#             run 1's and SLURM_RESTART_COUNT); it resumes and writes the table. Then a job whose
#             script gets SIGUSR1 at once (as Slurm sends it when --time is under the signal's lead):
#             a clean stop (exit 4, not the 138 of a death by the signal), and not requeued (the next
#             run would get it at once again).
#   array:    jobs/campaigns/slurm_array.sh submits the array of 3 scenes (with the user's options:
#             1 task, a time limit, a partition) and the aggregation step; RACEWAY_LAUNCHER="mpirun"
#             (mpirun inside the allocation); one task is killed outright (SIGKILL to every process of
#             the job, a lost node), one stopped by SIGUSR1; the aggregation step submits both again
#             (the user's options, none of its own SLURM_* variables), they resume, and the next one
#             writes the table with every scene done. Then a campaign whose launcher cannot start
#             raceway (plain srun: Open MPI ends in MPI_Init without PMIx): each scene is recorded as
#             failed once, with the launcher's exit code, nothing is submitted again, and the
#             aggregation step says why.
# Usage: real_slurm_test.sh CASE RACEWAY MPIEXEC SOURCE_DIR
set -u
case_name=$1 raceway=$(realpath "$2") source_dir=$(realpath "$4")
cluster=$source_dir/tests/system/campaign/slurm_cluster.sh
if ! why=$("$cluster" available); then
  echo "SKIP: no Slurm to test the recipes on: $why"
  exit 77
fi
source "$source_dir/tests/system/test_lib.sh"
trap '"$cluster" stop "$work/slurm"; rm -rf "$work"' EXIT
export OMPI_MCA_rmaps_base_oversubscribe=1
python=/usr/bin/python3
small=$source_dir/tests/system/campaign/slurm_campaign.toml

# A job of this cluster submitted from a Slurm job would otherwise take that job's variables.
# shellcheck disable=SC2046
unset $(compgen -v SLURM_) $(compgen -v SBATCH_) $(compgen -v SRUN_) 2> /dev/null
"$cluster" start "$work/slurm" $$ > "$work/cluster.log" 2>&1 || { cat "$work/cluster.log"; fail "no cluster"; finish; }
export SLURM_CONF=$work/slurm/slurm.conf

# FIELD of job JOB (scontrol show job), e.g. JobState, Restarts, NumTasks.
job_field() {
  timeout 20 scontrol show job "$1" 2> /dev/null | tr ' ' '\n' | sed -n "s/^$2=//p" | head -1
}
# Waits (at most SECONDS) until the command succeeds; fails with WHAT otherwise.
wait_until() {  # SECONDS WHAT COMMAND...
  local limit=$1 what=$2
  shift 2
  for _ in $(seq 1 $((limit * 10))); do "$@" && return 0; sleep 0.1; done
  fail "waited $limit s for $what"
  return 1
}
job_ended() {  # JOB
  [[ $(job_field "$1" JobState) =~ ^(COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY)$ ]]
}
has_checkpoint() { compgen -G "$1/*.checkpoint" > /dev/null; }
has_checkpoint_or_ended() { has_checkpoint "$1" || job_ended "$2"; }
# Whether FILE exists, or job JOB has ended (then waiting for FILE is over).
appeared_or_ended() { [[ -e $1 ]] || job_ended "$2"; }
# Stops the test here: the rest would wait for what did not happen.
give_up() {
  fail "$*"
  echo "--- slurmctld.log (last lines)"; tail -20 "$work/slurm/slurmctld.log"
  for f in "$work"/*.log; do echo "--- $f"; tail -30 "$f"; done
  finish
}

# raceway behind a wrapper that keeps the SLURM_* variables each rank 0 of a campaign started with
# (by job and run), then starts raceway.
wrapper=$work/raceway
cat > "$wrapper" <<EOF
#!/bin/bash
if [[ \${1:-} == campaign && \${2:-} != check && \${SLURM_PROCID:-0} == 0 && -n \${SLURM_JOB_ID:-} ]]; then
  env | grep '^SLURM_' | sort > "$work/env_\${SLURM_JOB_ID}_run\$((\${SLURM_RESTART_COUNT:-0} + 1))"
fi
exec "$raceway" "\$@"
EOF
chmod +x "$wrapper"
export RACEWAY=$wrapper
# The jobs' logs (sbatch's default folder is the one it is called in).
cd "$work" || give_up "no $work"

case $case_name in
campaign)
  script=$source_dir/jobs/campaigns/slurm_campaign.sh
  job=$(sbatch --parsable --ntasks=2 --time=10 --partition=other --output="$work/chain-%j.log" \
          "$script" "$small" "$work/c") || give_up "sbatch"
  wait_until 90 "a checkpoint of job $job's first run" has_checkpoint_or_ended "$work/c" "$job"
  has_checkpoint "$work/c" || give_up "no checkpoint"
  # What --signal=B:USR1@300 does five minutes before the time limit.
  scancel --batch --signal=USR1 "$job" || fail "scancel --signal=USR1"
  wait_until 150 "job $job to end after its requeue" job_ended "$job" || give_up "job $job did not end"
  log=$work/chain-$job.log
  [[ $(job_field "$job" JobState) == COMPLETED && $(job_field "$job" ExitCode) == 0:0 ]] \
    || fail "job $job: $(job_field "$job" JobState), exit $(job_field "$job" ExitCode): $(tail -5 "$log")"
  [[ $(job_field "$job" Restarts) == 1 ]] || fail "job $job ran $(($(job_field "$job" Restarts) + 1)) times, expected 2"
  # The options it was submitted with, kept by the requeue.
  [[ $(job_field "$job" NumTasks) == 2 && $(job_field "$job" TimeLimit) == 00:10:00 &&
     $(job_field "$job" Partition) == other ]] \
    || fail "job $job's options: NumTasks=$(job_field "$job" NumTasks) TimeLimit=$(job_field "$job" TimeLimit) Partition=$(job_field "$job" Partition)"
  for expected in "launcher: srun --mpi=pmix" "run 1 of at most 20, 2 task(s)" "SIGUSR1: asking raceway to checkpoint and stop" \
                  "campaign stopped by a signal" "requeueing job $job" "run 2 of at most 20, 2 task(s) on 1 node(s) --resume" \
                  "3 of 3 scenes done, 0 failed"; do
    grep -qF -- "$expected" "$log" || fail "not in job $job's log: '$expected'"
  done
  grep -q "stopped, left for --resume" "$log" || fail "no scene was stopped by the signal: $(cat "$log")"
  # Run 2 started from the environment job $job was submitted from: the same SLURM_* variables as
  # run 1 (none left over from run 1), with SLURM_RESTART_COUNT.
  [[ -f "$work/env_${job}_run1" && -f "$work/env_${job}_run2" ]] || fail "no environment of the runs: $(ls "$work")"
  extra=$(comm -13 <(cut -d= -f1 "$work/env_${job}_run1") <(cut -d= -f1 "$work/env_${job}_run2") | tr '\n' ' ')
  missing=$(comm -23 <(cut -d= -f1 "$work/env_${job}_run1") <(cut -d= -f1 "$work/env_${job}_run2") | tr '\n' ' ')
  [[ $extra == "SLURM_RESTART_COUNT " && -z $missing ]] || fail "run 2's SLURM_* variables: extra '$extra', missing '$missing'"
  { grep -qx "SLURM_NTASKS=2" "$work/env_${job}_run2" && grep -qx "SLURM_JOB_PARTITION=other" "$work/env_${job}_run2"; } \
    || fail "run 2's environment: $(cat "$work/env_${job}_run2")"
  "$python" - "$work/c" <<'PY' || fail "the table"
import csv, sys
rows = list(csv.DictReader(open(f"{sys.argv[1]}/campaign_table.csv")))
assert [r["scene"] for r in rows] == ["s000", "s001", "s002"], rows
for r in rows:
    assert r["status"] == "done" and float(r["cage_speed_rpm"]) > 0 and int(r["steps"]) > 0, r
PY
  # SIGUSR1 at once: as soon as the batch script runs its first line (the trap), as Slurm sends it
  # when the time limit is shorter than the signal's lead.
  job=$(sbatch --parsable --ntasks=2 --time=10 --output="$work/early-%j.log" "$script" "$small" "$work/e") \
    || give_up "sbatch"
  script_has_trap() {
    local pid
    for pid in $(timeout 10 scontrol listpids "$job" 2> /dev/null | awk 'NR > 1 {print $1}'); do
      grep -q slurm_script "/proc/$pid/cmdline" 2> /dev/null || continue
      # SIGUSR1 (10) caught: bit 9 of SigCgt.
      (( 0x$(awk '/^SigCgt:/ {print $2}' "/proc/$pid/status") & 0x200 )) && return 0
    done
    return 1
  }
  wait_until 60 "job $job's script" script_has_trap || give_up "job $job's script never ran"
  scancel --batch --signal=USR1 "$job" || fail "scancel --signal=USR1"
  wait_until 60 "job $job to end" job_ended "$job" || give_up "job $job did not end"
  log=$work/early-$job.log
  [[ $(job_field "$job" ExitCode) == 4:0 && $(job_field "$job" Restarts) == 0 ]] \
    || fail "job $job, SIGUSR1 at once: exit $(job_field "$job" ExitCode), $(job_field "$job" Restarts) restarts: $(cat "$log")"
  grep -q "not requeued: SIGUSR1 came while raceway was starting" "$log" || fail "job $job: $(cat "$log")"
  grep -q "^SIGUSR1" "$log" || fail "job $job: the signal was not taken: $(cat "$log")"
  ;;
array)
  script=$source_dir/jobs/campaigns/slurm_array.sh
  export RACEWAY_SBATCH_OPTIONS="--ntasks=1 --time=10 --partition=other" RACEWAY_LAUNCHER=mpirun
  bash "$script" "$small" "$work/c" > "$work/submit.log" 2>&1 || give_up "submit: $(cat "$work/submit.log")"
  array=$(sed -n 's/.* as array job \([0-9]*\),.*/\1/p' "$work/submit.log")
  [[ -n $array ]] || give_up "no array job: $(cat "$work/submit.log")"
  # s001 killed outright once it has a checkpoint (every process of the task: a lost node), s002
  # stopped by SIGUSR1 to its batch script (the time limit's warning).
  wait_until 90 "a checkpoint of s001" appeared_or_ended "$work/c/s001.h5.checkpoint" "${array}_1"
  scancel --full --signal=KILL "${array}_1" || fail "scancel s001"
  wait_until 90 "a checkpoint of s002" appeared_or_ended "$work/c/s002.h5.checkpoint" "${array}_2"
  scancel --batch --signal=USR1 "${array}_2" || fail "scancel --signal=USR1 s002"
  wait_until 30 "task 1 to end" job_ended "${array}_1"
  [[ -f "$work/c/s001.h5" ]] && give_up "s001 finished before it was killed"
  # Round 1's aggregation step submits s001 and s002 again; round 2's writes the table.
  all_ended() { [[ -f "$work/c/campaign_table.csv" && -z $(squeue -h 2> /dev/null) ]]; }
  wait_until 240 "the table and the end of every job" all_ended || give_up "no table"
  reports=$(scontrol show jobs 2> /dev/null | sed -n 's/^JobId=\([0-9]*\) JobName=raceway-array-report$/\1/p')
  [[ $(echo "$reports" | wc -l) == 2 ]] || fail "aggregation steps '$reports', expected 2 (one round of resubmission)"
  grep -q "round 1: 2 scene(s) not finished (stopped or killed): submitted again" "$work"/raceway-array-*.log \
    || fail "round 1 did not submit s001 and s002 again"
  # Every job with the user's options (the aggregation steps on one task); the last one ended well.
  for id in $(scontrol show jobs 2> /dev/null | sed -n 's/^JobId=\([0-9]*\) .*/\1/p'); do
    [[ $(job_field "$id" Partition) == other && $(job_field "$id" TimeLimit) == 00:10:00 &&
       $(job_field "$id" NumTasks) == 1 ]] || fail "job $id: $(timeout 20 scontrol show job "$id")"
  done
  [[ $(job_field "$(echo "$reports" | tail -1)" ExitCode) == 0:0 ]] || fail "the last aggregation step failed"
  grep -q "launcher: mpirun (RACEWAY_LAUNCHER)" "$work"/raceway-array-"${array}"_0.log || fail "task 0's launcher"
  # A task submitted by an aggregation step (a job) started with the variables of a task submitted
  # from the login node: none of the aggregation job's left over.
  first=$(grep -l "^SLURM_ARRAY_JOB_ID=$array$" "$work"/env_* | head -1)
  again=$(grep -L "^SLURM_ARRAY_JOB_ID=$array$" "$work"/env_* | head -1)
  [[ -n $first && -n $again ]] || fail "no environment of the tasks: $(ls "$work")"
  [[ $(cut -d= -f1 "$first") == "$(cut -d= -f1 "$again")" ]] \
    || fail "a resubmitted task's SLURM_* variables differ: $(diff <(cut -d= -f1 "$first") <(cut -d= -f1 "$again"))"
  "$python" - "$work/c" <<'PY' || fail "the table"
import csv, sys
rows = list(csv.DictReader(open(f"{sys.argv[1]}/campaign_table.csv")))
assert [r["scene"] for r in rows] == ["s000", "s001", "s002"], rows
for r in rows:
    assert r["status"] == "done" and float(r["cage_speed_rpm"]) > 0 and int(r["steps"]) > 0, r
PY
  grep -q '"exit_code": 4' "$work/c/"campaign_status_s002_*.json || fail "s002 has no record of its stop"
  # A launcher that cannot start raceway: a plain srun (MpiDefault=none), with which Open MPI ends
  # every rank in MPI_Init. Each scene is recorded once as failed, nothing is submitted again, and
  # the aggregation step says why (exit 1).
  export RACEWAY_LAUNCHER=srun RACEWAY_SBATCH_OPTIONS="--ntasks=2 --time=10"
  bash "$script" "$small" "$work/f" > "$work/submit_f.log" 2>&1 || give_up "submit: $(cat "$work/submit_f.log")"
  report=$(sed -n 's/.* the aggregation step as job \([0-9]*\) .*/\1/p' "$work/submit_f.log")
  wait_until 120 "the aggregation step $report" job_ended "$report" || give_up "aggregation step $report"
  sleep 2  # anything it submitted would be in the queue now
  log=$(ls "$work"/raceway-array-"$report"_*.log)
  [[ $(job_field "$report" ExitCode) == 1:0 ]] || fail "aggregation step: exit $(job_field "$report" ExitCode): $(cat "$log")"
  grep -q "no table: raceway started on no scene (3 failed, 0 not finished)" "$log" || fail "aggregation step: $(cat "$log")"
  grep -q "the launcher (srun) ended with exit code 1 and raceway left no record" "$log" || fail "no diagnosis: $(cat "$log")"
  [[ -z $(squeue -h 2> /dev/null) ]] || fail "submitted again: $(squeue)"
  for id in s000 s001 s002; do
    [[ $(cat "$work/f/campaign_status_${id}"_*.json 2> /dev/null | grep -c '"exit_code": 1') == 1 ]] \
      || fail "$id's records: $(cat "$work/f/campaign_status_${id}"_*.json)"
  done
  ;;
*) fail "unknown case $case_name" ;;
esac
finish
