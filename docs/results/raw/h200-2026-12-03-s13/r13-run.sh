#!/usr/bin/env bash
# r13 on the device machine: KD-tree build seconds (`cohort info`, as printed) of this session's
# build (gpu-bundle/bin/cohort: r13a 18f5464, r13b 58918a7) against the one before it
# ($BEFORE, default cohort-f0c4117: the KD build of the twelfth session's HEAD) and d4baeea's
# (cohort-d4baeea, the build issue 26 counts from), in turn, ROUNDS rounds (default 3): Crytek
# Sponza subdivided twice (4.47M) on all 16 cores and subdivided once (1.1M) on 2 cores
# (taskset -c 0,1). The node counts and SAH that `cohort info` prints must agree between this build
# and $BEFORE (the same trees). The fourteenth session's r14 ran it with BEFORE=cohort-1891e04.
# Usage: [ROUNDS=N] [BEFORE=cohort-REV] docs/results/raw/h200-2026-12-03-s13/r13-run.sh OUT_DIR
set -uo pipefail
R="${1:?usage: r13-run.sh OUT_DIR}"
mkdir -p "$R" /tmp/r13
export LD_LIBRARY_PATH="$PWD/gpu-bundle/lib"
B=gpu-bundle/bin
G="$PWD/gpu-scenes"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)" | tee "$R/builds.txt"
$B/cohort export "$G/crytek-sponza/sponza.obj.gz" -o /tmp/r13/sponza1m.ply --subdivide 1 >/dev/null
$B/cohort export "$G/crytek-sponza/sponza.obj.gz" -o /tmp/r13/sponza4m.ply --subdivide 2 >/dev/null
before="${BEFORE:-cohort-f0c4117}"
for round in $(seq "${ROUNDS:-3}"); do
  for spec in "0-15 sponza4m" "0,1 sponza1m"; do
    set -- $spec
    for run in "cohort compact" "cohort deep" "$before compact" "$before deep" "cohort-d4baeea deep"; do
      read -r bin tree <<<"$run"
      # d4baeea has no --tree: its one tree is the deep one
      args=(--tree "$tree")
      [[ $bin == cohort-d4baeea ]] && args=()
      line=$(taskset -c "$1" "$B/$bin" info "/tmp/r13/$2.ply" "${args[@]}" 2>&1 | grep 'kd-tree')
      echo "$round $2 cores=$1 $bin $tree $line"
    done
  done
done 2>&1 | tee -a "$R/builds.txt"
