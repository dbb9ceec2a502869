#!/usr/bin/env bash
# run-b on the device machine (repo root; gpu-bundle and gpu-scenes carried): would the H200 gain from
# 64-byte BVH nodes (planes quantised to 8 bits, docs/results.md "work of 2026-12-03", not in the tree)?
# gpu-bundle/bin: cohort (6b585a9's code) and cohort-quant (1855911 with the quantised nodes, an
# experiment-only build). `cohort bench` Sponza interior 1024x1024 at 64 spp, protocol rays 1024x1024,
# naive and sc+rg, --tree bvh4, two rounds alternating the binaries, OpenCL then CUDA; then the sc image
# from both on both backends (cmp). Usage: run-b.sh OUT_DIR
set -uo pipefail
R="${1:?usage: run-b.sh OUT_DIR}"
mkdir -p "$R" /tmp/r10
[[ -e /etc/OpenCL/vendors/nvidia.icd ]] || { mkdir -p /etc/OpenCL/vendors; echo /usr/lib/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd; }
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
B=gpu-bundle/bin
SP="$PWD/gpu-scenes/crytek-sponza/sponza.obj.gz"
INT="--camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60"
(
  for b in opencl cuda; do
    d=NVIDIA; [[ $b == cuda ]] && d=0
    for round in 1 2; do for c in cohort cohort-quant; do
      echo "== $b $c round $round"
      timeout 120 $B/$c bench "$SP" --view interior --res 1024 --spp 64 --trace-res 1024 --methods naive,sc+rg --reps 3 \
        --tree bvh4 --backend "$b" --device "$d" --json "$R/gpu-$b-$c-$round.json" 2>&1 | grep -E "traversal|\| (naive|sc\+rg) "
    done; done
    for c in cohort cohort-quant; do
      timeout 60 $B/$c render "$SP" $INT --white-sky --res 256x256 --spp 16 --method sc --tree bvh4 --backend "$b" \
        --device "$d" -o "/tmp/r10/$b-$c.exr" >/dev/null 2>&1
    done
  done
  for f in opencl-cohort-quant cuda-cohort cuda-cohort-quant; do
    cmp /tmp/r10/opencl-cohort.exr "/tmp/r10/$f.exr" && echo "opencl-cohort.exr == $f.exr" || echo "opencl-cohort.exr != $f.exr"
  done
) 2>&1 | tee "$R/gpu-log.txt"
