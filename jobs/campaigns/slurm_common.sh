# shellcheck shell=bash disable=SC2034  # launcher, code, usr1_at_start: set for the recipes
# Sourced by the Slurm recipes of jobs/campaigns (slurm_campaign.sh, slurm_array.sh) from the folder
# of the original script (Slurm runs a copy of a batch script elsewhere). Each recipe notes SIGUSR1
# in its first command (`trap 'usr1_pending=1' USR1`, right after the #SBATCH lines): Slurm may send
# it within a second of the job's start, and an untrapped SIGUSR1 would end the script (exit 138).

# The launcher of raceway's ranks, in the array `launcher`: RACEWAY_LAUNCHER where it is set (its
# words; set but empty: no launcher, one rank); otherwise `srun --mpi=pmix` where this Slurm has
# the PMIx plugin: Open MPI (Debian's and most builds) starts under srun through PMIx only, and a
# plain srun (Slurm's default MpiDefault=none) ends every rank in MPI_Init. Without the plugin,
# Open MPI's mpirun, which takes the nodes and slots of the allocation from Slurm.
choose_launcher() {
  local why
  if [[ -n ${RACEWAY_LAUNCHER+set} ]]; then
    read -r -a launcher <<< "$RACEWAY_LAUNCHER"
    why="RACEWAY_LAUNCHER"
  elif srun --mpi=list 2>&1 | grep -qw pmix; then
    launcher=(srun --mpi=pmix)
    why="this Slurm has the PMIx plugin (srun --mpi=list); RACEWAY_LAUNCHER chooses another"
  elif command -v mpirun > /dev/null; then
    launcher=(mpirun)
    why="this Slurm has no PMIx plugin for srun (srun --mpi=list); RACEWAY_LAUNCHER chooses another"
  else
    launcher=(srun)
    why="neither srun's PMIx plugin nor mpirun found: srun with Slurm's default MPI plugin"
  fi
  echo "launcher: ${launcher[*]:-none (one rank)} ($why)"
}

# Runs COMMAND... (raceway on the launcher, writing the campaign into OUTPUT) in the background and
# waits until it has really ended; its exit code is left in $code. SIGUSR1 is passed on to it once
# raceway has taken the signals on every rank: a rank that has not yet got so far (still loading,
# or not yet started by the launcher) would die of it. raceway takes them first in main(), before
# MPI_Init, and MPI_Init returns on no rank before every rank has called it; rank 0 then writes
# OUTPUT/campaign.json, whose new time says so. A SIGUSR1 before the command started means it is
# not started: code 4, what raceway's own stop gives. usr1_at_start is 1 when the signal came before
# raceway was running: then the time limit is shorter than the signal's lead, and the next job would
# get it at once again.
run_passing_usr1() {
  local output=$1 started child passed=0
  shift
  usr1_at_start=0
  if (( ${usr1_pending:-0} )); then
    echo "SIGUSR1 before raceway started: not started"
    usr1_at_start=1
    code=4
    return
  fi
  started=$(date '+%Y-%m-%d %H:%M:%S.%N')
  "$@" &
  child=$!
  while true; do
    if (( ${usr1_pending:-0} && !passed )); then
      if [[ -n $(find "$output/campaign.json" -newermt "$started" 2> /dev/null) ]]; then
        echo "SIGUSR1: asking raceway to checkpoint and stop"
        kill -USR1 "$child" 2> /dev/null
        passed=1
      elif kill -0 "$child" 2> /dev/null; then
        usr1_at_start=1
        sleep 0.1  # raceway still starting
        continue
      fi
    fi
    # wait returns early (status > 128) when the trap runs: wait until the command has really ended.
    wait "$child"
    code=$?
    kill -0 "$child" 2> /dev/null || break
  done
}

# A fingerprint of the campaign's progress in OUTPUT: its finished scenes and its checkpoints, with
# their times and sizes.
campaign_progress() {
  find "$1" -maxdepth 1 \( -name '*.h5' -o -name '*.checkpoint' \) -printf '%f %T@ %s\n' 2> /dev/null | sort
}

# How many call records (DIR/campaign_status_*.json) the campaign in OUTPUT has.
campaign_records() {
  find "$1" -maxdepth 1 -name 'campaign_status_*.json' 2> /dev/null | wc -l
}

# Runs COMMAND... without the variables of this job (SLURM_*, but SLURM_CONF): a job submitted from
# a job would take them over (sbatch exports the environment), and srun reads SLURM_NTASKS, say, as
# its own option.
without_job_environment() {
  local name unset=()
  for name in ${!SLURM_@}; do
    [[ $name == SLURM_CONF ]] || unset+=(-u "$name")
  done
  env "${unset[@]}" "$@"
}
