#!/usr/bin/env bash
# Manual stress run (docs/reliability.md): a 2,000,000-quad cylinder written, read back and
# deformed by `primo deform` (hierarchical, 2 iterations), with the time and peak memory of
# each step. Not part of scripts/test.sh: it takes minutes and gigabytes.
#   scripts/stress.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
primo=${1:-"$root/build"}/src/primo
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
measure() {  # label, command...
  local label=$1; shift
  /usr/bin/time -f "$label: %e s, peak %M kB" "$@" >/dev/null
}
measure "generate 2M quads" "$primo" generate cylinder --radius 0.25 --length 2 --segments 2000 --bands 1000 -o "$work/big.obj"
ls -l "$work/big.obj" | awk '{print "big.obj: " $5 " bytes"}'
cat >"$work/s.json" <<JSON
{"format": "primo-scenario/1", "mesh": "big.obj",
 "handles": [{"select": {"box": {"min": [-1, -0.1, -1], "max": [1, 0.01, 1]}}, "fix": "all"},
             {"select": {"box": {"min": [-1, 1.99, -1], "max": [1, 2.1, 1]}}, "fix": "all",
              "transform": {"translate": [0.2, 0, 0]}}],
 "solver": {"method": "hierarchical", "max_iterations": 2}}
JSON
measure "deform (load, validate, 2 hierarchical cycles, save)" "$primo" deform "$work/s.json" -o "$work/out.obj" --one-step || echo "deform failed (exit $?)"
