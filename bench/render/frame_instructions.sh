#!/usr/bin/env bash
# Instructions a frame costs with the irregular faces' surface (docs/irregular.md) against the
# bilinear faces of before (--irregular-levels 0): `bench_render --view-adaptive --irregular`
# (spot d3 and d6, the car d3, the paper's sphere d6; its views, sizes and default view-adaptive
# mode) under `valgrind --tool=callgrind --instr-atstart=no`. bench_render switches the counting on
# for each configuration's measured frames only (after two warm-up frames: the LLVM JIT compiles
# lavapipe's shaders there, and table building and start-up are never counted) and dumps them
# under the configuration's label; this script divides by the frames. Instructions of every
# thread (the main thread's compute passes and vertex stage, lavapipe's rasterizer threads, their
# JIT-compiled code included) do not move with the load of a shared machine the way wall and CPU
# time do (two repeats agree within 0.1%: docs/irregular-measurements.md "Frame time"). They are not time: a
# cache miss or a long division counts as one. Runs one process at a time (each frame about 130x
# slower than natively: about 12 minutes a repeat at -f 2).
#
# Usage: bench/render/frame_instructions.sh [-f FRAMES] [-r REPEATS] [-b BENCH_RENDER] [-k DIR]
#        [-t SECONDS] [-- BENCH_ARGS...]
#   -f frames counted per configuration (default 2); -r repeats of the whole run (default 1; 2
#   shows the spread); -b another build's bench_render (default build/bin's); -k keep the callgrind
#   dumps in DIR (callgrind_annotate them to see which functions grew); -t per-run timeout
#   (default 3600 s). BENCH_ARGS default to spot and the car of tests/data plus `--rounds 1
#   --orbit 0`; e.g. `-- --only sphere` for the sphere alone.
# Output: one JSON object per line on stdout, per repeat and configuration
#   {"bench":"frame_instructions","repeat":R,"model":...,"tables":"adaptive"|"bilinear",
#    "depth":D,"frames":F,"instructions_per_frame":N,"triangles":T}
# and per model and depth {"bench":"frame_instructions_ratio",...,"ratio":adaptive/bilinear,
#   "triangles_ratio":...}; a readable table on stderr.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bench=${LIMN_BIN:-$root/build/bin}/bench_render
frames=2 repeats=1 keep='' limit=3600
while getopts "f:r:b:k:t:" o; do
  case $o in f) frames=$OPTARG ;; r) repeats=$OPTARG ;; b) bench=$OPTARG ;; k) keep=$OPTARG ;;
    t) limit=$OPTARG ;; *) echo "usage: $0 [-f FRAMES] [-r REPEATS] [-b BENCH_RENDER] [-k DIR] [-t S] [-- ARGS]" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
command -v valgrind >/dev/null || { echo "frame_instructions.sh: valgrind is not installed" >&2; exit 3; }
[ -x "$bench" ] || { echo "frame_instructions.sh: no $bench (build the bench_render target)" >&2; exit 1; }
extra=("$@")
mesh_args=("$root/tests/data/quad/spot_control_mesh.obj" "$root/tests/data/osd/catmark/catmark_car.obj")
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for ((rep = 0; rep < repeats; ++rep)); do
  dir=$tmp/r$rep; mkdir -p "$dir"
  if ! timeout "$limit" valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$dir/cg.%p" \
      "$bench" --view-adaptive --irregular --rounds 1 --orbit 0 --frames "$frames" "${mesh_args[@]}" \
      "${extra[@]}" >"$dir/bench.json" 2>"$dir/bench.err"; then
    echo "frame_instructions.sh: bench_render failed or timed out (repeat $rep):" >&2
    grep -v '^==' "$dir/bench.err" | tail -5 >&2
    exit 1
  fi
  if [ -n "$keep" ]; then mkdir -p "$keep/r$rep"; cp "$dir"/cg.* "$dir/bench.json" "$keep/r$rep/"; fi
done
python3 - "$tmp" "$repeats" "$frames" <<'EOF'
import glob, json, os, re, sys
tmp, repeats, frames = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
rows = {}
for rep in range(repeats):
    d = os.path.join(tmp, "r%d" % rep)
    tri = {}
    for line in open(os.path.join(d, "bench.json")):
        j = json.loads(line)
        if j.get("bench") == "view_adaptive" and "triangles" in j:
            tri[(j["model"], j["tables"], j["depth"])] = j["triangles"]
    dumps = glob.glob(os.path.join(d, "cg.*.*"))  # in the order bench_render ran them
    for f in sorted(dumps, key=lambda f: int(f.rsplit(".", 1)[1])):
        text = open(f, errors="replace").read()
        m = re.search(r"^desc: Trigger: Client Request: frames (\S+) (\S+) (\d+) \d+$", text, re.M)
        t = re.search(r"^totals: (\d+)", text, re.M)
        if not m or not t: continue
        key = (m.group(1), m.group(2), int(m.group(3)))
        ipf = int(t.group(1)) / frames
        rows[(rep,) + key] = ipf
        print(json.dumps({"bench": "frame_instructions", "repeat": rep, "model": key[0], "tables": key[1],
                          "depth": key[2], "frames": frames, "instructions_per_frame": round(ipf),
                          "triangles": tri.get(key)}))
    for (r, model, tables, depth), ipf in sorted(rows.items()):
        if r != rep or tables != "adaptive" or (rep, model, "bilinear", depth) not in rows: continue
        base = rows[(rep, model, "bilinear", depth)]
        ta, tb = tri.get((model, "adaptive", depth)), tri.get((model, "bilinear", depth))
        print(json.dumps({"bench": "frame_instructions_ratio", "repeat": rep, "model": model, "depth": depth,
                          "adaptive_instructions_per_frame": round(ipf), "bilinear_instructions_per_frame": round(base),
                          "ratio": round(ipf / base, 4),
                          "triangles_ratio": round(ta / tb, 4) if ta and tb else None}))
        print("repeat %d  %-18s d%d  Minstr/frame irregular %9.1f  bilinear %9.1f  ratio %.4f  triangles %s / %s"
              % (rep, model, depth, ipf / 1e6, base / 1e6, ipf / base, ta, tb), file=sys.stderr)
EOF
