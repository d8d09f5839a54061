#!/usr/bin/env bash
# Runs the add-on test in headless Blender; exit 77 (CTest: skipped) when Blender is not installed.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
if ! command -v blender >/dev/null 2>&1; then
  echo "SKIP: blender is not installed (Debian: apt-get install blender); the add-on test needs Blender 3.4"
  exit 77
fi
export GROOM_BLENDER_ADDON_DIR=${GROOM_BLENDER_ADDON_DIR:-$here/../../blender}
exec blender -b --factory-startup --python-exit-code 1 --python "$here/test_addon.py"
