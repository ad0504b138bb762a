#!/usr/bin/env bash
# Builds everything with AddressSanitizer + UndefinedBehaviorSanitizer (gcc, -DTSP_SANITIZE=ON)
# into build-asan/ and runs the whole suite there. Any sanitizer report fails the test it
# happens in. Leak reports are suppressed only for third-party libraries (Mesa, X, HDF5): see
# scripts/sanitizers/lsan.supp, one comment per entry.
#   bash scripts/test-sanitizers.sh [ctest args, e.g. -R HostileInput]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTSP_SANITIZE=ON \
  -DTSP_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j"$(nproc)"
export ASAN_OPTIONS="abort_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd build-asan
run() {
  if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ] && command -v xvfb-run >/dev/null; then
    xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j"$(nproc)" --timeout 1200 "$@"
  else
    ctest --output-on-failure -j"$(nproc)" --timeout 1200 "$@"
  fi
}
# The window tests (GLFW) load Mesa's GLX driver with dlopen; it leaks 128 bytes and is unloaded
# at exit, so LeakSanitizer cannot name it (its frames show as <unknown module>; slow unwinding,
# which would name the caller, deadlocks inside Mesa's LLVM JIT). For those tests alone leak
# detection is off; AddressSanitizer and UBSan stay on. HostileOutputWindow runs `play` too.
# The same holds for Open MPI in tspplay-mpi (the MpiBuild tests): its components are plugins
# loaded with dlopen and unloaded by MPI_Finalize, and what they keep (about 120 KB of
# strdup'ed names and tables, in libmpi, libopen-pal and unnamed modules) is reported as leaked.
status=0
run -E '^(GlfwContext|Player|HostileOutputWindow|MpiBuild)\.' "$@" || status=1
ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" run -R '^(GlfwContext|Player|HostileOutputWindow|MpiBuild)\.' "$@" \
  || status=1
exit $status
