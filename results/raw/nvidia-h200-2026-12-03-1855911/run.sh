#!/usr/bin/env bash
# r10 on the device machine (repo root; gpu-bundle and gpu-scenes carried). gpu-bundle/bin holds
# cohort-base (1855911, main) and cohort (445e935: the BVH walk prefetches the children it
# pushes on CPU devices). Usage: run.sh OUT_DIR
#   1. PoCL on 2 pinned cores of the GPU machine's CPU: render CPU seconds (--stats) of naive, 64x64,
#      white sky: Sponza interior at 256 spp, the conference at 2048 spp; 3 rounds, binaries in turn.
#   2. The H200: the Sponza interior image (sc, 256x256, 16 spp) from both binaries on OpenCL and CUDA
#      (cmp: the prefetch is compiled out on GPUs), and one `cohort bench` round per binary on OpenCL.
set -uo pipefail
R="${1:?usage: run.sh OUT_DIR}"
mkdir -p "$R" /tmp/r10
[[ -e /etc/OpenCL/vendors/nvidia.icd ]] || { mkdir -p /etc/OpenCL/vendors; echo /usr/lib/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd; }
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
B=gpu-bundle/bin
G="$PWD/gpu-scenes"
SP="$G/crytek-sponza/sponza.obj.gz"
CONF="$G/conference/conference.obj.gz"
INT="--camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60"
(
  export POCL_CPU_MAX_CU_COUNT=2 POCL_MAX_PTHREAD_COUNT=2
  for c in cohort-base cohort; do
    taskset -c 0,1 timeout 120 $B/$c render "$CONF" --white-sky --res 16x16 --spp 1 --method naive --tree bvh4 \
      --device portable -o /tmp/r10/warm.exr >/dev/null 2>&1
  done
  for round in 1 2 3; do
    for c in cohort-base cohort; do
      for v in "sponza $SP 256" "conference $CONF 2048"; do
        set -- $v
        view=""; [[ $1 == sponza ]] && view="$INT"
        taskset -c 0,1 timeout 120 $B/$c render "$2" $view --white-sky --res 64x64 --spp "$3" --method naive \
          --tree bvh4 --device portable -o "/tmp/r10/cpu-$1-$c.exr" --stats "$R/cpu.json" >/dev/null 2>&1
        echo "$round $1 $c $(python3 -c "import json; j=json.load(open('$R/cpu.json')); print(j['timings']['render_cpu_seconds'], j['timings']['render_seconds'])")"
      done
    done
  done
  for s in sponza conference; do
    cmp "/tmp/r10/cpu-$s-cohort-base.exr" "/tmp/r10/cpu-$s-cohort.exr" && echo "pocl $s: same image" || echo "pocl $s: images differ"
  done
  rm -f "$R/cpu.json"
) 2>&1 | tee "$R/pocl-log.txt"
(
  nvidia-smi --query-gpu=name,driver_version --format=csv
  for b in opencl cuda; do
    d=NVIDIA; [[ $b == cuda ]] && d=0
    for c in cohort-base cohort; do
      timeout 60 $B/$c render "$SP" $INT --white-sky --res 256x256 --spp 16 --method sc --tree bvh4 --backend "$b" \
        --device "$d" -o "/tmp/r10/$b-$c.exr" >/dev/null 2>&1
    done
  done
  for f in opencl-cohort cuda-cohort-base cuda-cohort; do
    cmp /tmp/r10/opencl-cohort-base.exr "/tmp/r10/$f.exr" && echo "opencl-cohort-base.exr == $f.exr" || echo "opencl-cohort-base.exr != $f.exr"
  done
  for c in cohort-base cohort; do
    echo "== opencl $c"
    timeout 120 $B/$c bench "$SP" --view interior --res 1024 --spp 64 --trace-res 1024 --methods naive,sc+rg --reps 3 \
      --tree bvh4 --backend opencl --device NVIDIA --json "$R/gpu-$c.json" 2>&1 | grep -E "traversal|\| (naive|sc\+rg) "
  done
) 2>&1 | tee "$R/gpu-log.txt"
