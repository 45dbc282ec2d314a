#!/usr/bin/env bash
# What per-configuration bases for decaying-crease faces would save (lib/subdiv/crease_basis.h,
# docs/irregular-tables.md "Decaying-crease configurations"): per mesh and depth, the TBLS bytes and the
# instructions (valgrind --tool=callgrind, deterministic) of building and encoding the tables
# without the irregular faces' levels (K = 0), with them (K), and with K but the faces that have
# a chain not refined, their chains' programs and supports added as estimated bytes. One JSON
# object per line on stdout, a readable table on stderr.
# Usage: bench/tables/crease_bases.sh [-K 6] [-I] [MESH:DEPTH ...]   (tools in build/bin or $LIMN_BIN)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${LIMN_BIN:-$root/build/bin}
K=6 count=
while getopts "K:I" o; do
  case $o in K) K=$OPTARG ;; I) count=1 ;; *) exit 2 ;; esac
done
shift $((OPTIND - 1))
c=$root/tests/data/osd/catmark
[ $# -gt 0 ] || set -- "$c/catmark_car.obj:3" "$c/catmark_rook.obj:2" "$c/catmark_rook.obj:3" \
  "$c/catmark_chaikin0.obj:2" "$c/catmark_chaikin1.obj:2" "$c/catmark_cubes_semisharp.obj:2"
instructions() {
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null |
    sed -n 's/.*refs: *\([0-9,]*\).*/\1/p' | tr -d ,
}
printf "%-24s %2s %10s %10s %10s %7s %7s %9s %9s %9s %7s %7s\n" mesh d "B K=0" "B K=$K" "B chains" \
  "K/0" "ch/0" "Mi K=0" "Mi K=$K" "Mi ch" "K/0" "ch/0" >&2
for arg in "$@"; do
  lines=()
  for mode in k0 k chains; do
    json=$("$bin/bench_crease_bases" -K "$K" -E "$mode" "$arg")
    ins=0
    [ -z "$count" ] || ins=$(instructions "$bin/bench_crease_bases" -K "$K" -E "$mode" "$arg")
    lines+=("$json" "$ins")
  done
  python3 - "${lines[@]}" <<'PY'
import json, sys
a = sys.argv[1:]
r = [(json.loads(a[i]), int(a[i + 1])) for i in range(0, 6, 2)]
(k0, i0), (k, ik), (ch, ic) = r
out = {"mesh": k0["mesh"], "depth": k0["depth"], "K": k["K"], "bytes_k0": k0["total_bytes"],
       "bytes_k": k["total_bytes"], "bytes_chains": ch["total_bytes"], "chain_faces": ch["chain_faces"],
       "chains": ch["chains"], "band_programs": ch["band_programs"], "program_bytes": ch["program_bytes"],
       "face_bytes": ch["face_bytes"], "instructions_k0": i0, "instructions_k": ik, "instructions_chains": ic}
print(json.dumps(out))
m = lambda x: x / 1e6
rat = lambda x, y: x / y if y else float("nan")
print("%-24s %2d %10d %10d %10d %7.3f %7.3f %9.1f %9.1f %9.1f %7.3f %7.3f" % (
    k0["mesh"], k0["depth"], k0["total_bytes"], k["total_bytes"], ch["total_bytes"],
    rat(k["total_bytes"], k0["total_bytes"]), rat(ch["total_bytes"], k0["total_bytes"]),
    m(i0), m(ik), m(ic), rat(ik, i0), rat(ic, i0)), file=sys.stderr)
PY
done
