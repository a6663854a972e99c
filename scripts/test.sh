#!/usr/bin/env bash
# README command (2): install what is missing, then build and run the whole test suite in
# Debug under ASan + UBSan, in Release at -O2 (rounding bugs only show when optimised), and
# with clang: the libFuzzer harnesses of every reader (bounded time) and the whole-part solver under TSan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
start=$SECONDS
for preset in debug release clang; do
  echo "=== certipose: $preset ==="
  cmake --workflow --preset "$preset"
done
echo "=== certipose: all presets passed in $((SECONDS - start)) s ==="
