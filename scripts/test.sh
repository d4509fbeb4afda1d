#!/usr/bin/env bash
# Installs what is missing, builds PriMo (Release), runs every fuzz target for
# PRIMO_FUZZ_SECONDS (default 15; 0 skips) in its sanitizer build (scripts/fuzz.sh,
# docs/reliability.md), then the whole test suite with ctest, whose summary is the last thing
# printed. Fails when fuzzing finds anything or ctest fails.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${PRIMO_BUILD_DIR:-"$root/build"}

"$root/scripts/setup.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)"
status=0
fuzz_seconds=${PRIMO_FUZZ_SECONDS:-15}
if [[ $fuzz_seconds != 0 ]]; then
  "$root/scripts/fuzz.sh" "$fuzz_seconds" || status=1
fi
(cd "$build" && ctest --output-on-failure -j "$(nproc)" --timeout 900) || status=$?
exit "$status"
