#!/usr/bin/env bash
# Sourced by scripts/test-sanitize.sh and scripts/fuzz.sh: configures the one ASan + UBSan build both
# use (clang, GROOM_SANITIZE=ON, GROOM_FUZZ=ON) in $GROOM_SANITIZE_BUILD_DIR (default ./build-sanitize).
# Sharing it means CI compiles the instrumented libraries once for the sanitizer suite and the fuzzers.
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
sbuild=${GROOM_SANITIZE_BUILD_DIR:-$root/build-sanitize}
jobs=${GROOM_JOBS:-$(nproc)}

if ! command -v clang++ >/dev/null 2>&1 || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  bash "$root/scripts/install-deps.sh" --with-tools
fi
bash "$root/scripts/install-deps.sh" >/dev/null

configure_sanitize_build() {
  local launcher=()
  if command -v ccache >/dev/null 2>&1; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
    export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(dirname "$root")}
  fi
  # No Python module: an ASan-instrumented extension cannot load into an uninstrumented python3.
  # -O1: sanitizer reports stay readable and the heavy OpenVDB/CGAL units compile in reasonable time.
  cmake -S "$root" -B "$sbuild" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_FLAGS_RELEASE="-O1 -gline-tables-only -DNDEBUG" \
    -DGROOM_SANITIZE=ON -DGROOM_FUZZ=ON -DGROOM_BUILD_TESTS=ON -DGROOM_BUILD_BENCHMARKS=OFF \
    -DGROOM_BUILD_PYTHON=OFF -DGROOM_TEST_TIMEOUT=1200 "${launcher[@]}" >/dev/null
}

# Sanitizer behaviour for everything run from the build: stop at the first report, with a stack.
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/scripts/lsan.supp:print_suppressions=0}
