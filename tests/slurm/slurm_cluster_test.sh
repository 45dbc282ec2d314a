#!/usr/bin/env bash
# Slurm.ArrayPartsAreTheOneProcessFrames: a real one-node Slurm cluster, started here in a private
# folder (munged with a generated key, slurmctld and slurmd in the foreground, a generated
# slurm.conf on free ports; nothing in /etc is read or touched), runs limn-render sequences as job
# arrays through scripts/slurm-render.sh:
#   - a 24-frame turntable of spot and the 24 frames of the twist example (--frames), 4 tasks each:
#     every frame is the one-process run's, byte for byte;
#   - a task cancelled mid-run (scancel) leaves none of its frames and no temporary file, the
#     other tasks' frames stay, and the task submitted again completes the set.
# The cluster is stopped by the pids in its pid files (never by name: other Slurm or munge
# processes may run on the machine) and its folder removed, also on failure or interruption.
# Skipped (exit 77) where the Slurm or munge packages are missing (scripts/setup.sh --tests
# installs them) or without root (slurmd starts jobs as their user).
# Usage: slurm_cluster_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
src=$(cd "$2" && pwd)

skip() { echo "skipped: $*"; exit 77; }
source "$src/tests/slurm/local_cluster.sh"
why=$(local_cluster_missing)
[ -z "$why" ] || skip "$why"

work=$(mktemp -d)
fail() { echo "slurm test: FAIL: $*" >&2; exit 1; }
cleanup() {
  local status=$?
  trap - EXIT INT TERM
  [ $status -eq 0 ] || local_cluster_logs
  local_cluster_stop
  rm -rf "$work"
  exit $status
}
trap cleanup EXIT
trap 'exit 130' INT TERM
# A command that fails outside fail() (set -e) still says where.
trap 'echo "slurm test: FAIL: line $LINENO: a command exited with $?" >&2' ERR
local_cluster_start "$work" || fail "the cluster did not start"

# --- inputs and the one-process runs -----------------------------------------------------------
bin=$build/bin
export LIMN_RENDER=$bin/limn-render
cd "$work"
"$bin/limn-classify" -q "$src/tests/data/quad/spot_control_mesh.obj" | "$bin/limn-tables" -q --depth 2 -o spot.limn
"$bin/limn-examples" -q -o . --only twist
"$bin/limn-tables" -q --depth 2 twist/twist_0000.obj -o twist.limn
small=(--size 64x48 -q)
spot=(spot.limn --turntable 24 --view 20,15 "${small[@]}")
twist=(twist.limn --frames twist/twist_%04d.obj "${small[@]}")
mkdir one arr
"$LIMN_RENDER" "${spot[@]}" -o one/spot_%04d.png
"$LIMN_RENDER" "${twist[@]}" -o one/twist_%04d.png

same_frames() { # NAME COUNT DIR: DIR holds exactly one/NAME_0000..COUNT-1, byte for byte
  local name=$1 count=$2 dir=$3 k f
  [ "$(ls "$dir" | grep -c "^${name}_")" -eq "$count" ] || fail "$dir: $(ls "$dir" | grep -c "^${name}_") ${name} frames, not $count"
  for ((k = 0; k < count; k++)); do
    f=$(printf '%s_%04d.png' "$name" $k)
    cmp -s "one/$f" "$dir/$f" || fail "$dir/$f is not the one-process frame"
  done
}
no_temporaries() { ! ls -a "$1" | grep -q limn-tmp || fail "$1 holds a temporary file: $(ls -a "$1")"; }

# --- 4-task arrays: the one-process frames ---------------------------------------------------
start=$SECONDS
"$src/scripts/slurm-render.sh" -n 4 "${spot[@]}" -o arr/spot_%04d.png
"$src/scripts/slurm-render.sh" -n 4 "${twist[@]}" -o arr/twist_%04d.png
same_frames spot 24 arr
same_frames twist 24 arr
no_temporaries arr
echo "slurm test: two 4-task arrays wrote the one-process frames ($((SECONDS - start)) s)"

# --- a task cancelled mid-run, then submitted again ------------------------------------------
# 240 views: each task renders 60 frames, long enough to be cancelled after its first ones.
long=(spot.limn --turntable 240 --view 20,15 --size 48x36 -q)
"$LIMN_RENDER" "${long[@]}" -o one/long_%04d.png
mkdir cancel
"$src/scripts/slurm-render.sh" -n 4 "${long[@]}" -o cancel/long_%04d.png >cancel.log 2>&1 &
script=$!
# Part 1 of 4 is frames 60 to 119: it is cancelled once it has written its first. It is held
# there (SIGSTOP to its limn-render, the batch step, which slurm-render.sh execs) so that it is
# still mid-run however fast the machine renders; scancel sends SIGCONT before SIGTERM.
# The waits are bounded in seconds, not in polls: under load one poll (squeue, scontrol) can take
# a large part of a second, and a task can wait that long to be scheduled.
# A poll that fails (a busy controller times out; set -e would end the test without a word) is
# tried again, like slurm-render.sh's own.
job= pid=
deadline=$((SECONDS + 180))
while ((SECONDS < deadline)); do
  job=$(squeue -h -o %F 2>/dev/null | head -n 1) || job=
  if [ -n "$job" ] && [ "$(squeue -h -j "${job}_1" -o %T 2>/dev/null)" = RUNNING ]; then
    pid=$(scontrol listpids "$(squeue -h -j "${job}_1" -o %A 2>/dev/null)" 2>/dev/null | awk '$3 == "batch" { print $1 }') || pid=
    [ -n "$pid" ] && break
  fi
  sleep 0.05
done
[ -n "$pid" ] || fail "task 1 did not start"
deadline=$((SECONDS + 180))
while ((SECONDS < deadline)); do [ -f cancel/long_0060.png ] && break; sleep 0.01; done
kill -STOP "$pid" || fail "task 1's process $pid ended before it could be held"
[ -f cancel/long_0060.png ] || fail "task 1 did not write frame 60"
[ ! -e cancel/long_0119.png ] || fail "task 1 had finished before it could be held"
scancel "${job}_1"
status=0
wait $script || status=$?
[ $status -eq 1 ] || fail "slurm-render.sh exited with $status although task 1 was cancelled: $(cat cancel.log)"
grep -q "part 1: CANCELLED" cancel.log || fail "slurm-render.sh does not name the cancelled part: $(cat cancel.log)"
grep -q -- "--tasks 1\$" cancel.log || fail "slurm-render.sh does not say how to render part 1 again: $(cat cancel.log)"
for ((k = 60; k < 120; k++)); do
  f=$(printf 'cancel/long_%04d.png' $k)
  [ ! -e "$f" ] || fail "the cancelled task left $f"
done
no_temporaries cancel
[ "$(ls cancel | wc -l)" -eq 180 ] || fail "the other tasks wrote $(ls cancel | wc -l) frames, not 180"
"$src/scripts/slurm-render.sh" -n 4 --tasks 1 "${long[@]}" -o cancel/long_%04d.png
same_frames long 240 cancel
no_temporaries cancel
echo "slurm test: a cancelled task left none of its frames; submitted again it completed the set ($((SECONDS - start)) s)"
