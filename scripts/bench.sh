#!/usr/bin/env bash
# Installs what is missing, builds, runs the benchmark, plots it and writes its results page.
#   scripts/bench.sh            the quick mode (seconds after the build): out/ (CSV, JSON, PNG plots)
#                               and out/benchmark.md; then the scenes' quick variants, the cloth
#                               and the bowl (scripts/scenes.sh: out/scenes/); then the Python
#                               module's speed, quick (out/python/); then the superquadric
#                               fit's quick study (scripts/fit.sh: out/fit/)
#   scripts/bench.sh --full     everything (about 30 minutes on 2 cores): fse_bench's full run, the
#                               micro-benchmarks, the culling study and the aspect sweep, the pairs,
#                               the scenes' full variants (scripts/scenes.sh --full), the Python
#                               module's speed and the fitting study (scripts/fit.sh --full);
#                               writes every generated page (docs/benchmark.md, docs/pairs.md,
#                               docs/scenes.md, docs/python.md's and docs/fitting.md's results), their
#                               pictures and the README's generated blocks, all from this one run
#   scripts/bench.sh --pairs    the superellipsoid against every FCL shape, against FCL's libccd and
#                               Bullet (a minute); writes docs/pairs.md's results, docs/bench/pairs.png
#                               and the README's pairs block (also part of --full)
#   scripts/bench.sh --python   the Python module against the C++ library and Open3D (a minute),
#                               and its example: writes docs/python.md's results and its two
#                               pictures in docs/bench/ (also part of --full)
#   scripts/bench.sh ARGS...    fse_bench with these arguments (--help lists them); results in out/
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --bench
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)" --target fse_bench fse_microbench fse_python \
  fse_python_baseline
bench=build/bench
python_speed() {  # the Python module's speed and its example; ARGS: speed.py's (--quick, --docs DIR)
  mkdir -p out/python
  /usr/bin/python3 scripts/doc_blocks.py > out/python/commit
  PYTHONPATH=build/python /usr/bin/python3 python/bench/speed.py \
    --baseline build/python/fse_python_baseline --out out/python "$@"
  PYTHONPATH=build/python /usr/bin/python3 python/examples/fit_superquadric.py --out out/python
  if [ "${1:-}" = "--docs" ]; then cp out/python/fit_superquadric.png docs/bench/; fi
}
if [ $# -eq 0 ]; then set -- --quick; fi
pairs() {
  mkdir -p out/pairs
  /usr/bin/python3 scripts/doc_blocks.py > out/pairs/commit
  $bench/fse_bench --pairs 600 --out out/pairs | tee out/pairs/pairs.txt
  /usr/bin/python3 bench/plot.py out/pairs
  /usr/bin/python3 bench/pairs_doc.py out/pairs --docs docs --readme README.md
}
if [ "$1" = "--pairs" ]; then
  pairs
  exit 0
fi
if [ "$1" = "--python" ]; then
  python_speed --docs docs
  exit 0
fi
if [ "$1" = "--full" ]; then
  rm -rf out && mkdir -p out
  /usr/bin/python3 scripts/doc_blocks.py > out/commit
  $bench/fse_bench --out out
  $bench/fse_microbench --benchmark_min_time=0.2 --benchmark_out=out/micro.json \
    --benchmark_out_format=json
  $bench/fse_bench --culling 1000000 | tee out/culling.txt
  $bench/fse_bench --aspect-sweep | tee out/aspect_sweep.txt
  /usr/bin/python3 bench/plot.py out
  /usr/bin/python3 bench/benchmark_doc.py out --docs docs --readme README.md
  pairs
  scripts/scenes.sh --full
  python_speed --docs docs
  scripts/fit.sh --full
  exit 0
fi
$bench/fse_bench "$@"   # writes to out/ unless --out says otherwise
case " $* " in
  *" --help "*|*" -h "*|*" --aspect-sweep "*|*" --culling "*) ;;
  *" --out "*) ;;  # plot and document your directory with bench/plot.py and bench/benchmark_doc.py
  *) /usr/bin/python3 bench/plot.py out && /usr/bin/python3 bench/benchmark_doc.py out ;;
esac
if [ $# -eq 1 ] && [ "$1" = "--quick" ]; then
  scripts/scenes.sh
  python_speed --quick
  scripts/fit.sh
fi
