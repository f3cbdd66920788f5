#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer
# (g++, RelWithDebInfo) in build-asan/. Every report is fatal: UBSan does not
# recover, ASan halts on the first error, LSan fails the test on a leak that
# scripts/lsan.supp does not explain. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh

flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=g++ -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DVKRAY_BENCHMARKS=OFF -DVKRAY_TESTS=ON -DVKRAY_MPI=OFF >/dev/null
# (MPI off: Open MPI's own allocations would need LeakSanitizer suppressions,
# and only Mesa's are allowed; the MPI tests run in the normal build.)

# Set before building: test discovery runs the test binary at build time.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:print_stacktrace=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
cmake --build build-asan

export LP_NUM_THREADS=2
cd build-asan && ctest --output-on-failure -j 2 "$@"
