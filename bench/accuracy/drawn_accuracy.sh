#!/usr/bin/env bash
# What limn-render draws, against OpenSubdiv's limit (isolation 10, Gregory end caps), before and
# after the irregular faces' surface (docs/irregular.md): per mesh and depth, tables with
# --irregular-levels 0 (bilinear irregular faces, as before) and the default, each drawn with the
# view-adaptive tessellation (the default) and the fixed grids (--edge-pixels 0); every drawn
# vertex and every triangle's centroid through bench_accuracy --ply.
# Usage: bench/accuracy/drawn_accuracy.sh [-d "2 3"] [-s 320x240] [-m "adaptive fixed"] MESH...
# (tools in build/bin, or $LIMN_BIN)
set -euo pipefail
bin=${LIMN_BIN:-$(dirname "$0")/../../build/bin}
depths="2 3" size="" modes="adaptive fixed"
while getopts "d:s:m:" o; do
  case $o in d) depths=$OPTARG ;; s) size="--size $OPTARG" ;; m) modes=$OPTARG ;; *) exit 2 ;; esac
done
shift $((OPTIND - 1))
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
printf "%-26s %2s %-5s %-8s %9s %7s %9s %8s %9s\n" mesh d K tess vertices ">1e-5" "max dP" "max dN" centroid >&2
for mesh in "$@"; do
  name=$(basename "$mesh" .obj)
  "$bin/limn-classify" "$mesh" -o "$tmp/c.limn" 2>/dev/null || { echo "$name: refused" >&2; continue; }
  for d in $depths; do
    for K in 0 6; do
      "$bin/limn-tables" --depth "$d" --irregular-levels $K "$tmp/c.limn" -o "$tmp/t.limn" 2>/dev/null || continue
      for mode in $modes; do
        extra=""; [ $mode = fixed ] && extra="--edge-pixels 0"
        "$bin/limn-render" "$tmp/t.limn" $size $extra --mesh-out "$tmp/m.ply" -o "$tmp/i.png" 2>/dev/null || continue
        line=$("$bin/bench_accuracy" --ply "$tmp/m.ply" "$mesh" 2>/dev/null)
        echo "$line" | sed "s/^{/{\"depth\":$d,\"irregular_levels\":$K,\"tessellation\":\"$mode\",/"
        python3 -c 'import json,sys; j=json.loads(sys.argv[1]); print("%-26s %2s %-5s %-8s %9d %7d %9.2e %8.3g %9.2e" % (sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5], j["vertices"], j["vertices_off"], j["max_position_error"], j["max_normal_degrees"], j["max_centroid_error"]))' "$line" "$name" "$d" "$K" "$mode" >&2
      done
    done
  done
done
