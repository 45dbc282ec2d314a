#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (apt packages), builds limn and runs every test with CTest.
# Usage: scripts/test.sh [release|asan]      (the render tests run on Mesa lavapipe)
set -euo pipefail
cd "$(dirname "$0")/.."
kind=${1:-release}
scripts/setup.sh --tests
target=(); [ "$kind" = asan ] && target=(limn_sanitizer_suite)
scripts/build.sh "$kind" "${target[@]}"
dir=build; [ "$kind" = asan ] && dir=build-asan
# Leak checking is off under ASan: Mesa's LLVM JIT keeps allocations alive until exit.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# The GPU render tests (labels render and heavy: hundreds of renders on lavapipe) run in the
# release build only; under the sanitizers their executables are not built (CMakeLists.txt,
# limn_sanitizer_suite; CTest lists them as *_NOT_BUILT) and their CPU code runs through the
# tools in the CLI tests.
exclude=(); [ "$kind" = asan ] && exclude=(-LE '^(heavy|render|slurm)$' -E '_NOT_BUILT$')
# Every test has a TIMEOUT (600 s; the slowest takes well under a minute): a hang fails instead
# of holding the run, a test that timed out runs once more (CTest says so in its log), and the
# watchdog in each GoogleTest executable has printed the hung test's backtraces by then.
ctest --test-dir "$dir" --output-on-failure -j "$(nproc)" --timeout 600 --repeat after-timeout:2 \
  "${exclude[@]}"

# The WebGPU runtime (web/): node --test, on Dawn over the private Mesa 25 of setup.sh --tests,
# in the release run only (its image tests compare with build/'s limn-render). Each node suite
# is bounded (about 2-3 minutes here): a hang fails with timeout's 124 instead of holding CI.
if [ "$kind" = release ]; then
  LIMN_BUILD_DIR="$PWD/build" timeout -k 30 1200 node --test web/test/*.test.mjs
fi

# The browser viewer (web/viewer): headless Chromium (WebGPU on SwiftShader) against build/'s
# limn-render, and limn-view; release run only, about 2 minutes (SwiftShader draws spot at
# depth 3 in ~3 s a frame). The test files by name: browser.mjs is a helper.
if [ "$kind" = release ]; then
  LIMN_BUILD_DIR="$PWD/build" timeout -k 30 1200 node --test web/viewer/test/*.test.mjs
fi
