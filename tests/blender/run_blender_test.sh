#!/usr/bin/env bash
# Runs one test script of the Blender add-on in Debian's Blender, headless, with the add-on
# installed from its zip into a scratch user folder (the user's own Blender is not touched).
# Exits 77 (a skip for ctest) with the reason when Blender is not installed.
# usage: run_blender_test.sh ADDON_ZIP MODULE_DIR SCRIPT [ARGS...]
set -euo pipefail
zip=$1 module_dir=$2 script=$3
shift 3
blender=${PRIMO_BLENDER:-$(command -v blender || true)}
if [[ -z $blender ]]; then
  echo "SKIP: blender not found (Debian package blender; scripts/setup.sh installs it)"
  exit 77
fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
export BLENDER_USER_CONFIG=$scratch/config BLENDER_USER_SCRIPTS=$scratch/scripts
export PRIMO_TEST_SCRATCH=$scratch
# Blender prints its own lines around the script's; --python-exit-code makes an uncaught error
# (a failed assert) the exit code.
exec "$blender" -b --factory-startup --python-exit-code 1 --python "$script" -- \
  "$zip" "$module_dir" "$@"
