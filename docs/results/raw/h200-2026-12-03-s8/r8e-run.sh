#!/usr/bin/env bash
# r8e on the device machine: build times of the 4-wide BVH against the KD-trees (`cohort info`, build
# seconds as printed, 3 each in turn) for the bunny subdivided twice (1.1M triangles) and Crytek
# Sponza subdivided once (1.1M) on 2 cores (taskset -c 0,1), and Sponza subdivided twice (4.47M) on
# all 16 cores. Usage: docs/results/raw/h200-2026-12-03-s8/r8e-run.sh OUT_DIR
set -uo pipefail
R="${1:?usage: r8e-run.sh OUT_DIR}"
mkdir -p "$R" /tmp/r8e
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
C=gpu-bundle/bin/cohort
G="$PWD/gpu-scenes"
$C export "$G/bunny/bun_zipper.ply" -o /tmp/r8e/bunny16.ply --subdivide 2 >/dev/null
$C export "$G/crytek-sponza/sponza.obj.gz" -o /tmp/r8e/sponza1m.ply --subdivide 1 >/dev/null
$C export "$G/crytek-sponza/sponza.obj.gz" -o /tmp/r8e/sponza4m.ply --subdivide 2 >/dev/null
for round in 1 2 3; do
  for scene in bunny16 sponza1m; do
    for t in bvh4 compact deep; do
      echo "$round $scene 2cores $t $(taskset -c 0,1 $C info /tmp/r8e/$scene.ply --tree $t | grep -E 'BVH:|kd-tree' | sed -E 's/.*(built in .*)/\1/')"
    done
  done
  for t in bvh4 deep; do
    echo "$round sponza4m 16cores $t $($C info /tmp/r8e/sponza4m.ply --tree $t | grep -E 'BVH:|kd-tree' | sed -E 's/.*(built in .*)/\1/')"
  done
done 2>&1 | tee "$R/builds.txt"
