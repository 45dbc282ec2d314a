#!/usr/bin/env bash
# What the view-adaptive frame costs against the cost of shading its pixels (docs/benchmarks.md,
# "Rates from the screen-space error"): per model, limn-render --bench with
#   default   the error-driven rates (--max-error 0.25, --edge-pixels 32)
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
# Usage: bench/render/error_rates.sh [-s 1920x1080] [-n 4] [-f 10] [-r 3] [-m "quad_sphere spot car"]
#        [-c "default old coarse"] [-e "0.25"] [-u]
# (tools in build/bin, or $LIMN_BIN)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${LIMN_BIN:-$here/../../build/bin}
data=$here/../../tests/data
size=1920x1080 samples=4 frames=10 rounds=3 models="quad_sphere spot car" configs="default old coarse" errors=""
cputime=0
while getopts "s:n:f:r:m:c:e:u" o; do
  case $o in
    s) size=$OPTARG ;; n) samples=$OPTARG ;; f) frames=$OPTARG ;; r) rounds=$OPTARG ;; m) models=$OPTARG ;;
    c) configs=$OPTARG ;; e) errors=$OPTARG ;; u) cputime=1 ;; *) exit 2 ;;
  esac
done
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
for e in $errors; do args[e$e]="--max-error $e"; configs="$configs e$e"; done
case " $configs " in *" coarse "*) ;; *) configs="$configs coarse" ;; esac # the ratios' base
for r in $(seq "$rounds"); do
  for m in $models; do
    for c in $configs; do
      # shellcheck disable=SC2086
      line=$("$bin/limn-render" "$tmp/$m.limn" --size "$size" --samples "$samples" --bench "$frames" ${args[$c]})
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
python3 - "$tmp" "$models" "$configs" "$cputime" <<'EOF' >&2
import json, statistics, sys
tmp, models, configs = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
key = 'cpu_time_ms' if sys.argv[4] == '1' else 'cpu_ms'
cov = {j['model']: j['covered'] for j in map(json.loads, open(tmp + '/covered.jsonl'))}
runs = [json.loads(l) for l in open(tmp + '/all.jsonl')]
print('%-12s %-8s %9s %9s %12s %10s %12s' % ('model', 'config', key, 'gpu_ms', 'cpu/coarse', 'triangles', 'tri/covered'))
for m in models:
    med = {c: statistics.median(r[key] for r in runs if r['model'] == m and r['config'] == c) for c in configs}
    for c in configs:
        rs = [r for r in runs if r['model'] == m and r['config'] == c]
        gpu = statistics.median(r['gpu_ms']['total'] for r in rs)
        tri = rs[-1]['triangles']
        print('%-12s %-8s %9.1f %9.1f %12.2f %10d %12.3f' % (m, c, med[c], gpu, med[c] / med['coarse'], tri, tri / cov[m]))
EOF
