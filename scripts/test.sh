#!/usr/bin/env bash
# The README's second command: install what is missing, build, run the whole test suite via CTest.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
cd "${GROOM_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j "${GROOM_JOBS:-$(nproc)}"
