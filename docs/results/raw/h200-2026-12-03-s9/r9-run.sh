#!/usr/bin/env bash
# r9 on the device machine (repo root; gpu-bundle and gpu-scenes carried). Binaries in gpu-bundle/bin:
#   cohort-base (f5f2faa, the BVH as it landed in stop 38), cohort-new1 (79b7d2b: leaf triangles
#   copied into the leaves, near-plane box test, 2 MiB pages), cohort (the working tree: new1 and
#   one- or two-lane steps without the sorting network), cohort-var (the working tree with
#   experiment-only builder knobs: GRID=1|2 splits references at the root box's dyadic planes,
#   SPLITF the area factor); real-base / real4: the host build of the traversal (throwaway
#   harness, protocol rays on 2 threads; real4 = the working tree's traversal with cohort-var's builder).
#   PART builds (not run yet, no device; the bundle then holds cohort-new2 = 64f0fc8 and cohort =
#   main): the BVH build before and after the ninth session's binning changes, `cohort info --tree
#   bvh4` in turn, 3 rounds: bunny subdivided twice and Sponza once (1.1M each) on 2 cores, Sponza
#   twice (4.47M) on 16; then the Sponza interior image from both binaries on OpenCL and CUDA (cmp).
# Usage: r9-run.sh OUT_DIR PART   (PART: gpu | host | splits | pocl | builds; SPONZA_SPP, CONF_SPP for pocl)
set -uo pipefail
R="${1:?usage: r9-run.sh OUT_DIR PART}"; PART="${2:?part}"
mkdir -p "$R" /tmp/r9
[[ -e /etc/OpenCL/vendors/nvidia.icd ]] || { mkdir -p /etc/OpenCL/vendors; echo /usr/lib/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd; }
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
B=gpu-bundle/bin
G="$PWD/gpu-scenes"
SP="$G/crytek-sponza/sponza.obj.gz"
INT="--camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60"
cat /sys/kernel/mm/transparent_hugepage/enabled > "$R/thp-$PART.txt"
case "$PART" in
gpu)
  nvidia-smi --query-gpu=name,driver_version --format=csv | tee "$R/gpu.txt"
  for b in opencl cuda; do
    d=NVIDIA; [[ $b == cuda ]] && d=0
    for round in 1 2; do for c in cohort-base cohort; do
      echo "== $b $c round $round"
      timeout 120 $B/$c bench "$SP" --view interior --res 1024 --spp 64 --trace-res 1024 --methods naive,sc+rg --reps 3 \
        --tree bvh4 --backend "$b" --device "$d" --json "$R/gpu-$b-$c-$round.json" 2>&1 | grep -E "traversal|\| (naive|sc\+rg) "
    done; done
    for c in cohort-base cohort; do
      timeout 60 $B/$c render "$SP" $INT --white-sky --res 256x256 --spp 16 --method sc --tree bvh4 --backend "$b" \
        --device "$d" -o "/tmp/r9/$b-$c.exr" >/dev/null 2>&1
    done
  done 2>&1 | tee "$R/gpu-log.txt"
  for f in opencl-cohort cuda-cohort-base cuda-cohort; do
    cmp /tmp/r9/opencl-cohort-base.exr "/tmp/r9/$f.exr" && echo "opencl-cohort-base.exr == $f.exr" || echo "opencl-cohort-base.exr != $f.exr"
  done 2>&1 | tee "$R/images.txt" ;;
host)
  for round in 1 2 3; do
    for v in "real-base GRID=0" "real4 GRID=0" "real4 GRID=1" "real4 GRID=2"; do
      set -- $v
      echo "== round $round $1 $2"
      env HUGE=1 $2 taskset -c 0,1 timeout 60 $B/$1 "$SP" interior 256 2>&1 | grep -E "sah|per ray|Mrays"
    done
  done 2>&1 | tee "$R/host-log.txt" ;;
splits)
  for round in 1 2 3; do
    for v in "GRID=0" "SPLITF=0.5" "SPLITF=0.25 SPLITD=8" "GRID=1 SPLITF=0.25 SPLITD=8"; do
      echo "== round $round $v"
      env HUGE=1 $v taskset -c 0,1 timeout 60 $B/real4 "$SP" interior 256 2>&1 | grep -E "sah|per ray|Mrays"
    done
  done 2>&1 | tee "$R/splits-log.txt"
  export POCL_CPU_MAX_CU_COUNT=2 POCL_MAX_PTHREAD_COUNT=2
  taskset -c 0,1 timeout 120 $B/cohort-var render "$G/bunny/bun_zipper.ply" --white-sky --res 16x16 --spp 1 \
    --method naive --tree bvh4 --device portable -o /tmp/r9/warm.exr >/dev/null 2>&1
  for round in 1 2 3; do
    for v in "GRID=0" "SPLITF=0.25 SPLITD=8" "SPLITF=0.5"; do
      env $v taskset -c 0,1 timeout 90 $B/cohort-var render "$SP" --white-sky --res 64x64 --spp 256 --method naive \
        --tree bvh4 --device portable $INT -o /tmp/r9/cpu.exr --stats "$R/cpu.json" >/dev/null 2>&1
      echo "$round sponza $v $(python3 -c "import json; j=json.load(open('$R/cpu.json')); print(j['timings']['render_cpu_seconds'], j['timings']['render_seconds'], j['kdtree']['bvh4']['nodes'])")"
    done
  done 2>&1 | tee "$R/splits-pocl-log.txt"
  rm -f "$R/cpu.json" ;;
builds)
  $B/cohort export "$G/bunny/bun_zipper.ply" -o /tmp/r9/bunny16.ply --subdivide 2 >/dev/null
  $B/cohort export "$SP" -o /tmp/r9/sponza1m.ply --subdivide 1 >/dev/null
  $B/cohort export "$SP" -o /tmp/r9/sponza4m.ply --subdivide 2 >/dev/null
  for round in 1 2 3; do
    for c in cohort-new2 cohort; do
      for scene in bunny16 sponza1m; do
        echo "$round $scene 2cores $c $(taskset -c 0,1 $B/$c info /tmp/r9/$scene.ply --tree bvh4 | grep -E 'BVH:' | sed -E 's/.*(built in [0-9.]*s).*/\1/')"
      done
      echo "$round sponza4m 16cores $c $($B/$c info /tmp/r9/sponza4m.ply --tree bvh4 | grep -E 'BVH:' | sed -E 's/.*(built in [0-9.]*s).*/\1/')"
    done
  done 2>&1 | tee "$R/builds.txt"
  for b in opencl cuda; do
    d=NVIDIA; [[ $b == cuda ]] && d=0
    for c in cohort-new2 cohort; do
      timeout 60 $B/$c render "$SP" $INT --white-sky --res 256x256 --spp 16 \
        --method sc --tree bvh4 --backend "$b" --device "$d" -o "/tmp/r9/$b-$c.exr" >/dev/null 2>&1
    done
  done
  for f in opencl-cohort cuda-cohort-new2 cuda-cohort; do
    cmp /tmp/r9/opencl-cohort-new2.exr "/tmp/r9/$f.exr" && echo "opencl-cohort-new2.exr == $f.exr" || echo "opencl-cohort-new2.exr != $f.exr"
  done 2>&1 | tee "$R/images.txt" ;;
pocl)
  export POCL_CPU_MAX_CU_COUNT=2 POCL_MAX_PTHREAD_COUNT=2
  for c in cohort-base cohort-new1 cohort cohort-var; do  # compile each binary's kernels once, untimed
    taskset -c 0,1 timeout 120 $B/$c render "$G/bunny/bun_zipper.ply" --white-sky --res 16x16 --spp 1 --method naive \
      --tree bvh4 --device portable -o /tmp/r9/warm.exr >/dev/null 2>&1
  done
  for round in 1 2 3; do
    for m in crytek-sponza/sponza.obj.gz conference/conference.obj.gz; do
      extra=""; spp=${CONF_SPP:-256}
      [[ $m == crytek* ]] && extra="$INT" && spp=${SPONZA_SPP:-64}
      for v in "cohort-base GRID=0" "cohort-new1 GRID=0" "cohort GRID=0" "cohort-var GRID=1"; do
        set -- $v
        env $2 taskset -c 0,1 timeout 90 $B/$1 render "$G/$m" --white-sky --res 64x64 --spp $spp --method naive \
          --tree bvh4 --device portable $extra -o /tmp/r9/cpu.exr --stats "$R/cpu.json" >/dev/null 2>&1
        echo "$round $(basename "$m") $1 $2 $(python3 -c "import json; j=json.load(open('$R/cpu.json')); print(j['timings']['render_cpu_seconds'], j['timings']['render_seconds'], j['kdtree']['bvh4']['nodes'])")"
      done
    done
  done 2>&1 | tee "$R/pocl-log.txt"
  rm -f "$R/cpu.json" ;;
esac
