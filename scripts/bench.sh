#!/usr/bin/env bash
# Installs what is missing, builds, runs the benchmark binary and plots its output.
# Arguments go to the binary (default: --quick, a run of seconds; --help lists the options;
# no argument but --full runs everything: about 15 minutes on 2 cores).
# Results: out/ (results.csv, results.json, scaling.csv and the PNG plots).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --bench
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)" --target fse_bench fse_microbench
if [ $# -eq 0 ]; then set -- --quick; fi
if [ "$1" = "--full" ]; then shift; fi
build/bench/fse_bench "$@"   # writes to out/ unless --out says otherwise
case " $* " in
  *" --help "*|*" -h "*|*" --aspect-sweep "*|*" --culling "*) ;;
  *" --out "*) ;;  # the plots are for out/; run bench/plot.py on your directory
  *) /usr/bin/python3 bench/plot.py out ;;
esac
