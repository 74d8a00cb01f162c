#!/usr/bin/env bash
# Quick start 2: install dependencies, build, run every test through CTest.
# Options: --fast (only the tests labelled fast, ~1 min), --slow (only the slow ones), --fuzz (the
# scene fuzzer, ~1 min); other
# arguments go to ctest (e.g. -R mesh).
set -euo pipefail
cd "$(dirname "$0")/.."
ctest_args=()
for a in "$@"; do
  case "$a" in
    --fast) ctest_args+=(-L fast) ;;
    --slow) ctest_args+=(-L slow) ;;
    --fuzz) ctest_args+=(-L fuzz) ;;
    *) ctest_args+=("$a") ;;
  esac
done
bash scripts/install-deps.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)" "${ctest_args[@]}"
