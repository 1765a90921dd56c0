#!/bin/bash
#SBATCH --job-name=pedesis
#SBATCH --time=24:00:00
#SBATCH --output=pedesis-%j.out
#SBATCH --signal=B:USR1@300
# A pedesis run longer than a job's time limit, as a chain of jobs: each job continues the
# run in place (--resume); Slurm's USR1, 300 s before the limit, makes the run checkpoint
# and exit 75, and the job submits the next one; the job that finishes the run ends the
# chain. Submit the first job once, from the directory CONFIG and OUT are relative to:
#
#   export CONFIG=run.toml OUT=runs/long PEDESIS_JOB_SCRIPT=$PWD/pedesis_job.sh
#   sbatch pedesis_job.sh
#
# "B:" sends USR1 to this shell alone, so that it knows the stop came from the time limit;
# 300 s is ample for the run to reach a safe point and write its checkpoint.
set -u
CONFIG=${CONFIG:-run.toml}
OUT=${OUT:-run}
PEDESIS=${PEDESIS:-pedesis}
# Under Slurm, $0 is slurmd's copy of this script in its spool directory, not your file:
# name your file in PEDESIS_JOB_SCRIPT (sbatch hands the environment on to the jobs it
# submits, so setting it for the first one is enough).
script=${PEDESIS_JOB_SCRIPT:-$0}

# Pass USR1 and TERM on to the run. TERM (scancel, preemption) also reaches the run from
# Slurm itself; a repeated signal does not cut its clean stop short. A signal that comes
# before the run has started is sent once it has.
child='' signal=''
forward() {
    signal=$1
    if [ -n "$child" ]; then kill -s "$1" "$child" 2>/dev/null; fi
}
trap 'forward USR1' USR1
trap 'forward TERM' TERM

"$PEDESIS" run "$CONFIG" --out "$OUT" --resume &
child=$!
if [ -n "$signal" ]; then kill -s "$signal" "$child" 2>/dev/null; fi
# A trapped signal ends `wait` early (status 128 + signal) while the run is still writing
# its checkpoint: wait until it is gone; a last `wait` gives the run's own exit status.
while kill -0 "$child" 2>/dev/null; do wait "$child"; done
wait "$child"
status=$?

case $status in
0) echo "pedesis_job.sh: $OUT: the run is done" ;;
75)
    # Only the time limit's warning continues the chain: after scancel (TERM) a new job
    # would be unwanted, and a preempted job that Slurm requeues must not meet a twin.
    if [ "$signal" != USR1 ]; then
        echo "pedesis_job.sh: $OUT: stopped with a checkpoint; to continue: sbatch $script" >&2
        exit 75
    fi
    sbatch "$script" || exit 75
    echo "pedesis_job.sh: $OUT: checkpointed at the time limit; submitted the next job"
    ;;
*) exit "$status" ;;
esac
