#!/usr/bin/env bash
# r8c on the device machine (repo root, gpu-bundle and gpu-scenes carried): the deep KD-tree against
# the 4-wide BVH (with early split clipping) on the H200, naive and sc, 1024x1024 at 64 spp, white
# sky, 3 repetitions: the Crytek Sponza interior and its 4.47M-triangle subdivision (cohort export
# --subdivide 2) through OpenCL and CUDA, and four more models through OpenCL (exterior view).
# Usage: [BACKENDS="opencl cuda"] [OTHERS=1] docs/results/raw/h200-2026-12-03-s8/r8c-run.sh OUT_DIR
set -uo pipefail
R="${1:?usage: r8c-run.sh OUT_DIR}"
mkdir -p "$R" /tmp/r8c
[[ -e /etc/OpenCL/vendors/nvidia.icd ]] || { mkdir -p /etc/OpenCL/vendors; echo /usr/lib/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd; }
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
C=gpu-bundle/bin/cohort
G="$PWD/gpu-scenes"
SP="$G/crytek-sponza/sponza.obj.gz"
timeout 120 $C export "$SP" -o /tmp/r8c/sponza4m.ply --subdivide 2 2>&1 | tail -2
bench() {  # name scene view backend tree
  local d=NVIDIA; [[ $4 == cuda ]] && d=0
  echo "== $1 $4 $5"
  timeout 200 $C bench "$2" --view "$3" --res 1024 --spp 64 --trace-res 1024 --methods naive,sc --reps 3 \
    --tree "$5" --backend "$4" --device "$d" --json "$R/$1-$4-$5.json" 2>&1 | grep -E "tree build|traversal|\| (naive|sc) "
}
{
  for b in ${BACKENDS:-opencl cuda}; do
    for t in deep bvh4; do bench sponza "$SP" interior $b $t; bench sponza4m /tmp/r8c/sponza4m.ply interior $b $t; done
  done
  [[ "${OTHERS:-1}" == 1 ]] || exit 0
  for m in dragon-decimated-100k/dragon.ply armadillo/Armadillo.ply.gz damaged-helmet-gltf/DamagedHelmet.gltf \
           conference/conference.obj.gz; do
    for t in deep bvh4; do bench "$(basename "$(dirname "$m")")" "$G/$m" exterior opencl $t; done
  done
} 2>&1 | tee "$R/log.txt"
