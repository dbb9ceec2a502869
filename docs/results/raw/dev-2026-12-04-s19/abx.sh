#!/bin/sh
# abx.sh A B ROUNDS scene : fresh process per build, alternating, prints per-round ratio B/A
A=$1; B=$2; R=$3; S=$4
for r in $(seq $R); do
  a=$(taskset -c 0,1 ./bt-$A 2 1 $S | awk '{print $3}')
  b=$(taskset -c 0,1 ./bt-$B 2 1 $S | awk '{print $3}')
  echo "$a $b $(python3 -c "print(round($b/$a,3))")"
done | tee /dev/stderr | python3 -c "
import sys,statistics; r=[float(l.split()[2]) for l in sys.stdin]; a=[float(l.split()[0]) for l in open('/dev/null')] 
print('median ratio', statistics.median(r), 'n', len(r))"
