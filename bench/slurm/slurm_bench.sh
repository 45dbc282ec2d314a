#!/usr/bin/env bash
# bench_slurm: one limn-render sequence in one process vs as a Slurm job array
# (scripts/slurm-render.sh) on a one-node cluster started here (tests/slurm/local_cluster.sh: the
# same throwaway cluster as the Slurm test; needs slurm-wlm, munge and root). A turntable of MESH
# (default 96 views of spot at depth 4, 640x480):
#   one      limn-render --turntable N, one process
#   array    scripts/slurm-render.sh -n TASKS, from the start to its return (it polls squeue
#            every second); the frames are checked equal to one's
#   frames   from the start to the array's last frame in place (its modification time): the
#            array's time without the polling
#   local    the same TASKS parts as background processes on this machine (what GNU parallel or
#            make -j run): the array's time without Slurm
#   part     the per-task overhead of a part: a --frame-range run of its first frame (start-up, the
#            whole sequence's framing and one frame) minus one frame of the one-process run
# Rounds interleave the configurations (one, array, local, part); medians. One JSON line per round on
# stdout, a table on stderr.
# Usage: bench/slurm/slurm_bench.sh [--rounds R] [--tasks T] [--views N] [--size WxH] [--depth D]
#                                   [BUILD_DIR] [MESH]
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
rounds=1 tasks=2 views=96 size=640x480 depth=4
while [ $# -gt 0 ]; do
  case $1 in
    --rounds) rounds=$2; shift 2 ;;
    --tasks) tasks=$2; shift 2 ;;
    --views) views=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --depth) depth=$2; shift 2 ;;
    *) break ;;
  esac
done
build=$(cd "${1:-$src/build}" && pwd)
mesh=$(cd "$(dirname "${2:-$src/tests/data/quad/spot_control_mesh.obj}")" && pwd)/$(basename "${2:-spot_control_mesh.obj}")

source "$src/tests/slurm/local_cluster.sh"
why=$(local_cluster_missing)
[ -z "$why" ] || { echo "bench_slurm: $why" >&2; exit 3; }
work=$(mktemp -d)
cleanup() { local s=$?; trap - EXIT INT TERM; [ $s -eq 0 ] || local_cluster_logs; local_cluster_stop; rm -rf "$work"; exit $s; }
trap cleanup EXIT
trap 'exit 130' INT TERM
local_cluster_start "$work"
cd "$work"
export LIMN_RENDER=$build/bin/limn-render
"$build/bin/limn-classify" -q "$mesh" | "$build/bin/limn-tables" -q --depth "$depth" -o mesh.limn
args=(mesh.limn --turntable "$views" --size "$size" -q)

now() { date +%s.%N; }
calc() { awk "BEGIN { print $* }"; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
: >one.txt; : >array.txt; : >frames.txt; : >local.txt; : >part.txt
for ((r = 1; r <= rounds; r++)); do
  rm -rf one array local part; mkdir one array local part
  t0=$(now); "$LIMN_RENDER" "${args[@]}" -o one/%04d.png; t1=$(now)
  "$src/scripts/slurm-render.sh" -n "$tasks" "${args[@]}" -o array/%04d.png 2>/dev/null; t2=$(now)
  pids=()
  for ((i = 0; i < tasks; i++)); do "$LIMN_RENDER" "${args[@]}" --shard $i/$tasks -o local/%04d.png & pids+=($!); done
  for p in "${pids[@]}"; do wait "$p"; done # not the cluster's daemons, also children of this shell
  t4=$(now)
  "$LIMN_RENDER" "${args[@]}" --frame-range 0-0 -o part/%04d.png; t3=$(now)
  for f in one/*.png; do
    for d in array local; do cmp -s "$f" "$d/${f#one/}" || { echo "bench_slurm: $d/${f#one/} differs" >&2; exit 1; }; done
  done
  [ "$(ls array | wc -l)" -eq "$views" ] || { echo "bench_slurm: the array wrote $(ls array | wc -l) frames" >&2; exit 1; }
  one=$(calc "$t1 - $t0"); array=$(calc "$t2 - $t1")
  local_s=$(calc "$t4 - $t2")
  part=$(calc "$t3 - $t4 - $one / $views")
  frames=$(calc "$(stat -c %.9Y array/*.png | sort -g | tail -n 1) - $t1")
  echo "$one" >>one.txt; echo "$array" >>array.txt; echo "$frames" >>frames.txt; echo "$local_s" >>local.txt; echo "$part" >>part.txt
  printf '{"round":%d,"views":%d,"size":"%s","depth":%d,"tasks":%d,"one_s":%.2f,"array_s":%.2f,"array_frames_s":%.2f,"local_s":%.2f,"part_overhead_s":%.2f}\n' \
    "$r" "$views" "$size" "$depth" "$tasks" "$one" "$array" "$frames" "$local_s" "$part"
done
one=$(median <one.txt); array=$(median <array.txt); frames=$(median <frames.txt); local_s=$(median <local.txt); part=$(median <part.txt)
{
  printf 'bench_slurm: %d-view turntable of %s, depth %d, %s, %d round(s), %d CPUs, medians\n' \
    "$views" "$(basename "$mesh")" "$depth" "$size" "$rounds" "$(nproc)"
  printf '  one process          %8.2f s\n' "$one"
  printf '  %d-task array         %8.2f s   (%.2fx the one process)\n' "$tasks" "$array" "$(calc "$array / $one")"
  printf '  its frames in place %8.2f s   (%.2fx the one process)\n' "$frames" "$(calc "$frames / $one")"
  printf '  %d local processes   %8.2f s   (%.2fx the one process)\n' "$tasks" "$local_s" "$(calc "$local_s / $one")"
  printf '  per-task overhead    %8.2f s   (start-up + framing, = %.1f frames)\n' "$part" "$(calc "$part / ($one / $views)")"
} >&2
