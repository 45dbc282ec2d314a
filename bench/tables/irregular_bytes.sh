#!/usr/bin/env bash
# TBLS bytes and limn-tables wall time with the irregular faces' surface (docs/irregular.md)
# against the bilinear faces of before (--irregular-levels 0), per mesh and depth. One JSON object
# per line on stdout, a readable table on stderr. The bytes are exact; the times are wall-clock
# medians of R interleaved runs (K = 0, K, K = 0, ...; the machine is shared and noisy).
# Usage: bench/tables/irregular_bytes.sh [-K 6] [-R 3] [-b BIN] [-a ARGS] [-I] [MESH:DEPTH ...]
#   (tools in build/bin, or $LIMN_BIN). -b BIN: another build's limn-tables (e.g. of an earlier
#   commit), timed in the same interleaved runs: "before_seconds*" and "before_bytes*" in the
#   JSON; -a ARGS: more arguments for it (e.g. -b build/bin/limn-tables -a "--boundary-bases
#   off": this build without an option). -I: also the
#   instructions each run executes (valgrind --tool=callgrind, one run each: deterministic, where
#   wall times on a loaded machine are not): "instructions*" in the JSON, millions on stderr.
# Without arguments: the meshes of docs/irregular.md's table.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${LIMN_BIN:-$root/build/bin}
K=6 R=3 before='' count=''
beforeArgs=()
while getopts "K:R:b:a:I" o; do
  case $o in K) K=$OPTARG ;; R) R=$OPTARG ;; b) before=$OPTARG ;; a) read -ra beforeArgs <<<"$OPTARG" ;;
    I) count=1 ;; *) exit 2 ;; esac
done
shift $((OPTIND - 1))
[ $# -gt 0 ] || set -- "$root/tests/data/quad/spot_control_mesh.obj:3" "$root/tests/data/quad/spot_control_mesh.obj:6" \
  "$root/tests/data/osd/catmark/catmark_car.obj:3" "$root/tests/data/osd/catmark/catmark_smoothtris0.obj:2" \
  "$root/tests/data/tri/spot_triangulated.obj:3" "$root/tests/data/quad/blub_control_mesh.obj:3"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# Instructions of one limn-tables run (the tunable set so that the tool does not start itself
# again with it, which callgrind would not follow: lib/base/cli.cpp, preferHugePages).
instructions() {
  GLIBC_TUNABLES=glibc.malloc.hugetlb=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 |
    sed -n 's/.*refs: *\([0-9,]*\).*/\1/p' | tr -d ,
}
bytes() { "$bin/limn-info" --json "$1" | python3 -c 'import json,sys; print([c["bytes"] for c in json.load(sys.stdin)["chunks"] if c["type"]=="TBLS"][0])'; }
printf "%-22s %2s %12s %12s %8s %8s %8s%s\n" mesh d "bytes K=0" "bytes K=$K" ratio "s K=0" "s K=$K" \
  "${before:+  before: s K=0  s K=$K}" >&2
for arg in "$@"; do
  mesh=${arg%:*} d=${arg##*:} name=$(basename "${arg%:*}" .obj)
  "$bin/limn-classify" "$mesh" -o "$tmp/c.limn"
  times=()
  for ((i = 0; i < R; ++i)); do
    t0=$(date +%s.%N); "$bin/limn-tables" -q --depth "$d" --irregular-levels 0 "$tmp/c.limn" -o "$tmp/t0.limn"
    t1=$(date +%s.%N); "$bin/limn-tables" -q --depth "$d" --irregular-levels "$K" "$tmp/c.limn" -o "$tmp/tk.limn"
    t2=$(date +%s.%N); t3=$t2 t4=$t2
    if [ -n "$before" ]; then
      "$before" "${beforeArgs[@]}" -q --depth "$d" --irregular-levels 0 "$tmp/c.limn" -o "$tmp/b0.limn"
      t3=$(date +%s.%N); "$before" "${beforeArgs[@]}" -q --depth "$d" --irregular-levels "$K" "$tmp/c.limn" -o "$tmp/bk.limn"
      t4=$(date +%s.%N)
    fi
    times+=("$t0,$t1,$t2,$t3,$t4")
  done
  b0=$(bytes "$tmp/t0.limn") bk=$(bytes "$tmp/tk.limn") before_bytes=
  [ -z "$before" ] || before_bytes="$(bytes "$tmp/b0.limn"),$(bytes "$tmp/bk.limn")"
  counts=""
  if [ -n "$count" ]; then
    for k in 0 "$K"; do
      counts+="$(instructions "$bin/limn-tables" -q --depth "$d" --irregular-levels "$k" "$tmp/c.limn" -o "$tmp/i.limn"),"
    done
    for k in ${before:+0 "$K"}; do
      counts+="$(instructions "$before" "${beforeArgs[@]}" -q --depth "$d" --irregular-levels "$k" "$tmp/c.limn" -o "$tmp/i.limn"),"
    done
  fi
  python3 - "$name" "$d" "$K" "$b0" "$bk" "${before:+1}" "$counts" "$before_bytes" "${times[@]}" <<'PY'
import json, statistics, sys
name, d, K, b0, bk = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
counts = [int(c) for c in sys.argv[7].split(",") if c]
before_bytes = [int(c) for c in sys.argv[8].split(",") if c]
runs = [list(map(float, r.split(","))) for r in sys.argv[9:]]
s0 = statistics.median(r[1] - r[0] for r in runs)
sk = statistics.median(r[2] - r[1] for r in runs)
out = {"mesh": name, "depth": d, "irregular_levels": K, "bytes_bilinear": b0, "bytes": bk,
       "ratio": round(bk / b0, 4), "seconds_bilinear": round(s0, 4), "seconds": round(sk, 4)}
line = "%-22s %2d %12d %12d %8.3f %8.3f %8.3f" % (name, d, b0, bk, bk / b0, s0, sk)
if sys.argv[6]:
    out["before_seconds_bilinear"] = round(statistics.median(r[3] - r[2] for r in runs), 4)
    out["before_seconds"] = round(statistics.median(r[4] - r[3] for r in runs), 4)
    line += "  %8.3f %8.3f" % (out["before_seconds_bilinear"], out["before_seconds"])
    out["before_bytes_bilinear"], out["before_bytes"] = before_bytes
    line += "  before bytes %d %d (%.3f)" % (before_bytes[0], before_bytes[1], before_bytes[1] / before_bytes[0])
if counts:
    out["instructions_bilinear"], out["instructions"] = counts[0], counts[1]
    line += "  instructions (M) K=0 %.1f K=%d %.1f" % (counts[0] / 1e6, K, counts[1] / 1e6)
    if len(counts) == 4:
        out["before_instructions_bilinear"], out["before_instructions"] = counts[2], counts[3]
        line += ", before %.1f %.1f" % (counts[2] / 1e6, counts[3] / 1e6)
print(json.dumps(out))
print(line, file=sys.stderr)
PY
done
