#!/usr/bin/env bash
# Quick start 2: install dependencies, build, run every test through CTest but the label long.
# Options: --fast (only the tests labelled fast, ~2 min), --slow (only the slow ones), --fuzz (the
# scene fuzzer, ~1 min), --long (the long ones too: the penalty backend's full runs of burnishing
# and carter, ~3 min each); other arguments go to ctest (e.g. -R mesh).
set -euo pipefail
cd "$(dirname "$0")/.."
ctest_args=()
long=(-LE long)
for a in "$@"; do
  case "$a" in
    --fast) ctest_args+=(-L fast) ;;
    --slow) ctest_args+=(-L slow) ;;
    --fuzz) ctest_args+=(-L fuzz) ;;
    --long) long=() ;;
    *) ctest_args+=("$a") ;;
  esac
done
bash scripts/install-deps.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)" "${long[@]}" "${ctest_args[@]}"
