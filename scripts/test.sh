#!/usr/bin/env bash
# Installs what is missing, builds, and runs the test suite (docs/hardening.md).
#   scripts/test.sh              Release build in build/: the whole suite
#   scripts/test.sh --sanitize   clang, AddressSanitizer + UBSan, in build-asan/: the whole suite but
#                                the packaging tests, and a smoke run of each fuzz target
#   scripts/test.sh --tsan       gcc, ThreadSanitizer, in build-tsan/: the tests of what threads
#                                share (thread safety, batched queries, the per-thread evaluation
#                                count, the lazily computed rolling radius, the FCL traversal that
#                                calls the batched queries, the cloth and the bowl scenes on 1 and
#                                2 threads, the interposer's first calls); it builds only the test
#                                programs that hold them
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
flags=(-DCMAKE_BUILD_TYPE=Release)
deps=()
targets=()
tests=()
case "${1:-}" in
  --sanitize)
    build=build-asan
    deps=(--fuzz)
    # Line tables only: a report's stack still names files and lines, and the build is faster
    # than with full debug information (docs/hardening.md → "CI").
    flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DFSE_BUILD_FUZZ=ON
           "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG" -DFSE_BUILD_BENCH=OFF)
    tests=(-E "^package_") ;;
  --tsan)
    build=build-tsan
    flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG"
           -DFSE_SANITIZE_THREAD=ON -DFSE_BUILD_BENCH=OFF)
    targets=(--target test_shape test_threads test_batch test_fcl_glue test_interpose test_sim)
    tests=(-R "ThreadSafety|EvaluationsArePerThread|Interpose.FirstCallsRace|BatchDistance|RollingRadiusIsComputedOnce|DirectionCoverIsBuiltOnce|FclIntegration|SameResultsForOneAndTwoThreads|OneAndTwoThreadsGiveIdenticalResults") ;;
  "") ;;
  *) echo "usage: scripts/test.sh [--sanitize | --tsan]" >&2; exit 2 ;;
esac
scripts/install-deps.sh "${deps[@]}"
cmake -S . -B "$build" "${flags[@]}" -DFSE_BUILD_TESTS=ON
cmake --build "$build" --parallel "$(nproc)" "${targets[@]}"
cd "$build"
ctest --output-on-failure --parallel "$(nproc)" "${tests[@]}"
