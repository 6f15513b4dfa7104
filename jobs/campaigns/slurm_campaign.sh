#!/bin/bash
# One Slurm allocation running one raceway campaign (docs/campaigns.md), requeued with --resume
# until it is done:
#
#   RACEWAY=$PWD/build/raceway sbatch --ntasks=8 --time=24:00:00 jobs/campaigns/slurm_campaign.sh \
#     jobs/campaigns/qj215_speed.toml runs/qj215_speed
#
# Slurm sends SIGUSR1 to this script 5 minutes before the time limit (--signal=B:USR1@300); the
# script passes it to the launcher, every running scene writes a checkpoint and stops, raceway
# exits 4, and the script requeues the job (scontrol requeue): the same job, with every option it
# was submitted with (ranks, time, partition, account, ...) and the environment it was submitted
# from, starts again, finds DIR/campaign.json and continues with --resume (finished scenes are
# skipped, interrupted ones resume from their checkpoints). Slurm starts a requeued job no sooner
# than its credential lifetime later (AuthInfo cred_expire, 120 s by default). A failed scene does
# not requeue: the job ends with raceway's exit code and the table names the scene and its
# diagnosis. Nor does a job that got the signal while raceway was starting (as Slurm sends it when
# --time is shorter than the signal's lead: every run would get it at once) or made no progress.
#
# Environment (taken from sbatch's, which exports the submitting shell's by default):
#   RACEWAY           the executable (default: raceway on PATH)
#   RACEWAY_LAUNCHER  the launcher of the ranks (default: srun --mpi=pmix where Slurm has PMIx, else
#                     mpirun; empty: one rank; slurm_common.sh, choose_launcher)
#   RACEWAY_MAX_JOBS  at most this many runs of the job (default 20)
#SBATCH --job-name=raceway-campaign
#SBATCH --signal=B:USR1@300
#SBATCH --requeue
#SBATCH --open-mode=append
#SBATCH --output=raceway-campaign-%j.log
# The first command (sbatch reads #SBATCH lines up to the first one): Slurm's SIGUSR1 may come at
# once (slurm_common.sh).
trap 'usr1_pending=1' USR1
set -u
usr1_pending=${usr1_pending:-0}
campaign=${1:?usage: slurm_campaign.sh CAMPAIGN.toml OUTPUT_DIR}
output=${2:?usage: slurm_campaign.sh CAMPAIGN.toml OUTPUT_DIR}
raceway=${RACEWAY:-raceway}
run_number=$((${SLURM_RESTART_COUNT:-0} + 1))
max_jobs=${RACEWAY_MAX_JOBS:-20}
# Slurm runs a copy of the batch script; the original (the path sbatch was given) has slurm_common.sh.
self=${RACEWAY_SLURM_SCRIPT:-$(scontrol show job "${SLURM_JOB_ID:-0}" 2> /dev/null | sed -n 's/^ *Command=\([^ ]*\).*/\1/p')}
self=${self:-$0}
# shellcheck source=jobs/campaigns/slurm_common.sh
source "$(dirname "$self")/slurm_common.sh" || exit 1

resume=()
[[ -f "$output/campaign.json" ]] && resume=(--resume)
echo "raceway campaign $campaign -> $output: job ${SLURM_JOB_ID:-(no Slurm job id)}, run $run_number of at most" \
  "$max_jobs, ${SLURM_NTASKS:-1} task(s) on ${SLURM_JOB_NUM_NODES:-1} node(s) ${resume[*]}"
choose_launcher
before=$(campaign_progress "$output")
records=$(campaign_records "$output")
run_passing_usr1 "$output" "${launcher[@]}" "$raceway" campaign "$campaign" -o "$output" "${resume[@]}"
echo "raceway campaign exited with code $code"
if [[ $code != 4 ]]; then
  if [[ $code != 0 && $(campaign_records "$output") == "$records" ]]; then
    echo "the campaign left no record of this run: the launcher (${launcher[*]:-none}) or raceway ended" \
      "before it ran a scene; the lines above say why (docs/campaigns.md, 'Clusters: Slurm')"
  fi
  exit "$code"
fi
if (( usr1_at_start )); then
  echo "not requeued: SIGUSR1 came while raceway was starting, as Slurm sends it when the time limit is" \
    "shorter than the signal's lead (--signal=B:USR1@300): the next run would get it at once again"
elif [[ "$(campaign_progress "$output")" == "$before" ]]; then
  echo "not requeued: this run made no progress (no scene finished, no checkpoint written)"
elif (( run_number >= max_jobs )); then
  echo "not requeued: $max_jobs runs already (RACEWAY_MAX_JOBS)"
elif [[ -z ${SLURM_JOB_ID:-} ]]; then
  echo "not requeued: not a Slurm job"
else
  # Said first: Slurm may end this script as soon as the job is requeued.
  echo "requeueing job $SLURM_JOB_ID: it runs again with --resume (run $((run_number + 1)))"
  scontrol requeue "$SLURM_JOB_ID" ||
    echo "scontrol requeue $SLURM_JOB_ID failed: submit this script again to continue (it resumes)"
fi
exit 4
