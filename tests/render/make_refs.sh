#!/usr/bin/env bash
# Regenerates the reference images in tests/render/ref/ from ref/cases.txt.
# Usage: tests/render/make_refs.sh [BIN_DIR]   (default build/bin)
#
# Run it only when a change to the renderer is *meant* to change the pictures, look at every
# image it rewrites (git diff shows which), and commit them with the change that explains why.
# The test never writes references: it compares the renderer's output against these files.
set -euo pipefail
cd "$(dirname "$0")"
bin=$(cd "${1:-../../build/bin}" && pwd)
models=$(cd ../../../shared/models && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
grep -v '^\s*#' ref/cases.txt | while read -r name model options; do
  [ -n "$name" ] || continue
  "$bin/limn-classify" "$models/$model" -o "$tmp/$name.limn"
  case "$options" in
    --tables=*) tables=${options%% *}; options=${options#"$tables"}
                # shellcheck disable=SC2086
                "$bin/limn-tables" "$tmp/$name.limn" -o "$tmp/$name.limn" $(echo "${tables#--tables=}" | tr , ' ') ;;
  esac
  # shellcheck disable=SC2086
  "$bin/limn-render" "$tmp/$name.limn" --size 128x96 --validate $options -o "ref/$name.png"
  echo "ref/$name.png"
done
