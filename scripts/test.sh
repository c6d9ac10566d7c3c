#!/usr/bin/env bash
# Sets up and builds (scripts/setup.sh), runs the whole test suite (CTest, under a virtual X
# server for the rendering tests), then builds Core and its unit tests with AddressSanitizer
# and UndefinedBehaviorSanitizer in build-asan/ and runs them there.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
build="${SPHCOVER_BUILD_DIR:-$root/build}"
jobs="${SPHCOVER_JOBS:-$(nproc)}"

# A failing test runs once more: OpenGL contexts under xvfb (VTK and pvbatch rendering) abort
# now and then for reasons outside the project; a real failure fails twice.
# -noreset: by default Xvfb resets whenever its last client disconnects, and a test connecting
# during that reset aborts with "bad X server connection" (Example.VisualDebuggingOfSubdivision
# next to Example.ScriptedVtkPipeline failed 3 times in 3 so; with -noreset 3 passes in 3).
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
  ctest --test-dir "$build" --output-on-failure -j "$jobs" --repeat until-pass:2

asan="${SPHCOVER_ASAN_BUILD_DIR:-$root/build-asan}"
if [[ ! -f "$asan/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$asan" -G Ninja \
    -DSPHCOVER_CORE_ONLY=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSPHCOVER_SANITIZE=ON
fi
cmake --build "$asan" -j "$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$asan" --output-on-failure -j "$jobs"
