#!/usr/bin/env bash
# Checks that every C++ file follows .clang-format and that the Python package, its tests and the
# docs' examples pass flake8 (python/.flake8) (CI). With --fix, reformats the C++ files in place (flake8 fixes nothing).
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.hpp')
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
if ! clang-format --dry-run --Werror "${files[@]}"; then
  echo "check_format: the files above differ from .clang-format; run: bash scripts/check_format.sh --fix" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files follow .clang-format"
if ! (cd python && /usr/bin/python3 -m flake8 . ../docs/examples); then
  echo "check_format: the Python lines above break python/.flake8's rules" >&2
  exit 1
fi
echo "check_format: python/ and docs/examples/ pass flake8"
