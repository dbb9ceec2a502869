#!/usr/bin/env bash
# r16 on the device machine (sixteenth session): r13-run.sh's KD build rounds with
# BEFORE=cohort-b6e96ad (the fifteenth session's HEAD: the same tree bits), then the same five
# builds of the bunny x16 (`cohort export bun_zipper.ply --subdivide 2`, 1.11M) on 2 cores, and
# Embree 3's high-quality BVH build of both 1.1M meshes on the same 2 cores (cohort-embree-bench),
# the anchor of issue 26's 1 s target. gpu-bundle/lib/libembree3.so.3 travels xz-compressed.
# Usage: [ROUNDS=N] docs/results/raw/h200-2026-12-04-s16/r16-run.sh OUT_DIR
set -uo pipefail
R="${1:?usage: r16-run.sh OUT_DIR}"
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mkdir -p "$R" /tmp/r13
[[ -f gpu-bundle/lib/libembree3.so.3 ]] || xz -dk gpu-bundle/lib/libembree3.so.3.xz
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
B=gpu-bundle/bin
G="$PWD/gpu-scenes"
BEFORE=cohort-b6e96ad "$HERE/../h200-2026-12-03-s13/r13-run.sh" "$R"
$B/cohort export "$G/bunny/bun_zipper.ply" -o /tmp/r13/bunny16.ply --subdivide 2 >/dev/null
for round in $(seq "${ROUNDS:-3}"); do
  for run in "cohort compact" "cohort deep" "cohort-b6e96ad compact" "cohort-b6e96ad deep" \
             "cohort-d4baeea deep"; do
    read -r bin tree <<<"$run"
    args=(--tree "$tree")
    [[ $bin == cohort-d4baeea ]] && args=()
    line=$(taskset -c 0,1 "$B/$bin" info /tmp/r13/bunny16.ply "${args[@]}" 2>&1 | grep 'kd-tree')
    echo "$round bunny16 cores=0,1 $bin $tree $line"
  done
done 2>&1 | tee -a "$R/builds.txt"
for round in $(seq "${ROUNDS:-3}"); do
  for scene in sponza1m bunny16; do
    line=$(taskset -c 0,1 $B/cohort-embree-bench "/tmp/r13/$scene.ply" --threads 2 --build-quality high \
      --trace-res 16 --reps 3 --view interior 2>&1 | grep -o '[0-9]* triangles, BVH build (high) [0-9.]*s')
    echo "$round $scene cores=0,1 embree-high $line"
  done
done 2>&1 | tee "$R/embree-2cores.txt"
