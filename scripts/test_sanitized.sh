#!/usr/bin/env bash
# The second CI build: Debug with AddressSanitizer and UndefinedBehaviorSanitizer in ./build-sanitize,
# running the tests labelled fast (memory errors and undefined behaviour fail the test that hits
# them). Usage: scripts/test_sanitized.sh [extra ctest args]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
if [ ! -f build-sanitize/build.ninja ] && [ ! -f build-sanitize/Makefile ]; then
  rm -f build-sanitize/CMakeCache.txt
  cmake -S . -B build-sanitize "${generator[@]}" -DCMAKE_BUILD_TYPE=Debug -DROLLER_SANITIZE=ON -DROLLER_WERROR=ON
fi
cmake --build build-sanitize -j "$(nproc)"
# Leaks are checked too; the suppressions name allocations inside system libraries we do not own.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/sanitizer.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" -L fast "$@"
