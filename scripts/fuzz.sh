#!/usr/bin/env bash
# Builds the libFuzzer targets (clang + ASan) and runs each for SECONDS (default 60), starting
# from the seed corpus in fuzz/corpus/<target>/. Any crash fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
scripts/setup.sh
scripts/build.sh fuzz
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
status=0
for target in build-fuzz/bin/fuzz_*; do
  [ -x "$target" ] || continue
  name=$(basename "$target")
  work=$(mktemp -d)
  cp -r "fuzz/corpus/${name#fuzz_}/." "$work/" 2>/dev/null || true
  echo "fuzz: $name for ${seconds}s"
  if ! "$target" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 "$work" \
       > "$work.log" 2>&1; then
    tail -40 "$work.log"; status=1
  else
    grep -E "^Done|#[0-9]+.*DONE" "$work.log" | tail -1 || true
  fi
  rm -rf "$work" "$work.log"
done
exit $status
