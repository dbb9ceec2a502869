#!/usr/bin/env bash
# r9g on the device machine: the BVH build before (cohort-new2: 64f0fc8's builder) and after the
# ninth session's binning changes (cohort: eb6e0e8), `cohort info --tree bvh4` build seconds, in
# turn, 3 rounds: bunny subdivided twice and Sponza once (1.1M each) on 2 cores (taskset -c 0,1),
# Sponza twice (4.47M) on 16 cores; then the Sponza interior image through the new build on
# OpenCL and CUDA against the old binary's (cmp). Usage: r9g-run.sh OUT_DIR
set -uo pipefail
R="${1:?usage: r9g-run.sh OUT_DIR}"
mkdir -p "$R" /tmp/r9g
[[ -e /etc/OpenCL/vendors/nvidia.icd ]] || { mkdir -p /etc/OpenCL/vendors; echo /usr/lib/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd; }
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
B=gpu-bundle/bin
G="$PWD/gpu-scenes"
SP="$G/crytek-sponza/sponza.obj.gz"
$B/cohort export "$G/bunny/bun_zipper.ply" -o /tmp/r9g/bunny16.ply --subdivide 2 >/dev/null
$B/cohort export "$SP" -o /tmp/r9g/sponza1m.ply --subdivide 1 >/dev/null
$B/cohort export "$SP" -o /tmp/r9g/sponza4m.ply --subdivide 2 >/dev/null
for round in 1 2 3; do
  for c in cohort-new2 cohort; do
    for scene in bunny16 sponza1m; do
      echo "$round $scene 2cores $c $(taskset -c 0,1 $B/$c info /tmp/r9g/$scene.ply --tree bvh4 | grep -E 'BVH:' | sed -E 's/.*(built in [0-9.]*s).*/\1/')"
    done
    echo "$round sponza4m 16cores $c $($B/$c info /tmp/r9g/sponza4m.ply --tree bvh4 | grep -E 'BVH:' | sed -E 's/.*(built in [0-9.]*s).*/\1/')"
  done
done 2>&1 | tee "$R/builds.txt"
for b in opencl cuda; do
  d=NVIDIA; [[ $b == cuda ]] && d=0
  for c in cohort-new2 cohort; do
    timeout 60 $B/$c render "$SP" --camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60 --white-sky --res 256x256 --spp 16 \
      --method sc --tree bvh4 --backend "$b" --device "$d" -o "/tmp/r9g/$b-$c.exr" >/dev/null 2>&1
  done
done
for f in opencl-cohort cuda-cohort-new2 cuda-cohort; do
  cmp /tmp/r9g/opencl-cohort-new2.exr "/tmp/r9g/$f.exr" && echo "opencl-cohort-new2.exr == $f.exr" || echo "opencl-cohort-new2.exr != $f.exr"
done 2>&1 | tee "$R/images.txt"
