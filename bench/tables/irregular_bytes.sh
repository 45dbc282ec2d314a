#!/usr/bin/env bash
# TBLS bytes and limn-tables wall time with the irregular faces' surface (docs/irregular.md)
# against the bilinear faces of before (--irregular-levels 0), per mesh and depth. One JSON object
# per line on stdout, a readable table on stderr. The bytes are exact; the times are wall-clock
# medians of R interleaved runs (K = 0, K, K = 0, ...; the machine is shared and noisy).
# Usage: bench/tables/irregular_bytes.sh [-K 6] [-R 3] [MESH:DEPTH ...]   (tools in build/bin, or $LIMN_BIN)
# Without arguments: the meshes of docs/irregular.md's table.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${LIMN_BIN:-$root/build/bin}
K=6 R=3
while getopts "K:R:" o; do case $o in K) K=$OPTARG ;; R) R=$OPTARG ;; *) exit 2 ;; esac; done
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
  times=()
  for ((i = 0; i < R; ++i)); do
    t0=$(date +%s.%N); "$bin/limn-tables" -q --depth "$d" --irregular-levels 0 "$tmp/c.limn" -o "$tmp/t0.limn"
    t1=$(date +%s.%N); "$bin/limn-tables" -q --depth "$d" --irregular-levels "$K" "$tmp/c.limn" -o "$tmp/tk.limn"
    t2=$(date +%s.%N); times+=("$t0,$t1,$t2")
  done
  b0=$(bytes "$tmp/t0.limn") bk=$(bytes "$tmp/tk.limn")
  python3 - "$name" "$d" "$K" "$b0" "$bk" "${times[@]}" <<'PY'
import json, statistics, sys
name, d, K, b0, bk = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
runs = [list(map(float, r.split(","))) for r in sys.argv[6:]]
s0 = statistics.median(t1 - t0 for t0, t1, _ in runs)
sk = statistics.median(t2 - t1 for _, t1, t2 in runs)
print(json.dumps({"mesh": name, "depth": d, "irregular_levels": K, "bytes_bilinear": b0, "bytes": bk,
                  "ratio": round(bk / b0, 4), "seconds_bilinear": round(s0, 3), "seconds": round(sk, 3)}))
print("%-22s %2d %12d %12d %8.3f %8.2f %8.2f" % (name, d, b0, bk, bk / b0, s0, sk), file=sys.stderr)
PY
done
