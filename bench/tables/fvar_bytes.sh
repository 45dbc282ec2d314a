#!/usr/bin/env bash
# FVSF bytes (the smooth face-varying UV surface, formats/limn.md section 9) and limn-tables
# instructions with and without the irregular faces' surface (--irregular-levels 0 / K), per mesh
# and depth, with smooth UVs under rule RULE (default corners-only). One JSON object per line.
# Usage: bench/tables/fvar_bytes.sh [-K 6] [-F RULE] [-b OLD/limn-tables] [-I] [MESH:DEPTH ...]
#   -b: another build's limn-tables measured the same way ("before_*"; its chunks read by the
#   limn-info beside it, if any); -I: instructions each run executes (valgrind --tool=callgrind:
#   deterministic on a loaded machine), else wall seconds of one run. Tools in build/bin, or
#   $LIMN_BIN.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${LIMN_BIN:-$root/build/bin}
K=6 rule=corners-only before= count=
while getopts "K:F:b:I" o; do
  case $o in K) K=$OPTARG ;; F) rule=$OPTARG ;; b) before=$OPTARG ;; I) count=1 ;; *) exit 2 ;; esac
done
shift $((OPTIND - 1))
d=$root/tests/data
[ $# -gt 0 ] || set -- "$d/quad/spot_control_mesh.obj:3" "$d/tri/cube_no_bottom.obj:2" "$d/tri/cube_no_bottom.obj:3" \
  "$d/quad/blub_control_mesh.obj:3" "$d/tri/spot_triangulated.obj:3"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cost() { # instructions (or seconds) of one limn-tables run
  if [ -n "$count" ]; then
    GLIBC_TUNABLES=glibc.malloc.hugetlb=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 |
      sed -n 's/.*refs: *\([0-9,]*\).*/\1/p' | tr -d ,
  else
    local t0; t0=$(date +%s.%N); "$@" >/dev/null 2>&1; python3 -c "import sys; print(round($(date +%s.%N) - $t0, 4))"
  fi
}
# The chunk's bytes as the writing build's limn-info reads them (beside it, else in $bin): a
# layout can change between builds.
fvsf() { local info=$bin/limn-info; [ -x "$(dirname "$2")/limn-info" ] && info=$(dirname "$2")/limn-info
  "$info" --json "$1" | python3 -c 'import json,sys; print(sum(c["bytes"] for c in json.load(sys.stdin)["chunks"] if c["type"]=="FVSF"))'; }
for arg in "$@"; do
  mesh=${arg%:*} depth=${arg##*:} name=$(basename "${arg%:*}" .obj)
  "$bin/limn-classify" -q "$mesh" --fvar "$rule" -o "$tmp/c.limn"
  line="{\"mesh\": \"$name\", \"depth\": $depth, \"rule\": \"$rule\", \"irregular_levels\": $K"
  for tool in "$bin/limn-tables" ${before:+"$before"}; do
    prefix=; [ "$tool" = "$bin/limn-tables" ] || prefix=before_
    for k in 0 "$K"; do
      c=$(cost "$tool" -q --depth "$depth" --irregular-levels "$k" "$tmp/c.limn" -o "$tmp/t$k.limn")
      key=$([ "$k" = 0 ] && echo bilinear || echo surface)
      unit=seconds; [ -z "$count" ] || unit=instructions
      line+=", \"${prefix}fvsf_bytes_$key\": $(fvsf "$tmp/t$k.limn" "$tool"), \"${prefix}${unit}_$key\": $c"
    done
  done
  echo "$line}"
done
