#!/usr/bin/env bash
# Installs the Debian 12 packages limn builds and tests with; with --tests also node, npm and the
# test-only npm packages of tests/tools (the glTF validator), and Slurm and munge (the cluster
# test), which scripts/test.sh needs and the examples do not. Idempotent: prints nothing and
# touches nothing when everything is installed.
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
  # The Slurm test (tests/slurm) starts a one-node cluster of its own: the daemons and the client
  # commands, and munge for their authentication. The test runs them from a private folder; the
  # packages' own services are not used.
  packages+=(slurm-wlm munge)
  # The browser viewer's tests (web/viewer/test): Debian's chromium, whose WebGPU runs headless
  # on SwiftShader; playwright-core (below) drives it, never downloading a browser of its own.
  packages+=(chromium)
  # The tests' watchdog (tests/support/test_watchdog.cpp) prints a hung test's backtraces with gdb.
  packages+=(gdb)
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

# The WebGPU runtime's tests (web/): its npm packages, pinned by web/package-lock.json, into
# web/node_modules, and Mesa 25's lavapipe unpacked privately into web/.mesa (both ignored by
# git). Dawn (npm `webgpu`) refuses Debian 12's Mesa 22.3 over Vulkan; Mesa 25.0.7 comes from
# bookworm-backports with apt-get download into a private apt state, never installed system-wide
# (limn's own GPU tests and reference images are made on Debian's Mesa). Idempotent like
# npm_tools; not fatal: without them the web tests fail saying what is missing.
web_tools() {
  $tests || return 0
  local dir
  dir="$(cd "$(dirname "$0")/.." && pwd)/web"
  if ! cmp -s "$dir/package-lock.json" "$dir/node_modules/.limn-installed-lock.json"; then
    echo "setup: npm ci in web (webgpu, naga-wasm, pngjs)" >&2
    if (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null 2>&1); then
      cp "$dir/package-lock.json" "$dir/node_modules/.limn-installed-lock.json"
    else
      echo "setup: warning: npm ci in web failed; the web tests will fail until it succeeds" >&2
    fi
  fi
  local m="$dir/.mesa" lib="usr/lib/x86_64-linux-gnu/libvulkan_lvp.so"
  # The ICD file names the library by absolute path: a checkout moved or copied elsewhere (a
  # worktree made from another's folder) kept one naming the old place, and Dawn found no driver.
  if [ -f "$m/root/$lib" ]; then
    grep -qF "\"$m/root/$lib\"" "$m/icd.json" 2>/dev/null && return 0
    printf '{"file_format_version":"1.0.1","ICD":{"library_path":"%s","api_version":"1.4.305"}}\n' \
      "$m/root/$lib" > "$m/icd.json"
    return 0
  fi
  echo "setup: Mesa 25 lavapipe from bookworm-backports into web/.mesa (private)" >&2
  rm -rf "$m" && mkdir -p "$m/lists/partial" "$m/debs"
  local mirror
  mirror=$(sed -n 's/^URIs: *//p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -1)
  echo "deb ${mirror:-http://deb.debian.org/debian} bookworm-backports main" > "$m/sources.list"
  local a=(-o "Dir::Etc::SourceList=$m/sources.list" -o Dir::Etc::SourceParts=/dev/null
           -o "Dir::State::Lists=$m/lists" -o "Dir::Cache=$m/cache" -o APT::Sandbox::User=root)
  if apt-get "${a[@]}" update -qq >/dev/null 2>&1 &&
     (cd "$m/debs" && apt-get "${a[@]}" download -qq mesa-vulkan-drivers/bookworm-backports >/dev/null 2>&1); then
    for f in "$m"/debs/*.deb; do dpkg -x "$f" "$m/root"; done
    printf '{"file_format_version":"1.0.1","ICD":{"library_path":"%s","api_version":"1.4.305"}}\n' \
      "$m/root/$lib" > "$m/icd.json"
    rm -rf "$m/debs" "$m/lists" "$m/cache"
  else
    echo "setup: warning: could not download Mesa 25 from bookworm-backports; the web tests will fail" >&2
    rm -rf "$m"
  fi
}

# The viewer's test-only npm package (playwright-core), pinned by web/viewer/package-lock.json,
# into web/viewer/node_modules (ignored by git); idempotent and not fatal like npm_tools.
viewer_tools() {
  $tests || return 0
  local dir
  dir="$(cd "$(dirname "$0")/.." && pwd)/web/viewer"
  cmp -s "$dir/package-lock.json" "$dir/node_modules/.limn-installed-lock.json" && return 0
  echo "setup: npm ci in web/viewer (playwright-core)" >&2
  if (cd "$dir" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error >/dev/null 2>&1); then
    cp "$dir/package-lock.json" "$dir/node_modules/.limn-installed-lock.json"
  else
    echo "setup: warning: npm ci in web/viewer failed; the viewer's browser tests will fail until it succeeds" >&2
  fi
}

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = installed ] || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  npm_tools
  web_tools
  viewer_tools
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
web_tools
viewer_tools
