# shellcheck shell=bash
# Sourced by the Slurm recipes of jobs/campaigns (slurm_campaign.sh, slurm_array.sh) from the folder
# of the original script (Slurm runs a copy of a batch script elsewhere).

# Runs the command in the background, passes SIGUSR1 (Slurm's warning before the time limit) on to
# it, and waits until it has really ended; its exit code is left in $code.
run_passing_usr1() {
  "$@" &
  local child=$!
  # shellcheck disable=SC2064  # the child's pid is fixed now
  trap "echo 'SIGUSR1: asking raceway to checkpoint and stop'; kill -USR1 $child" USR1
  # wait returns early (status > 128) when the trap runs: wait until the command has really ended.
  while true; do
    wait "$child"
    # shellcheck disable=SC2034  # read by the caller
    code=$?
    kill -0 "$child" 2> /dev/null || break
  done
}
