#!/usr/bin/env bash
# Install.PipelineRunsFromThePrefix: `cmake --install BUILD --prefix P` into an empty folder, then
# a whole pipeline run from P alone: the tools in P/bin, the OpenImageIO reader in P/lib/limn
# (found next to the tools, not in the build tree), the README in P/share/doc/limn with the docs and
# format specs it links to in the same layout (docs/, formats/), so that every such link resolves.
# Usage: install_test.sh BUILD_DIR
set -euo pipefail
build=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "install test: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$work/prefix" >/dev/null
p=$work/prefix
unset LIMN_IMAGE_PLUGIN
cd "$work"

tools="blend classify examples heightmap info loop render seams tables trim"
for t in $tools; do [ -x "$p/bin/limn-$t" ] || fail "bin/limn-$t not installed"; done
# Only the tools: no test, benchmark or helper executable lands in bin/.
[ "$(ls "$p/bin" | wc -l)" -eq 10 ] || fail "bin/ holds more than the 10 tools: $(ls "$p/bin")"
[ -f "$p/lib/limn/limn_image_oiio.so" ] || fail "lib/limn/limn_image_oiio.so not installed"
[ -f "$p/share/doc/limn/README.md" ] || fail "share/doc/limn/README.md not installed"
[ -f "$p/share/doc/limn/formats/limn.md" ] || fail "share/doc/limn/formats/limn.md not installed"
[ -f "$p/share/doc/limn/docs/tools.md" ] || fail "share/doc/limn/docs/tools.md not installed"
grep -o '](\(docs\|formats\)/[^)#]*' "$p/share/doc/limn/README.md" | sed 's/^](//' | sort -u |
  while read -r f; do
    [ -f "$p/share/doc/limn/$f" ] || fail "the installed README links to $f, which is not installed"
  done
"$p/bin/limn-render" --version | grep -q '^limn-render ' || fail "limn-render --version"

"$p/bin/limn-examples" --only quad_sphere -o meshes
"$p/bin/limn-classify" meshes/quad_sphere.obj | "$p/bin/limn-tables" --depth 2 |
  "$p/bin/limn-seams" > qs.limn
"$p/bin/limn-info" --json qs.limn | grep -q '"depth":2,' || fail "limn-info on the installed pipeline"
# A PPM is no PNG, so the installed OpenImageIO plugin has to read it.
printf 'P3\n2 2\n255\n255 0 0 0 255 0 0 0 255 255 255 255\n' > tex.ppm
"$p/bin/limn-render" qs.limn --size 64x48 --texture tex.ppm --validate -o qs.png
[ "$(head -c 8 qs.png | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "qs.png is no PNG"

# And it is the installed plugin that did it: without it the same render is a missing capability.
mv "$p/lib/limn/limn_image_oiio.so" "$work/moved.so"
set +e
"$p/bin/limn-render" qs.limn --size 64x48 --texture tex.ppm -o qs2.png 2>err.txt
status=$?
set -e
[ "$status" -eq 3 ] || fail "without the plugin: exit $status, expected 3 ($(cat err.txt))"
[ ! -e qs2.png ] || fail "without the plugin a qs2.png was left"
echo "install test: passed"
