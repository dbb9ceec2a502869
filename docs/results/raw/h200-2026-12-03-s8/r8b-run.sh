#!/usr/bin/env bash
# r8b on the device machine (repo root, gpu-bundle and gpu-scenes carried):
#  1. the H200: the deep KD-tree against the 4-wide BVH (--tree bvh4) with naive and sc, OpenCL and
#     CUDA, Crytek Sponza interior 1024x1024 at 64 spp (cohort bench, protocol rays too), and
#     whether both write the same image bits (256x256, 16 spp renders, cmp);
#  2. the machine's CPU through PoCL on 2 cores (taskset 0,1, two PoCL threads): render CPU seconds
#     of the BVH without and with early split clipping (XF: area factor, XG: gain limit; build-time
#     knobs of this experiment's binary, not of the product), alternating, 3 rounds, five scenes.
# Usage: docs/results/raw/h200-2026-12-03-s8/r8b-run.sh OUT_DIR
set -uo pipefail
R="${1:?usage: r8b-run.sh OUT_DIR}"
mkdir -p "$R" /tmp/r8b-img
[[ -e /etc/OpenCL/vendors/nvidia.icd ]] || { mkdir -p /etc/OpenCL/vendors; echo /usr/lib/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd; }
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
C=gpu-bundle/bin/cohort
G="$PWD/gpu-scenes"
SP="$G/crytek-sponza/sponza.obj.gz"
nvidia-smi --query-gpu=name,driver_version --format=csv | tee "$R/gpu.txt"
$C devices | tee "$R/devices.txt"
for b in opencl cuda; do
  d=NVIDIA; [[ $b == cuda ]] && d=0
  for t in deep bvh4; do
    echo "== bench $b $t"
    timeout 150 $C bench "$SP" --view interior --res 1024 --spp 64 --trace-res 1024 --methods naive,sc --reps 3 \
      --tree "$t" --backend "$b" --device "$d" --json "$R/gpu-$b-$t.json" 2>&1 | tail -8
    timeout 60 $C render "$SP" --camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60 --white-sky --res 256x256 --spp 16 \
      --method sc --tree "$t" --backend "$b" --device "$d" -o "/tmp/r8b-img/$b-$t.exr" --stats "$R/img-$b-$t.json" >/dev/null
  done
done 2>&1 | tee "$R/gpu-log.txt"
for f in opencl-bvh4 cuda-deep cuda-bvh4; do
  cmp /tmp/r8b-img/opencl-deep.exr "/tmp/r8b-img/$f.exr" && echo "opencl-deep.exr == $f.exr" || echo "opencl-deep.exr != $f.exr"
done 2>&1 | tee "$R/images.txt"
export POCL_CPU_MAX_CU_COUNT=2 POCL_MAX_PTHREAD_COUNT=2
for round in 1 2 3; do
  for m in crytek-sponza/sponza.obj.gz dragon-decimated-100k/dragon.ply armadillo/Armadillo.ply.gz \
           damaged-helmet-gltf/DamagedHelmet.gltf conference/conference.obj.gz; do
    extra=""; spp=256
    [[ $m == crytek* ]] && extra="--camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60" && spp=64
    for cfg in "none 1e30 1" "f16 16 1" "f1g08 1 0.8" "f1 1 1"; do
      set -- $cfg
      XF=$2 XG=$3 taskset -c 0,1 timeout 60 $C render "$G/$m" --white-sky --res 64x64 --spp $spp --method naive \
        --tree bvh4 --device portable $extra -o /tmp/r8b-img/cpu.exr --stats "$R/cpu.json" >/dev/null 2>&1
      echo "$round $(basename "$m") $1 $(python3 -c "import json; j=json.load(open('$R/cpu.json')); print(j['timings']['render_cpu_seconds'], j['timings']['render_seconds'], j['kdtree']['bvh4']['nodes'])")"
    done
  done
done 2>&1 | tee "$R/cpu-split.txt"
rm -f "$R/cpu.json"
