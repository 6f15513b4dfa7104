#!/bin/bash
# A raceway campaign (docs/campaigns.md) as a Slurm job array: one array task per scene, each a
# durable run, and a dependent aggregation job that makes the table, the same table as one
# allocation's campaign (jobs/campaigns/slurm_campaign.sh). Run it on the login node to submit:
#
#   RACEWAY=$PWD/build/raceway RACEWAY_SBATCH_OPTIONS="--ntasks=2 --time=4:00:00" \
#     jobs/campaigns/slurm_array.sh jobs/campaigns/qj215_speed.toml runs/qj215_speed
#
# What it does, by RACEWAY_ARRAY_STEP:
#   submit (unset): counts the scenes (`raceway campaign check`), submits this script as the array
#     0..N-1 (RACEWAY_ARRAY_STEP=task, with RACEWAY_SBATCH_OPTIONS: ranks, time, partition,
#     account, ...) and, after the whole array has ended (--dependency=afterany), once more as the
#     aggregation step (the same options, one task on one node).
#   task: `raceway campaign FILE -o DIR --only $SLURM_ARRAY_TASK_ID --resume` on the task's ranks: the
#     scene runs (or resumes from its checkpoint) on all of them; a failed scene is retried once.
#     Slurm's SIGUSR1 five minutes before the time limit (--signal=B:USR1@300) makes it write a
#     checkpoint and stop (exit 4). A task whose raceway left neither a record nor a checkpoint of
#     the scene (the launcher failed, raceway died at once) records the launcher's exit code itself:
#     the scene is then counted as failed, not submitted again.
#   report: scenes neither finished nor failed (stopped by the signal, or killed without a word: a
#     hard time limit, a lost node) are submitted again as an array of their indices with a new
#     aggregation step after it (RACEWAY_JOB_NUMBER counts the rounds, RACEWAY_MAX_JOBS, default 20,
#     ends them); when none is left, `raceway campaign report DIR` writes the table and plots.
#   Every submission leaves out the submitting job's SLURM_* variables (slurm_common.sh).
#
# Environment: RACEWAY (the executable; default raceway on PATH), RACEWAY_LAUNCHER (default: srun
# --mpi=pmix where Slurm has PMIx, else mpirun; empty: one rank; slurm_common.sh, choose_launcher),
# RACEWAY_SBATCH_OPTIONS, SBATCH (default sbatch).
#SBATCH --job-name=raceway-array
#SBATCH --signal=B:USR1@300
#SBATCH --output=raceway-array-%A_%a.log
# The first command (sbatch reads #SBATCH lines up to the first one): Slurm's SIGUSR1 may come at
# once (slurm_common.sh).
trap 'usr1_pending=1' USR1
set -u
usr1_pending=${usr1_pending:-0}
campaign=${1:?usage: slurm_array.sh CAMPAIGN.toml OUTPUT_DIR}
output=${2:?usage: slurm_array.sh CAMPAIGN.toml OUTPUT_DIR}
raceway=${RACEWAY:-raceway}
step=${RACEWAY_ARRAY_STEP:-submit}
sbatch=${SBATCH:-sbatch}
round=${RACEWAY_JOB_NUMBER:-1}
max_jobs=${RACEWAY_MAX_JOBS:-20}
# Slurm runs a copy of the batch script: the submit step passes the original's path on.
self=${RACEWAY_SLURM_SCRIPT:-$0}
# shellcheck source=jobs/campaigns/slurm_common.sh
source "$(dirname "$self")/slurm_common.sh" || exit 1

# Submits the array of INDICES (a Slurm list: 0-7 or 1,3) and its aggregation step (round ROUND).
submit() {
  local indices=$1 next_round=$2 array report
  # shellcheck disable=SC2086  # the options are words
  array=$(without_job_environment $sbatch --parsable --array="$indices" ${RACEWAY_SBATCH_OPTIONS:-} \
            --export=ALL,RACEWAY_ARRAY_STEP=task,RACEWAY_SLURM_SCRIPT="$self" "$self" "$campaign" "$output") || exit 1
  array=${array%%;*}
  # shellcheck disable=SC2086
  report=$(without_job_environment $sbatch --parsable --dependency=afterany:"$array" ${RACEWAY_SBATCH_OPTIONS:-} \
             --nodes=1 --ntasks=1 --job-name=raceway-array-report \
             --export=ALL,RACEWAY_ARRAY_STEP=report,RACEWAY_JOB_NUMBER="$next_round",RACEWAY_SLURM_SCRIPT="$self" \
             "$self" "$campaign" "$output") || exit 1
  echo "submitted scenes $indices as array job $array, the aggregation step as job ${report%%;*} (round $next_round)"
}

# The records of scene ID (DIR/campaign_status_ID_N.json), the latest first.
records_of() {
  ls -t "$output"/campaign_status_"$1"_*.json 2> /dev/null
}

# The latest exit code recorded for scene ID, or none.
recorded_exit() {
  local latest
  latest=$(records_of "$1" | head -1)
  [[ -n $latest ]] && sed -n 's/.*"exit_code": *\([0-9]*\).*/\1/p' "$latest" | head -1
}

# A record of scene ID (what raceway writes after a call) for a task whose raceway wrote none: its
# exit code CODE and the diagnosis TEXT.
record_task() {
  local id=$1 n=0 text=${3//\\/\\\\}
  text=${text//\"/\\\"}
  while [[ -e "$output/campaign_status_${id}_$n.json" ]]; do n=$((n + 1)); done
  printf '{\n "written_by": "jobs/campaigns/slurm_array.sh",\n "scenes_this_call": {\n  "%s": {\n   "exit_code": %d,\n   "attempts": 1,\n   "diagnosis": "%s"\n  }\n }\n}\n' \
    "$id" "$2" "$text" > "$output/campaign_status_${id}_$n.json"
}

case $step in
submit)
  count=$("$raceway" campaign check "$campaign" | grep -c '^  s[0-9]')
  (( count > 0 )) || { echo "no scenes in $campaign (raceway campaign check $campaign)"; exit 2; }
  submit "0-$((count - 1))" 1
  ;;
task)
  scene=${SLURM_ARRAY_TASK_ID:?an array task needs SLURM_ARRAY_TASK_ID}
  id=$(printf 's%03d' "$scene")
  echo "raceway campaign $campaign -> $output: scene $scene (array job ${SLURM_ARRAY_JOB_ID:-?}, ${SLURM_NTASKS:-1} task(s))"
  choose_launcher
  records=$(records_of "$id" | wc -l)
  checkpoint=$(campaign_progress "$output" | grep "^$id\.h5\.checkpoint ")
  # --resume: a scene that has a checkpoint continues from it, a finished one is skipped.
  run_passing_usr1 "$output" "${launcher[@]}" "$raceway" campaign "$campaign" -o "$output" --only "$scene" --resume
  echo "scene $scene: raceway exited with code $code"
  # raceway left no record and no new checkpoint of the scene: it did not start, or died before its
  # first checkpoint. Without a record the aggregation step would take the scene for killed and
  # submit it again, round after round, when it cannot start at all (a launcher that cannot start
  # raceway). A scene killed after a checkpoint is left to be submitted again: it resumes.
  if [[ ! -f "$output/$id.h5" && $(records_of "$id" | wc -l) == "$records" &&
        $(campaign_progress "$output" | grep "^$id\.h5\.checkpoint ") == "$checkpoint" ]]; then
    mkdir -p "$output" || exit 1
    if [[ $code == 4 ]]; then
      record_task "$id" 4 "stopped by SIGUSR1 before raceway started"
    else
      [[ $code == 0 ]] && code=1
      record_task "$id" "$code" "the launcher (${launcher[*]:-none}) ended with exit code $code and raceway left no record of the scene: it did not start, or died before its first checkpoint (array task ${SLURM_ARRAY_JOB_ID:-?}_$scene: its log says why; docs/campaigns.md, 'Clusters: Slurm')"
    fi
    echo "scene $scene: recorded with exit code $code (raceway left no record)"
  fi
  exit "$code"
  ;;
report)
  count=$("$raceway" campaign check "$campaign" | grep -c '^  s[0-9]')
  left=()
  failed=0
  for (( i = 0; i < count; i++ )); do
    id=$(printf 's%03d' "$i")
    [[ -f "$output/$id.h5" ]] && continue
    code=$(recorded_exit "$id")
    if [[ -n $code && $code != 4 ]]; then failed=$((failed + 1)); else left+=("$i"); fi
  done
  if (( ${#left[@]} > 0 )) && (( round < max_jobs )); then
    echo "round $round: ${#left[@]} scene(s) not finished (stopped or killed): submitted again"
    submit "$(IFS=,; echo "${left[*]}")" $((round + 1))
    exit 0
  fi
  (( ${#left[@]} > 0 )) && echo "not submitted again: $max_jobs rounds already (RACEWAY_MAX_JOBS)"
  if [[ ! -f "$output/campaign.json" ]]; then
    echo "no table: raceway started on no scene ($failed failed, ${#left[@]} not finished); the tasks recorded:"
    sed -n 's/^ *"diagnosis": "\(.*\)"$/  \1/p' "$output"/campaign_status_*.json 2> /dev/null | sort -u
    exit 1
  fi
  "$raceway" campaign report "$output" || exit 1
  echo "table: $output/campaign_table.csv ($failed failed, ${#left[@]} not finished)"
  (( failed + ${#left[@]} == 0 )) || exit 1
  ;;
*) echo "RACEWAY_ARRAY_STEP=$step: expected submit, task or report"; exit 2 ;;
esac
