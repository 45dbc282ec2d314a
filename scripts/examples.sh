#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds limn and runs the main job: generates the built-in
# example meshes, runs them through every pipeline and renders them (Makefile.examples); results
# go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
# Only the tools: the tests and benchmarks are scripts/test.sh's business.
scripts/build.sh release limn_tools
make -s -f Makefile.examples BIN=build/bin OUT=out -j "$(nproc)"
n=$(make -s -f Makefile.examples BIN=build/bin OUT=out list | wc -l)
echo "$n images in out/ (make -f Makefile.examples list names them)"
