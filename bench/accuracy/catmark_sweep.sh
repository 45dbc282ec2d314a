#!/usr/bin/env bash
# Every catmark shape limn accepts, spot and blub, against OpenSubdiv's limit (bench_accuracy
# --ply: every drawn vertex, its signed normal, and every triangle's centroid): default tables
# (--irregular-levels 6), depths 1 and 3, 64x64 and limn-render's default size, view-adaptive
# and fixed grids. One line per run: mesh, depth, size, tessellation, then bench_accuracy's JSON;
# meshes a tool refuses are named as such. About 10 minutes on two cores.
# Usage: bench/accuracy/catmark_sweep.sh [OUT]   (tools in build/bin, or $LIMN_BIN)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${LIMN_BIN:-$here/../../build/bin}
data=$here/../../tests/data
out=${1:-/dev/stdout}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for mesh in "$data"/osd/catmark/*.obj "$data"/quad/spot_control_mesh.obj "$data"/quad/blub_control_mesh.obj; do
  name=$(basename "$mesh" .obj)
  "$bin/limn-classify" "$mesh" -o "$tmp/c.limn" 2>/dev/null || { echo "$name refused by limn-classify"; continue; }
  for d in 1 3; do
    "$bin/limn-tables" --depth $d "$tmp/c.limn" -o "$tmp/t.limn" 2>/dev/null || { echo "$name d$d refused by limn-tables"; continue; }
    for size in 64x64 default; do
      for mode in adaptive fixed; do
        args=(); [ $size = default ] || args+=(--size $size); [ $mode = fixed ] && args+=(--edge-pixels 0)
        "$bin/limn-render" "$tmp/t.limn" "${args[@]}" --mesh-out "$tmp/m.ply" -o "$tmp/i.png" 2>/dev/null || { echo "$name d$d $size $mode: limn-render failed"; continue; }
        echo "$name d$d $size $mode $("$bin/bench_accuracy" --ply "$tmp/m.ply" "$mesh" 2>/dev/null)"
      done
    done
  done
done >"$out"
