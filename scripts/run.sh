#!/usr/bin/env bash
# Installs what is missing, builds PriMo (Release) and runs it. With no arguments it solves the
# bundled example scenario and writes the result next to the build; any arguments are passed
# to `primo` as they are (e.g. `scripts/run.sh deform my.json -o out.obj`).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${PRIMO_BUILD_DIR:-"$root/build"}

"$root/scripts/setup.sh" >/dev/null
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)" --target primo >/dev/null
if (($# == 0)); then
  out="$build/bent-bar.obj"
  "$build/src/primo" deform "$root/assets/scenarios/bar-bend.json" -o "$out" --stats "$build/bent-bar.stats.json"
  echo "wrote $out"
  cat "$build/bent-bar.stats.json"
else
  exec "$build/src/primo" "$@"
fi
