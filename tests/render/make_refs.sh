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
models=$(cd ../data && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
grep -v '^\s*#' ref/cases.txt | while read -r name model options; do
  [ -n "$name" ] || continue
  "$bin/limn-classify" "$models/$model" -o "$tmp/$name.limn"
  trim=()
  # Leading --TOOL=A,B,... options run that tool first, in the order given (render_cli_test.cpp
  # does the same): limn-tables and limn-blend rewrite the container, limn-trim writes a mask.
  while :; do
    first=${options%% *}
    case "$first" in
      --tables=*|--blend=*|--trim=*) ;;
      *) break ;;
    esac
    options=${options#"$first"}; options=${options# }
    tool=${first%%=*}; tool=limn-${tool#--}
    args=$(echo "${first#*=}" | tr , ' ')
    if [ "$tool" = limn-trim ]; then
      # shellcheck disable=SC2086
      "$bin/limn-trim" "$tmp/$name.limn" -o "$tmp/$name.mask.png" $args
      trim=(--trim "$tmp/$name.mask.png")
    else
      # shellcheck disable=SC2086
      "$bin/$tool" "$tmp/$name.limn" -q -o "$tmp/$name.limn" $args
    fi
  done
  # shellcheck disable=SC2086
  "$bin/limn-render" "$tmp/$name.limn" --size 128x96 --validate "${trim[@]}" $options -o "ref/$name.png"
  echo "ref/$name.png"
done
