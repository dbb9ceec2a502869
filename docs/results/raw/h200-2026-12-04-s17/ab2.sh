#!/bin/sh
# ab2.sh ROUNDS REPS A B scenes: 2 threads on CPUs 0,1, alternated; per run min and median per scene
R=$1; N=$2; A=$3; B=$4; shift 4
for r in $(seq $R); do
  for b in $A $B; do
    echo "$b $(taskset -c 0,1 ./bt-$b 2 $N "$@" 2>/dev/null | awk '{print $5, $3}' | tr '\n' ' ')"
  done
done
