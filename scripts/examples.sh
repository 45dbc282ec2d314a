#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds limn and runs the main job: generates the built-in
# example meshes and runs them through the pipeline (Makefile.examples); results go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh release
make -s -f Makefile.examples BIN=build/bin OUT=out -j "$(nproc)"
