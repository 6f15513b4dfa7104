#!/bin/bash
# One Slurm allocation running one raceway campaign (docs/campaigns.md), resubmitted with --resume
# until it is done:
#
#   sbatch --ntasks=8 --time=24:00:00 jobs/campaigns/slurm_campaign.sh jobs/campaigns/qj215_speed.toml runs/qj215_speed
#
# Slurm sends SIGUSR1 to this script 5 minutes before the time limit (--signal=B:USR1@300); the
# script passes it to the launcher, every running scene writes a checkpoint and stops, raceway
# exits 4, and the script submits itself again; the next job continues with --resume (finished
# scenes are skipped, interrupted ones resume from their checkpoints). A failed scene does not
# resubmit: the job ends with raceway's exit code and the table names the scene and its diagnosis.
#
# Environment: RACEWAY (the executable; default raceway on PATH), RACEWAY_LAUNCHER (default
# "srun"; e.g. "mpirun -np $SLURM_NTASKS"), RACEWAY_MAX_JOBS (default 20: resubmissions stop
# there), SBATCH (default sbatch).
#SBATCH --job-name=raceway-campaign
#SBATCH --signal=B:USR1@300
#SBATCH --output=raceway-campaign-%j.log
set -u
campaign=${1:?usage: slurm_campaign.sh CAMPAIGN.toml OUTPUT_DIR}
output=${2:?usage: slurm_campaign.sh CAMPAIGN.toml OUTPUT_DIR}
raceway=${RACEWAY:-raceway}
launcher=${RACEWAY_LAUNCHER:-srun}
job_number=${RACEWAY_JOB_NUMBER:-1}
max_jobs=${RACEWAY_MAX_JOBS:-20}
# Slurm runs a copy of the batch script; resubmit the original (the path sbatch was given).
self=${RACEWAY_SLURM_SCRIPT:-$(scontrol show job "${SLURM_JOB_ID:-0}" 2> /dev/null | sed -n 's/^ *Command=\([^ ]*\).*/\1/p')}
self=${self:-$0}

resume=()
[[ -f "$output/campaign.json" ]] && resume=(--resume)
echo "raceway campaign $campaign -> $output (job $job_number of at most $max_jobs, ${SLURM_JOB_ID:-no Slurm job id}) ${resume[*]}"
# shellcheck source=jobs/campaigns/slurm_common.sh
source "$(dirname "$self")/slurm_common.sh"
# shellcheck disable=SC2086  # the launcher is a command with its options
run_passing_usr1 $launcher "$raceway" campaign "$campaign" -o "$output" "${resume[@]}"
echo "raceway campaign exited with code $code"
if [[ $code == 4 ]]; then
  if (( job_number >= max_jobs )); then
    echo "not resubmitted: $max_jobs jobs already (RACEWAY_MAX_JOBS)"
  else
    ${SBATCH:-sbatch} --export=ALL,RACEWAY_JOB_NUMBER=$((job_number + 1)) "$self" "$campaign" "$output"
  fi
fi
exit $code
