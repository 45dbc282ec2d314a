#!/usr/bin/env bash
# Renders one limn-render sequence (--turntable, --cameras or --frames) as a Slurm job array of N
# tasks, task I running `limn-render --shard I/N ARGS...`, and waits for the array to finish.
# Every part frames and lights its frames as the whole sequence does, so the frames are the bytes
# one process writes. Paths are relative to the folder this is run in (the tasks start there).
#
# Usage: scripts/slurm-render.sh [-n N] [--tasks LIST] [--] LIMN-RENDER-ARGS...
#   -n N          parts (array tasks) [default: 4]
#   --tasks LIST  submit only these parts, as sbatch --array takes them (1,3 or 0-2), e.g. to
#                 render again a part that failed or was cancelled [default: 0-(N-1)]
# Other sbatch options come from sbatch's environment variables (SBATCH_PARTITION,
# SBATCH_TIMELIMIT, SBATCH_ACCOUNT, ...) or #SBATCH-free defaults: one CPU per task, the task logs
# in slurm-JOB_TASK.out. LIMN_RENDER names the limn-render to run [default: the one in build/bin
# beside this script, else limn-render on PATH]; it must be reachable at the same path on the
# compute nodes (a shared filesystem).
# Exit status: 0 when every task succeeded; otherwise the highest task exit status (limn-render's:
# 1 bad input, 2 usage, 3 missing capability; 1 for a cancelled or killed task), 2 for a usage
# error here; the failed parts are named. Ctrl-C (or SIGTERM) cancels the array; each cancelled
# task removes the frames it had written.
set -euo pipefail

# Inside an array task: sbatch runs a copy of this script with LIMN_SLURM_PARTS set.
if [ -n "${LIMN_SLURM_PARTS:-}" ]; then
  exec "$LIMN_RENDER" --shard "$SLURM_ARRAY_TASK_ID/$LIMN_SLURM_PARTS" "$@"
fi

usage() { echo "slurm-render.sh: error: $*" >&2; echo "usage: scripts/slurm-render.sh [-n N] [--tasks LIST] [--] LIMN-RENDER-ARGS..." >&2; exit 2; }
parts=4 tasks=
while [ $# -gt 0 ]; do
  case $1 in
    -n) [ $# -ge 2 ] || usage "-n needs a number of parts"; parts=$2; shift 2 ;;
    --tasks) [ $# -ge 2 ] || usage "--tasks needs a list such as 1,3 or 0-2"; tasks=$2; shift 2 ;;
    --) shift; break ;;
    *) break ;;
  esac
done
[[ $parts =~ ^[1-9][0-9]{0,4}$ ]] || usage "-n: '$parts' is not a number of parts from 1 to 99999"
[[ -z $tasks || $tasks =~ ^[0-9,-]+$ ]] || usage "--tasks: '$tasks' is not a list of parts such as 1,3 or 0-2"
[ $# -gt 0 ] || usage "give limn-render's arguments: INPUT --turntable N (or --cameras, --frames) -o NAME_%04d.png"
for a in "$@"; do [ "$a" != --shard ] || usage "--shard is given to each task here; leave it out"; done
for c in sbatch squeue scontrol scancel; do command -v $c >/dev/null || { echo "slurm-render.sh: error: $c not found (Slurm's client commands)" >&2; exit 3; }; done

here=$(cd "$(dirname "$0")" && pwd)
if [ -z "${LIMN_RENDER:-}" ]; then
  if [ -x "$here/../build/bin/limn-render" ]; then LIMN_RENDER=$here/../build/bin/limn-render
  else LIMN_RENDER=$(command -v limn-render) || { echo "slurm-render.sh: error: no limn-render: build it or set LIMN_RENDER" >&2; exit 3; }; fi
fi
LIMN_RENDER=$(cd "$(dirname "$LIMN_RENDER")" && pwd)/$(basename "$LIMN_RENDER")
[ -x "$LIMN_RENDER" ] || { echo "slurm-render.sh: error: $LIMN_RENDER is not executable" >&2; exit 3; }
# An unknown option or a bad value fails here, once, not in N tasks: limn-render parses the
# arguments in order and stops at the last, a part that cannot exist.
check=$("$LIMN_RENDER" "$@" --shard "$parts/$parts" 2>&1 >/dev/null) && true
case $check in
  *"--shard: '$parts/$parts' is not I/N"*) ;; # everything else was accepted
  *) echo "$check" >&2; exit 2 ;;
esac

# Waiting: squeue every LIMN_SLURM_POLL seconds (default 1) until no task is left, then each
# task's state and exit code from scontrol (the controller keeps finished jobs for MinJobAge,
# 300 s by default). sbatch --wait polls at growing intervals: on a 17 s array it returned 26 s
# after the last frame.
job=$(LIMN_SLURM_PARTS=$parts LIMN_RENDER=$LIMN_RENDER \
  sbatch --parsable --export=ALL --job-name=limn-render --cpus-per-task=1 \
  --array="${tasks:-0-$((parts - 1))}" "$0" "$@")
job=${job%%;*}
echo "slurm-render.sh: submitted job $job, parts ${tasks:-0-$((parts - 1))} of $parts" >&2
cancel() {
  trap - INT TERM
  scancel "$job" && echo "slurm-render.sh: cancelled job $job" >&2
  exit 130
}
trap cancel INT TERM
poll=${LIMN_SLURM_POLL:-1}
failures=0
while :; do
  if left=$(squeue -h -j "$job" -o %i 2>/dev/null); then
    failures=0
    [ -z "$left" ] && break
  else
    # A busy controller: try again; a job squeue no longer knows is done.
    failures=$((failures + 1))
    [ $failures -lt 30 ] || break
  fi
  sleep "$poll"
done
info=$(scontrol -o show job "$job") || { echo "slurm-render.sh: error: job $job: scontrol cannot say how its parts ended" >&2; exit 1; }
status=0 failed= seen=0
while read -r line; do
  [[ $line =~ ArrayTaskId=([0-9]+) ]] || continue
  task=${BASH_REMATCH[1]}
  seen=$((seen + 1))
  [[ $line =~ JobState=([A-Z_]+) ]] && state=${BASH_REMATCH[1]} || state=UNKNOWN
  [[ $line =~ ExitCode=([0-9]+):([0-9]+) ]] && code=${BASH_REMATCH[1]} signal=${BASH_REMATCH[2]} || code=1 signal=0
  if [ "$state" != COMPLETED ] || [ "$code" -ne 0 ]; then
    [ "$code" -gt 0 ] || code=1 # cancelled or killed by a signal
    [ "$code" -le $status ] || status=$code
    failed="$failed $task"
    echo "slurm-render.sh: part $task: $state, exit code $code${signal:+, signal $signal}" >&2
  fi
done <<<"$info"
[ $seen -gt 0 ] || { echo "slurm-render.sh: error: job $job: scontrol lists none of its parts" >&2; exit 1; }
if [ $status -eq 0 ]; then
  echo "slurm-render.sh: job $job: parts ${tasks:-0-$((parts - 1))} of $parts done" >&2
else
  echo "slurm-render.sh: job $job: parts${failed} failed; see slurm-${job}_I.out, and render them again with --tasks$(echo "$failed" | tr ' ' ',' | sed 's/^,/ /')" >&2
fi
exit $status
