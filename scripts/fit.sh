#!/usr/bin/env bash
# Installs what is missing, builds the fitting application and runs its study (docs/fitting.md).
#   scripts/fit.sh            the quick study (seconds after the build): two shapes, full views,
#                             noise 0 and 1 %; out/fit/ (study.csv, results.md, study.png)
#   scripts/fit.sh --full     the whole study (about two minutes): six shape families, full and
#                             one-sided views, noise 0, 1 and 2 %, 20 % outliers; writes
#                             docs/fitting.md's results, docs/fitting/study.png and the README's
#                             fitting block
#   scripts/fit.sh ARGS...    fse_fit with these arguments (--help lists them)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)" --target fse_fit
fit=build/fit/fse_fit
case "${1:-}" in
  "")
    $fit study --quick --out out/fit
    /usr/bin/python3 scripts/doc_blocks.py > out/fit/commit
    /usr/bin/python3 fit/fit_report.py out/fit
    echo "results: out/fit/results.md"
    ;;
  --full)
    $fit study --out out/fit
    /usr/bin/python3 scripts/doc_blocks.py > out/fit/commit
    /usr/bin/python3 fit/fit_report.py out/fit --docs docs --readme README.md
    ;;
  *) $fit "$@" ;;
esac
