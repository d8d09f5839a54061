#!/usr/bin/env bash
# The README's first command: install what is missing, build in Release, run the demo groom.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
PATH="${GROOM_BUILD_DIR:-$root/build}:$PATH" bash "$root/datasets/demo.sh" "${1:-$root/out/demo}"
