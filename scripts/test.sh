#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (apt packages), builds limn and runs every test with CTest.
# Usage: scripts/test.sh [release|asan]      (the render tests run on Mesa lavapipe)
set -euo pipefail
cd "$(dirname "$0")/.."
kind=${1:-release}
scripts/setup.sh --tests
scripts/build.sh "$kind"
dir=build; [ "$kind" = asan ] && dir=build-asan
# Leak checking is off under ASan: Mesa's LLVM JIT keeps allocations alive until exit.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# The "heavy" tests (hundreds of renders checking crack-freedom) run in the release build; under
# ASan they would double the CI time and exercise no code the other render tests do not.
exclude=(); [ "$kind" = asan ] && exclude=(-LE heavy)
ctest --test-dir "$dir" --output-on-failure -j "$(nproc)" "${exclude[@]}"
