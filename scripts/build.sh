#!/usr/bin/env bash
# Configures and builds groom in Release into ./build (or $GROOM_BUILD_DIR). Extra args go to cmake.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${GROOM_BUILD_DIR:-$root/build}
jobs=${GROOM_JOBS:-$(nproc)}
launcher=()
# ccache (optional) makes rebuilds and parallel work trees cheap; the build does not need it.
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(dirname "$root")}
fi
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" >/dev/null
cmake --build "$build" -j "$jobs" 2>&1 | grep -vE '^\[ *[0-9]+%\]|^Consolidate|^-- ' || true
# grep swallowed cmake's status: check the result explicitly.
cmake --build "$build" -j "$jobs" >/dev/null
