#!/usr/bin/env bash
# Sets up and builds (scripts/setup.sh), runs the whole test suite (CTest, under a virtual X
# server for the rendering tests), then builds Core and its unit tests with AddressSanitizer
# and UndefinedBehaviorSanitizer in build-asan/ and runs them there.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
build="${SPHCOVER_BUILD_DIR:-$root/build}"
jobs="${SPHCOVER_JOBS:-$(nproc)}"

# Every test runs once: a failure is a failure. The tests that open an X display (label x11)
# each start an X server of their own (Testing/RunWithXvfb.sh: a fresh Xvfb with -noreset), so
# the suite needs no DISPLAY and runs without one: a test that opened the display without the
# launcher fails at once instead of sharing a server. (The aborts that the earlier rerun hid were
# Xvfb resetting when its last client disconnected while pvbatch reopened the display: "bad X
# server connection", SIGABRT; see Testing/RunWithXvfb.sh.)
env -u DISPLAY -u XAUTHORITY \
  ctest --test-dir "$build" --output-on-failure -j "$jobs"

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

# libFuzzer harnesses of the readers (Testing/Fuzz), when clang is installed: Core and the
# Readers module built with clang, coverage, ASan and UBSan in build-fuzz/, each harness fuzzing
# for SPHCOVER_FUZZ_SECONDS (default 60) as a CTest test (label `fuzz`), two at a time.
# Skipped where clang++ or its libFuzzer runtime (Debian: libclang-rt-14-dev) is missing.
fuzz_probe='extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }'
if command -v clang++ >/dev/null 2>&1 &&
  echo "$fuzz_probe" | clang++ -fsanitize=fuzzer,address,undefined -x c++ - -o /dev/null 2>/dev/null; then
  fuzz="${SPHCOVER_FUZZ_BUILD_DIR:-$root/build-fuzz}"
  if [[ ! -f "$fuzz/CMakeCache.txt" ]]; then
    cmake -S "$root" -B "$fuzz" -G Ninja \
      -DSPHCOVER_FUZZ=ON \
      -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      -DPython3_EXECUTABLE=/usr/bin/python3
  fi
  if [[ -n "${SPHCOVER_FUZZ_SECONDS:-}" ]]; then
    cmake "$fuzz" -DSPHCOVER_FUZZ_SECONDS="$SPHCOVER_FUZZ_SECONDS" >/dev/null
  fi
  cmake --build "$fuzz" -j "$jobs"
  ctest --test-dir "$fuzz" --output-on-failure -j 2 -L fuzz
else
  echo "test: no clang++ with libFuzzer: skipping the fuzz tests (Testing/Fuzz)" >&2
fi
