#!/usr/bin/env bash
# Quick start 2: install dependencies, build, run every test through CTest.
# Extra arguments go to ctest (e.g. -L fast, -R mesh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)" "$@"
