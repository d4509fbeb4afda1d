#!/usr/bin/env bash
# Installs what is missing, builds PriMo (Release) and runs it. With no arguments it opens the
# editor on the bundled Spot mesh; without a display it renders the posed Spot under Xvfb and
# saves the picture instead. Any arguments are passed to `primo` as they are (e.g.
# `scripts/run.sh edit my.obj` or `scripts/run.sh deform my.json -o out.obj`).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${PRIMO_BUILD_DIR:-"$root/build"}

"$root/scripts/setup.sh" >/dev/null
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)" --target primo >/dev/null
if (($# > 0)); then
  exec "$build/src/primo" "$@"
fi
if [[ -n ${DISPLAY:-} || -n ${WAYLAND_DISPLAY:-} ]]; then
  exec "$build/src/primo"
fi
out="$build/editor-spot.png"
echo "run.sh: no display; rendering the editor offscreen (xvfb-run) to $out"
xvfb-run -a -s "-screen 0 1280x800x24" "$build/src/primo" edit \
  "$root/assets/scenarios/spot-pose.json" --screenshot "$out" --screenshot-ui
echo "wrote $out (open the editor on a desktop with: scripts/run.sh)"
