#!/usr/bin/env bash
# TBLS bytes and limn-tables wall time with the irregular faces' surface (docs/irregular.md)
# against the bilinear faces of before (--irregular-levels 0), per mesh and depth. One JSON object
# per line on stdout, a readable table on stderr. The bytes are exact; the times are one run each.
# Usage: bench/tables/irregular_bytes.sh [-K 6] [MESH:DEPTH ...]   (tools in build/bin, or $LIMN_BIN)
# Without arguments: the meshes of docs/irregular.md's table.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${LIMN_BIN:-$root/build/bin}
K=6
while getopts "K:" o; do case $o in K) K=$OPTARG ;; *) exit 2 ;; esac; done
shift $((OPTIND - 1))
[ $# -gt 0 ] || set -- "$root/tests/data/quad/spot_control_mesh.obj:3" "$root/tests/data/quad/spot_control_mesh.obj:6" \
  "$root/tests/data/osd/catmark/catmark_car.obj:3" "$root/tests/data/osd/catmark/catmark_smoothtris0.obj:2" \
  "$root/tests/data/tri/spot_triangulated.obj:3" "$root/tests/data/quad/blub_control_mesh.obj:3"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
bytes() { "$bin/limn-info" --json "$1" | python3 -c 'import json,sys; print([c["bytes"] for c in json.load(sys.stdin)["chunks"] if c["type"]=="TBLS"][0])'; }
printf "%-22s %2s %12s %12s %8s %8s %8s\n" mesh d "bytes K=0" "bytes K=$K" ratio "s K=0" "s K=$K" >&2
for arg in "$@"; do
  mesh=${arg%:*} d=${arg##*:} name=$(basename "${arg%:*}" .obj)
  "$bin/limn-classify" "$mesh" -o "$tmp/c.limn"
  t0=$(date +%s.%N); "$bin/limn-tables" -q --depth "$d" --irregular-levels 0 "$tmp/c.limn" -o "$tmp/t0.limn"
  t1=$(date +%s.%N); "$bin/limn-tables" -q --depth "$d" --irregular-levels "$K" "$tmp/c.limn" -o "$tmp/tk.limn"
  t2=$(date +%s.%N)
  b0=$(bytes "$tmp/t0.limn") bk=$(bytes "$tmp/tk.limn")
  python3 - "$name" "$d" "$K" "$b0" "$bk" "$t0" "$t1" "$t2" <<'PY'
import json, sys
name, d, K, b0, bk, t0, t1, t2 = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5]), *map(float, sys.argv[6:9])
print(json.dumps({"mesh": name, "depth": d, "irregular_levels": K, "bytes_bilinear": b0, "bytes": bk,
                  "ratio": round(bk / b0, 4), "seconds_bilinear": round(t1 - t0, 3), "seconds": round(t2 - t1, 3)}))
print("%-22s %2d %12d %12d %8.3f %8.2f %8.2f" % (name, d, b0, bk, bk / b0, t1 - t0, t2 - t1), file=sys.stderr)
PY
done
