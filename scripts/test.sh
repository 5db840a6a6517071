#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite.
#   scripts/test.sh              Release build in build/
#   scripts/test.sh --sanitize   AddressSanitizer + UBSan build in build-asan/
#   scripts/test.sh --tsan       ThreadSanitizer build in build-tsan/: the tests of what threads
#                                share (batched queries, the lazily computed rolling radius, the
#                                FCL traversal that calls the batched queries)
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
flags=(-DCMAKE_BUILD_TYPE=Release)
tests=()
case "${1:-}" in
  --sanitize)
    build=build-asan
    flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DFSE_SANITIZE=ON) ;;
  --tsan)
    build=build-tsan
    flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DFSE_SANITIZE_THREAD=ON -DFSE_BUILD_BENCH=OFF)
    tests=(-R "BatchDistance|RollingRadiusIsComputedOnce|FclIntegration") ;;
esac
scripts/install-deps.sh
cmake -S . -B "$build" "${flags[@]}" -DFSE_BUILD_TESTS=ON
cmake --build "$build" --parallel "$(nproc)"
cd "$build"
ctest --output-on-failure --parallel "$(nproc)" "${tests[@]}"
