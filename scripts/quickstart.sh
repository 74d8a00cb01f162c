#!/usr/bin/env bash
# Quick start 1: install dependencies, build, run the default scene. Output in out/<scene>.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/roller run problems/z1_outf05.toml "$@"
