#!/usr/bin/env bash
# Installs the Debian 12 packages limn builds and tests with. Idempotent: prints nothing and
# touches nothing when every package is already installed. Uses sudo when not root.
set -euo pipefail

packages=(
  # build
  cmake ninja-build g++ pkg-config
  # Makefile.examples (scripts/examples.sh and its test); cmake only recommends it
  make
  # libraries the users chose (see ../shared/docs/toolchain.md)
  libopenmesh-dev libosd-dev libglm-dev libopenimageio-dev libtinygltf-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  glslang-tools glslang-dev spirv-tools
  # PNG encoding/decoding of our own (lib/image); OpenImageIO pulls it in too, named for clarity
  zlib1g-dev
  # tests, benchmarks, fuzzers
  libgtest-dev libgmock-dev libbenchmark-dev clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = installed ] || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "setup: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >/dev/null
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
