#!/usr/bin/env bash
# Installs what is missing, builds the scene runner, runs the scenes and reports them.
#   scripts/scenes.sh            the quick variant (about a minute after the build): the 3,240-
#                                vertex cloth for 2 s with every contact model and the Bullet
#                                peer, and the bowl of 50 bodies for 3 s with every model and
#                                the Bullet peer;
#                                tables, plots and pictures in out/scenes/{cloth_3240,bowl_50}/
#   scripts/scenes.sh --full     both cloths (3,240 and 6,460 vertices) for the scenes' 10 s and
#                                the bowl for its 15 s (about 10 minutes on 2 cores); writes
#                                docs/scenes.md's results, docs/scenes/*.png and the README's
#                                scenes block
#   scripts/scenes.sh ARGS...    fse_sim with these arguments (--help lists them)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --bench
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)" --target fse_sim
sim=build/sim/fse_sim
every=(--contact exact paper mesh --peer --snapshots 0 1 2 3 5 10)
bowl=(--contact exact vertices paper mesh --peer --snapshots 0 1 2 4 8 15)
# The commit a run was made at, for its report's stamp (uncommitted changes marked).
record_commit() {
  /usr/bin/python3 scripts/doc_blocks.py > "$1/commit"
}
case "${1:-}" in
  "")
    $sim sim/scenes/cloth_3240.json "${every[@]}" --duration 2 --out out/scenes/cloth_3240
    record_commit out/scenes/cloth_3240
    $sim sim/scenes/bowl_50.json "${bowl[@]}" --duration 3 --out out/scenes/bowl_50
    record_commit out/scenes/bowl_50
    /usr/bin/python3 sim/scene_report.py out/scenes/cloth_3240 out/scenes/bowl_50
    echo "results: out/scenes/cloth_3240/results.md, out/scenes/bowl_50/results.md"
    ;;
  --full)
    for n in 3240 6460; do
      $sim sim/scenes/cloth_$n.json "${every[@]}" --out out/scenes/cloth_$n
      record_commit out/scenes/cloth_$n
    done
    $sim sim/scenes/bowl_50.json "${bowl[@]}" --out out/scenes/bowl_50
    record_commit out/scenes/bowl_50
    /usr/bin/python3 sim/scene_report.py out/scenes/cloth_3240 out/scenes/cloth_6460 \
      out/scenes/bowl_50 --docs docs --readme README.md
    ;;
  *) $sim "$@" ;;
esac
