#!/usr/bin/env bash
# r9e on the device machine (as r8f, after the ninth session's traversal changes, 64f0fc8): every method that can trace the 4-wide BVH, through it (cohort bench
# --tree bvh4, Crytek Sponza interior, 1024x1024, 64 spp, 3 repetitions), OpenCL and CUDA, and three
# `render --method auto` per backend (--tree auto: the BVH; auto then probes naive, wavefront, sc,
# rg and sc+rg). Usage: docs/results/raw/h200-2026-12-03-s9/r9e-run.sh OUT_DIR
set -uo pipefail
R="${1:?usage: r9e-run.sh OUT_DIR}"
mkdir -p "$R" /tmp/r9e
[[ -e /etc/OpenCL/vendors/nvidia.icd ]] || { mkdir -p /etc/OpenCL/vendors; echo /usr/lib/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd; }
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
C=gpu-bundle/bin/cohort
SP="$PWD/gpu-scenes/crytek-sponza/sponza.obj.gz"
for b in opencl cuda; do
  d=NVIDIA; [[ $b == cuda ]] && d=0
  echo "== bench $b"
  timeout 200 $C bench "$SP" --view interior --res 1024 --spp 64 --no-traversal --methods naive,wavefront,sc,rg,sc+rg \
    --reps 3 --tree bvh4 --backend "$b" --device "$d" --json "$R/bench-$b.json" 2>&1 | grep -E "\| "
  for i in 1 2 3; do
    timeout 60 $C render "$SP" --camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60 --white-sky --res 1024x1024 --spp 64 \
      --method auto --backend "$b" --device "$d" --stats "$R/auto-$b-$i.json" -o "/tmp/r9e/auto-$b-$i.exr" >/dev/null
    python3 -c "import json; j=json.load(open('$R/auto-$b-$i.json')); a=j['auto']; print('auto $b $i', j['kdtree']['kind'], a['method'], round(j['rays_per_second']/1e6,1), {k: round(v/1e6,1) for k, v in a['final_rays_per_second'].items()})"
  done
done 2>&1 | tee "$R/log.txt"
