#!/usr/bin/env bash
# Rewrites the golden per-step roller values (tests/golden/*.csv) from the current build: every
# scene of tests/scenes/test_golden_values.cpp at refine 1 with both backends. Run it only when a
# change of the physics or of an algorithm is intended, and say in the commit message what moved
# and why (tests/golden/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/roller
[ -x "$bin" ] || { echo "update_golden: build first (bash scripts/build.sh)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scenes=(hertz cattaneo z1_outf05 z1_outf10 z2_infini z2_large z3_data01 z4_v25)
for scene in "${scenes[@]}"; do
  for backend in ipopt penalty; do
    "$bin" run "problems/$scene.toml" --contact "$backend" --out "$tmp/$scene-$backend" > /dev/null
    # step, centre and force of the strip on the roller, as roller.csv writes them (17 digits)
    cut -d, -f1,4,5,7,8 "$tmp/$scene-$backend/roller.csv" > "tests/golden/${scene}_${backend}.csv"
    echo "tests/golden/${scene}_${backend}.csv: steps 0 to $(($(wc -l < "tests/golden/${scene}_${backend}.csv") - 2))"
  done
done
