#!/usr/bin/env bash
# r18 on the device machine (eighteenth session): KD build seconds (`cohort info`, as printed) of
# this session's build (gpu-bundle/bin/cohort) against the seventeenth session's HEAD
# (cohort-4fb8979: the same tree bits) and Embree 3's high-quality BVH build (cohort-embree-bench),
# alternated within each round so that ratios compare builds run at the same machine speed:
# Crytek Sponza subdivided twice (4.47M) on all 16 cores, Sponza x4 (subdivided once, 1.1M) and the
# bunny x16 (bun_zipper.ply subdivided twice, 1.11M) on 2 cores (taskset -c 0,1).
# Usage: [ROUNDS=N] [BASELINE=cohort-COMMIT] docs/results/raw/h200-2026-12-04-s18/r18-run.sh OUT_DIR
# (the nineteenth session ran it with BASELINE=cohort-c820c8c, the eighteenth session's HEAD)
set -uo pipefail
R="${1:?usage: r18-run.sh OUT_DIR}"
BASE="${BASELINE:-cohort-4fb8979}"
mkdir -p "$R" /tmp/r18
[[ -f gpu-bundle/lib/libembree3.so.3 ]] || xz -dk gpu-bundle/lib/libembree3.so.3.xz
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
B=gpu-bundle/bin
G="$PWD/gpu-scenes"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)" | tee "$R/builds.txt"
$B/cohort export "$G/crytek-sponza/sponza.obj.gz" -o /tmp/r18/sponza1m.ply --subdivide 1 >/dev/null
$B/cohort export "$G/crytek-sponza/sponza.obj.gz" -o /tmp/r18/sponza4m.ply --subdivide 2 >/dev/null
$B/cohort export "$G/bunny/bun_zipper.ply" -o /tmp/r18/bunny16.ply --subdivide 2 >/dev/null
for round in $(seq "${ROUNDS:-3}"); do
  for spec in "0-15 sponza4m" "0,1 sponza1m" "0,1 bunny16"; do
    set -- $spec
    for run in "cohort compact" "$BASE compact" "cohort deep" "$BASE deep" "embree high"; do
      read -r bin tree <<<"$run"
      if [[ $bin == embree ]]; then
        [[ $1 == 0,1 ]] || continue
        line=$(taskset -c "$1" $B/cohort-embree-bench "/tmp/r18/$2.ply" --threads 2 --build-quality high \
          --trace-res 16 --reps 3 --view interior 2>&1 | grep -o '[0-9]* triangles, BVH build (high) [0-9.]*s')
      else
        line=$(taskset -c "$1" "$B/$bin" info "/tmp/r18/$2.ply" --tree "$tree" 2>&1 | grep 'kd-tree')
      fi
      echo "$round $2 cores=$1 $bin $tree $line"
    done
  done
done 2>&1 | tee -a "$R/builds.txt"
