#!/usr/bin/env bash
# r8a on the device machine (repo root, gpu-bundle and gpu-scenes carried): every method on both
# backends (PARTS=methods scripts/gpu-methods-run), then three `cohort render --method auto` per
# backend on the same workload as bench's interior view (camera bounds and fov of interior_view()).
# Usage: docs/results/raw/h200-2026-12-03-s8/r8a-run.sh OUT_DIR
set -uo pipefail
R="${1:?usage: r8a-run.sh OUT_DIR}"
mkdir -p "$R" /tmp/r8a-img
PARTS=methods scripts/gpu-methods-run "$R" ""
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
S="$PWD/gpu-scenes/crytek-sponza/sponza.obj.gz"
for b in opencl cuda; do
  d=NVIDIA; [[ $b == cuda ]] && d=0
  for i in 1 2 3; do
    echo "== render --method auto, $b, $i"
    timeout 60 gpu-bundle/bin/cohort render "$S" --camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60 --white-sky \
      --res 1024x1024 --spp 64 --method auto --backend "$b" --device "$d" \
      --stats "$R/auto-$b-$i.json" -o "/tmp/r8a-img/auto-$b-$i.exr"
  done
done 2>&1 | tee "$R/render-log.txt"
