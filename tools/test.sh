#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (CTest). Extra arguments go to ctest,
# e.g. tools/test.sh -R map   or   tools/test.sh -L scenario
#   tools/test.sh --sanitize [ctest arguments]   the whole suite under AddressSanitizer and
#   UndefinedBehaviorSanitizer, in build-sanitize/ (slower; leaks are errors, except the known
#   ones of the system's graphics libraries and the Python interpreter, in tools/lsan.supp)
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)

if [ "${1:-}" = "--sanitize" ]; then
  shift
  export AEROBOX_BUILD_DIR=${AEROBOX_SANITIZE_DIR:-$top/build-sanitize}
  if [ ! -f "$AEROBOX_BUILD_DIR/CMakeCache.txt" ]; then
    "$top/tools/build.sh" -DAEROBOX_SANITIZE=ON
  else
    "$top/tools/build.sh"
  fi
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  export LSAN_OPTIONS=suppressions=$top/tools/lsan.supp:print_suppressions=0
  # LeakSanitizer's check at exit stops every thread under ptrace, and its tracer can crash when
  # threads are still running or ending then (an intermittent fault of the sanitizer, reported
  # upstream as google/sanitizers#1353; seen once in a Python test that renders). Mesa's
  # llvmpipe, its shader cache and OpenBLAS otherwise leave worker threads at exit: run them in
  # the calling thread here, so that a process ends with its own threads only.
  export LP_NUM_THREADS=0 MESA_SHADER_CACHE_DISABLE=true OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
  cd "$AEROBOX_BUILD_DIR"
  exec ctest --output-on-failure --parallel "$(nproc)" "$@"
fi

build=${AEROBOX_BUILD_DIR:-$top/build}
"$top/tools/build.sh"
cd "$build"
ctest --output-on-failure --parallel "$(nproc)" "$@"
