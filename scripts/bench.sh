#!/usr/bin/env bash
# Installs what is missing, builds, and runs the benchmark binary. Arguments go to the
# binary (default: --quick, a run of a few seconds; --help lists the modes).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)" --target fse_bench
if [ $# -eq 0 ]; then set -- --quick; fi
build/bench/fse_bench "$@"
