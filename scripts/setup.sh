#!/usr/bin/env bash
# Installs the Debian 12 packages limn builds and tests with; with --tests also node, npm and the
# test-only npm packages of tests/tools (the glTF validator), which scripts/test.sh needs and the
# examples do not. Idempotent: prints nothing and touches nothing when everything is installed.
# Uses sudo when not root. Usage: scripts/setup.sh [--tests]
set -euo pipefail

packages=(
  # build
  cmake ninja-build g++ pkg-config
  # Makefile.examples (scripts/examples.sh and its test); cmake only recommends it
  make
  # libraries the users chose (see ../shared/docs/toolchain.md)
  libopenmesh-dev libosd-dev libglm-dev libopenimageio-dev libtinygltf-dev
  # compressed glTF, each decoded by its own library (lib/mesh/gltf_draco.cpp, gltf_meshopt.cpp):
  # KHR_draco_mesh_compression and EXT_/KHR_meshopt_compression; nlohmann's JSON (tinygltf's
  # parser) reads the extensions before tinygltf 2.7, which refuses Draco's and meshopt's JSON
  libdraco-dev libmeshoptimizer-dev nlohmann-json3-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  glslang-tools glslang-dev spirv-tools
  # PNG encoding/decoding of our own (lib/image); OpenImageIO pulls it in too, named for clarity
  zlib1g-dev
  # tests, benchmarks, fuzzers
  libgtest-dev libgmock-dev libbenchmark-dev clang libclang-rt-14-dev
)
# node and npm run the Khronos glTF-Validator (npm package, below) that checks the glTF
# limn-render --mesh-out writes. Debian's nodejs and npm unless the commands are already there
# (NodeSource's nodejs bundles npm and conflicts with Debian's npm package).
tests=false
[ "${1:-}" = --tests ] && tests=true
if $tests; then
  command -v node >/dev/null && command -v npm >/dev/null || packages+=(nodejs npm)
fi

# Test-only npm packages, pinned by tests/tools/package-lock.json, into tests/tools/node_modules
# (ignored by git). Idempotent: skipped when the lock installed last (a copy in node_modules)
# matches the committed one.
npm_tools() {
  $tests || return 0
  local dir
  dir="$(cd "$(dirname "$0")/.." && pwd)/tests/tools"
  if ! cmp -s "$dir/package-lock.json" "$dir/node_modules/.limn-installed-lock.json"; then
    echo "setup: npm ci in tests/tools (gltf-validator)" >&2
    # Not fatal: without the registry everything else still builds and runs, and the glTF
    # validation test fails saying the validator is missing.
    # npm's own reason is kept for the warning (a proxy's certificate, no route to the registry).
    local log
    log=$(mktemp)
    if (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null 2>"$log"); then
      cp "$dir/package-lock.json" "$dir/node_modules/.limn-installed-lock.json"
    else
      echo "setup: warning: npm ci failed; the glTF-Validator test will fail until it succeeds:" >&2
      grep -m 2 -E "code |reason" "$log" | sed "s/^/  /" >&2 || true
    fi
    rm -f "$log"
  fi
}

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = installed ] || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  npm_tools
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "setup: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >/dev/null
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
npm_tools
