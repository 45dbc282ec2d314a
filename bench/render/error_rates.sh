#!/usr/bin/env bash
# What the view-adaptive frame costs against the cost of shading its pixels (docs/benchmarks.md,
# "Rates from the screen-space error"): per model, limn-render --bench with
#   default   the error-driven rates (--max-error 0.1, --edge-pixels 32)
#   old       the rule before them (--max-error 0 --edge-pixels 4: segments of about 4 px)
#   coarse    --edge-pixels 1000 --max-error 0 (about 2 triangles an element: the pixels' shading)
#   pixel     per-pixel limit normals and the interior at 1 px (--pixel-normals --interior-error 1)
#   eX        --max-error X (with -e "X ...": other error targets)
# interleaved in rounds (the machine is noisy and shared); one JSON line per run on stdout, and
# per model the median cpu_ms ratios default/coarse and old/coarse with triangles per covered
# pixel on stderr. Models: quad_sphere (limn-examples) at depth 3 with seams (README's pipeline),
# spot and catmark_car (tests/data) at depth 3.
# With -u the ratios are of CPU time (user + system, all threads) per frame instead of cpu_ms: a
# run of f + 1 frames less a run of 1 frame, over f (steadier than wall-clock time on a loaded
# machine; docs/adaptive.md); each JSON line then also has cpu_time_ms.
# With -I the ratios are of instructions per measured frame, all threads' (the queue's compute
# passes and vertex stage, lavapipe's rasterizer threads, their JIT-compiled code included), each
# run under `valgrind --tool=callgrind --instr-atstart=no`: runBenchmark (lib/render/bench.cpp)
# counts its measured frames only, not start-up or the warm-up frames where LLVM compiles the
# shaders. They do not move with the machine's load (a frame's count repeats within 0.01%, so -f
# defaults to 1 and -r to 1 there) but they are not time: a cache miss or a division counts as
# one instruction. Each run is about 50-130x slower than natively (minutes for the car at
# 1920x1080 with 4 samples); -t SECONDS bounds each (default 3600): a run that does not finish
# prints {"skipped":...} and the others go on. Each JSON line then also has
# instructions_per_frame.
# Usage: bench/render/error_rates.sh [-s 1920x1080] [-n 4] [-f 10] [-r 3] [-m "quad_sphere spot car"]
#        [-c "default old coarse"] [-e "0.25"] [-u | -I [-t SECONDS]]
# (tools in build/bin, or $LIMN_BIN)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${LIMN_BIN:-$here/../../build/bin}
data=$here/../../tests/data
size=1920x1080 samples=4 frames='' rounds='' models="quad_sphere spot car" configs="default old coarse" errors=""
cputime=0 instructions=0 limit=3600
while getopts "s:n:f:r:m:c:e:uIt:" o; do
  case $o in
    s) size=$OPTARG ;; n) samples=$OPTARG ;; f) frames=$OPTARG ;; r) rounds=$OPTARG ;; m) models=$OPTARG ;;
    c) configs=$OPTARG ;; e) errors=$OPTARG ;; u) cputime=1 ;; I) instructions=1 ;; t) limit=$OPTARG ;; *) exit 2 ;;
  esac
done
if [ "$instructions" = 1 ]; then
  [ "$cputime" = 0 ] || { echo "error_rates.sh: -u and -I measure differently; give one" >&2; exit 2; }
  command -v valgrind >/dev/null || { echo "error_rates.sh: -I needs valgrind (not installed)" >&2; exit 3; }
  frames=${frames:-1} rounds=${rounds:-1}
else
  frames=${frames:-10} rounds=${rounds:-3}
fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for m in $models; do
  case $m in
    quad_sphere) "$bin/limn-examples" --only quad_sphere -o "$tmp" >/dev/null; obj=$tmp/quad_sphere.obj ;;
    spot) obj=$data/quad/spot_control_mesh.obj ;;
    car) obj=$data/osd/catmark/catmark_car.obj ;;
    *) echo "unknown model $m" >&2; exit 2 ;;
  esac
  "$bin/limn-classify" "$obj" | "$bin/limn-tables" --depth 3 | "$bin/limn-seams" > "$tmp/$m.limn"
done
declare -A args=([default]="" [old]="--max-error 0 --edge-pixels 4" [coarse]="--max-error 0 --edge-pixels 1000"
  [pixel]="--pixel-normals --interior-error 1")
# CPU seconds (user + system) of one limn-render run.
cpu() { /usr/bin/time -f "%U %S" -o "$tmp/time" "$@" >/dev/null && awk '{print $1 + $2}' "$tmp/time"; }
# One limn-render --bench run under callgrind, its JSON line on stdout, the instructions it counted
# in $tmp/cg. The tools start themselves again with glibc.malloc.hugetlb=1 unless it is set
# (lib/base/cli_run.cpp), which valgrind would not follow: so it is set here.
counted() {
  local tunables=${GLIBC_TUNABLES:-}
  case $tunables in *glibc.malloc.hugetlb*) ;; *) tunables=${tunables:+$tunables:}glibc.malloc.hugetlb=1 ;; esac
  rm -f "$tmp/cg"
  GLIBC_TUNABLES=$tunables timeout "$limit" valgrind --tool=callgrind --instr-atstart=no \
    --callgrind-out-file="$tmp/cg" "$@" 2>"$tmp/valgrind.err"
}
for e in $errors; do args[e$e]="--max-error $e"; configs="$configs e$e"; done
case " $configs " in *" coarse "*) ;; *) configs="$configs coarse" ;; esac # the ratios' base
for r in $(seq "$rounds"); do
  for m in $models; do
    for c in $configs; do
      if [ "$instructions" = 1 ]; then
        # shellcheck disable=SC2086
        if ! line=$(counted "$bin/limn-render" "$tmp/$m.limn" --size "$size" --samples "$samples" --bench "$frames" ${args[$c]}) ||
          ! total=$(awk '/^totals:/ {print $2}' "$tmp/cg") || [ -z "$total" ]; then
          why="did not finish within $limit s"
          grep -q "limn-render: error" "$tmp/valgrind.err" && why=$(grep -m1 "limn-render: error" "$tmp/valgrind.err" | tr -d '"\\')
          echo "{\"model\":\"$m\",\"config\":\"$c\",\"round\":$r,\"size\":\"$size\",\"samples\":$samples,\"skipped\":\"$why\"}" | tee -a "$tmp/skipped.jsonl"
          continue
        fi
        line=$(echo "$line" | sed "s/^{/{\"instructions_per_frame\":$((total / frames)),/")
      else
        # shellcheck disable=SC2086
        line=$("$bin/limn-render" "$tmp/$m.limn" --size "$size" --samples "$samples" --bench "$frames" ${args[$c]})
      fi
      if [ "$cputime" = 1 ]; then
        # shellcheck disable=SC2086
        many=$(cpu "$bin/limn-render" "$tmp/$m.limn" --size "$size" --samples "$samples" --bench $((frames + 1)) ${args[$c]})
        # shellcheck disable=SC2086
        one=$(cpu "$bin/limn-render" "$tmp/$m.limn" --size "$size" --samples "$samples" --bench 1 ${args[$c]})
        line=$(echo "$line" | sed "s/^{/{\"cpu_time_ms\":$(awk -v a="$many" -v b="$one" -v f="$frames" 'BEGIN{printf "%.2f", (a - b) * 1000 / f}'),/")
      fi
      echo "$line" | sed "s/^{/{\"model\":\"$m\",\"config\":\"$c\",\"round\":$r,/" | tee -a "$tmp/all.jsonl"
    done
  done
done
# Covered pixels (web/test/compare.mjs: not the background), from one image per model, the
# default's (the tessellations cover the same pixels within their silhouettes' error).
for m in $models; do
  "$bin/limn-render" "$tmp/$m.limn" --size "$size" --samples 1 -o "$tmp/$m.png" 2>/dev/null
  node "$here/../../web/test/compare.mjs" "$tmp/$m.png" "$tmp/$m.png" | sed "s/^{/{\"model\":\"$m\",/" >> "$tmp/covered.jsonl"
done
touch "$tmp/all.jsonl"
python3 - "$tmp" "$models" "$configs" "$cputime$instructions" <<'EOF' >&2
import json, statistics, sys
tmp, models, configs = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
key = {'10': 'cpu_time_ms', '01': 'instructions_per_frame'}.get(sys.argv[4], 'cpu_ms')
cov = {j['model']: j['covered'] for j in map(json.loads, open(tmp + '/covered.jsonl'))}
runs = [json.loads(l) for l in open(tmp + '/all.jsonl')]
print('%-12s %-8s %14s %9s %12s %10s %12s' % ('model', 'config', 'Minstr/frame' if key == 'instructions_per_frame' else key,
                                             'gpu_ms', '/ coarse', 'triangles', 'tri/covered'))
scale = 1e-6 if key == 'instructions_per_frame' else 1
for m in models:
    med = {c: statistics.median(r[key] for r in rs) for c in configs
           for rs in [[r for r in runs if r['model'] == m and r['config'] == c]] if rs}
    for c in configs:
        rs = [r for r in runs if r['model'] == m and r['config'] == c]
        if not rs:
            print('%-12s %-8s %14s' % (m, c, 'skipped'))
            continue
        gpu = statistics.median(r['gpu_ms']['total'] for r in rs)
        tri = rs[-1]['triangles']
        ratio = '%12.2f' % (med[c] / med['coarse']) if 'coarse' in med else '%12s' % '-'
        print('%-12s %-8s %14.1f %9.1f %s %10d %12.3f' % (m, c, med[c] * scale, gpu, ratio, tri, tri / cov[m]))
EOF
