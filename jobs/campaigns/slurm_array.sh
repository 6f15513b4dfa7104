#!/bin/bash
# A raceway campaign (docs/campaigns.md) as a Slurm job array: one array task per scene, each a
# durable run, and a dependent aggregation job that makes the table, the same table as one
# allocation's campaign (jobs/campaigns/slurm_campaign.sh). Run it on the login node to submit:
#
#   RACEWAY_SBATCH_OPTIONS="--ntasks=2 --time=4:00:00" jobs/campaigns/slurm_array.sh jobs/campaigns/qj215_speed.toml runs/qj215_speed
#
# What it does, by RACEWAY_ARRAY_STEP:
#   submit (unset): counts the scenes (`raceway campaign check`), submits this script as the array
#     0..N-1 (RACEWAY_ARRAY_STEP=task, with RACEWAY_SBATCH_OPTIONS: ranks and time per scene) and,
#     after the whole array has ended (--dependency=afterany), once more as the aggregation step.
#   task: `raceway campaign FILE -o DIR --only $SLURM_ARRAY_TASK_ID --resume` on the task's ranks: the
#     scene runs (or resumes from its checkpoint) on all of them; a failed scene is retried once.
#     Slurm's SIGUSR1 five minutes before the time limit (--signal=B:USR1@300) makes it write a
#     checkpoint and stop (exit 4).
#   report: scenes neither finished nor failed (stopped by the signal, or killed without a word: a
#     hard time limit, a lost node) are submitted again as an array of their indices with a new
#     aggregation step after it (RACEWAY_JOB_NUMBER counts the rounds, RACEWAY_MAX_JOBS, default 20,
#     ends them); when none is left, `raceway campaign report DIR` writes the table and plots.
#
# Environment: RACEWAY (the executable; default raceway on PATH), RACEWAY_LAUNCHER (default "srun";
# e.g. "mpirun -np $SLURM_NTASKS"; empty: one rank), RACEWAY_SBATCH_OPTIONS, SBATCH (default sbatch).
#SBATCH --job-name=raceway-array
#SBATCH --signal=B:USR1@300
#SBATCH --output=raceway-array-%A_%a.log
set -u
campaign=${1:?usage: slurm_array.sh CAMPAIGN.toml OUTPUT_DIR}
output=${2:?usage: slurm_array.sh CAMPAIGN.toml OUTPUT_DIR}
raceway=${RACEWAY:-raceway}
launcher=${RACEWAY_LAUNCHER-srun}
step=${RACEWAY_ARRAY_STEP:-submit}
sbatch=${SBATCH:-sbatch}
round=${RACEWAY_JOB_NUMBER:-1}
max_jobs=${RACEWAY_MAX_JOBS:-20}
# Slurm runs a copy of the batch script: the submit step passes the original's path on.
self=${RACEWAY_SLURM_SCRIPT:-$0}

# Submits the array of INDICES (a Slurm list: 0-7 or 1,3) and its aggregation step (round ROUND).
submit() {
  local indices=$1 next_round=$2 array report
  # shellcheck disable=SC2086  # the options are words
  array=$($sbatch --parsable --array="$indices" ${RACEWAY_SBATCH_OPTIONS:-} \
            --export=ALL,RACEWAY_ARRAY_STEP=task,RACEWAY_SLURM_SCRIPT="$self" "$self" "$campaign" "$output") || exit 1
  array=${array%%;*}
  report=$($sbatch --parsable --dependency=afterany:"$array" --ntasks=1 --job-name=raceway-array-report \
             --export=ALL,RACEWAY_ARRAY_STEP=report,RACEWAY_JOB_NUMBER="$next_round",RACEWAY_SLURM_SCRIPT="$self" \
             "$self" "$campaign" "$output") || exit 1
  echo "submitted scenes $indices as array job $array, the aggregation step as job ${report%%;*} (round $next_round)"
}

# The latest exit code an array task recorded for scene ID, or none.
recorded_exit() {
  local latest
  latest=$(ls -t "$output"/campaign_status_"$1"_*.json 2> /dev/null | head -1)
  [[ -n $latest ]] && sed -n 's/.*"exit_code": *\([0-9]*\).*/\1/p' "$latest" | head -1
}

case $step in
submit)
  count=$("$raceway" campaign check "$campaign" | grep -c '^  s[0-9]')
  (( count > 0 )) || { echo "no scenes in $campaign (raceway campaign check $campaign)"; exit 2; }
  submit "0-$((count - 1))" 1
  ;;
task)
  scene=${SLURM_ARRAY_TASK_ID:?an array task needs SLURM_ARRAY_TASK_ID}
  echo "raceway campaign $campaign -> $output: scene $scene (array job ${SLURM_ARRAY_JOB_ID:-?}, ${SLURM_NTASKS:-1} ranks)"
  # --resume: a scene that has a checkpoint continues from it, a finished one is skipped.
  # shellcheck source=jobs/campaigns/slurm_common.sh
  source "$(dirname "$self")/slurm_common.sh"
  # shellcheck disable=SC2086  # the launcher is a command with its options
  run_passing_usr1 $launcher "$raceway" campaign "$campaign" -o "$output" --only "$scene" --resume
  echo "scene $scene: raceway exited with code $code"
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
  "$raceway" campaign report "$output" || exit 1
  echo "table: $output/campaign_table.csv ($failed failed, ${#left[@]} not finished)"
  (( failed + ${#left[@]} == 0 )) || exit 1
  ;;
*) echo "RACEWAY_ARRAY_STEP=$step: expected submit, task or report"; exit 2 ;;
esac
