#!/usr/bin/env bash
# Configures and builds roller (Release) in ./build. Usage: scripts/build.sh [extra cmake args];
# ROLLER_CMAKE_ARGS in the environment adds more (CI: -DROLLER_WERROR=ON).
set -euo pipefail
cd "$(dirname "$0")/.."
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
# Configure unless a previous configure completed (a failed one leaves a cache but no build file).
if [ ! -f build/build.ninja ] && [ ! -f build/Makefile ]; then
  rm -f build/CMakeCache.txt
  # shellcheck disable=SC2086  # ROLLER_CMAKE_ARGS is a list of words
  cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release ${ROLLER_CMAKE_ARGS:-} "$@"
fi
cmake --build build -j "$(nproc)"
