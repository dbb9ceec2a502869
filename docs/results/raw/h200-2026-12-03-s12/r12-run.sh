#!/usr/bin/env bash
# r12 on the device machine: tree build seconds (`cohort info`, as printed) of this session's BVH
# build (gpu-bundle/bin/cohort, f0c4117) against the one before it (cohort-e541858) and of the
# KD-trees against d4baeea's (cohort-d4baeea, the build issue 26 counts from), in turn, 3 rounds:
# Crytek Sponza subdivided twice (4.47M) on all 16 cores and subdivided once (1.1M) on 2 cores
# (taskset -c 0,1); then time to first pixel of a naive render of the 4.47M scene (interior view,
# white sky, 1024x1024, 4 spp, OpenCL on the H200) with each BVH build, twice each.
# Usage: docs/results/raw/h200-2026-12-03-s12/r12-run.sh OUT_DIR
set -uo pipefail
R="${1:?usage: r12-run.sh OUT_DIR}"
mkdir -p "$R" /tmp/r12
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
B=gpu-bundle/bin
G="$PWD/gpu-scenes"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)" | tee "$R/builds.txt"
$B/cohort export "$G/crytek-sponza/sponza.obj.gz" -o /tmp/r12/sponza1m.ply --subdivide 1 >/dev/null
$B/cohort export "$G/crytek-sponza/sponza.obj.gz" -o /tmp/r12/sponza4m.ply --subdivide 2 >/dev/null
built() {  # cores binary scene tree
  taskset -c "$1" "$B/$2" info "/tmp/r12/$3.ply" --tree "$4" 2>&1 | grep -E 'BVH:|kd-tree' | sed -E 's/.*(built in .*)/\1/'
}
for round in 1 2 3; do
  for spec in "0-15 sponza4m" "0,1 sponza1m"; do
    set -- $spec
    for run in "cohort bvh4" "cohort-e541858 bvh4" "cohort compact" "cohort deep" "cohort-d4baeea deep"; do
      read -r bin tree <<<"$run"
      # d4baeea has no --tree: its one tree is the deep one
      if [[ $bin == cohort-d4baeea ]]; then
        echo "$round $2 cores=$1 $bin $tree $(taskset -c "$1" "$B/$bin" info "/tmp/r12/$2.ply" 2>&1 | grep 'kd-tree' | sed -E 's/.*(built in .*)/\1/')"
      else
        echo "$round $2 cores=$1 $bin $tree $(built "$1" "$bin" "$2" "$tree")"
      fi
    done
  done
done 2>&1 | tee -a "$R/builds.txt"
echo /usr/lib/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd
for round in 1 2; do
  for bin in cohort cohort-e541858; do
    start=$EPOCHREALTIME
    "$B/$bin" render /tmp/r12/sponza4m.ply --white-sky --camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60 \
      --res 1024x1024 --spp 4 --method naive --device NVIDIA --stats "$R/render-$bin-$round.json" -o "/tmp/r12/img-$bin.exr" \
      >"$R/render-$bin-$round.log" 2>&1
    end=$EPOCHREALTIME
    echo "$round $bin render wall_s=$(awk -v a="$start" -v b="$end" 'BEGIN{print b-a}')"
  done
done 2>&1 | tee "$R/renders.txt"
