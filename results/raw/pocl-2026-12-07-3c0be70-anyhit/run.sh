#!/usr/bin/env bash
# Any-hit walks farthest child first (DIR/cohort) beside the build before (DIR/cohort-base): renders
# with shadow rays (an environment map), the two builds in turn, 5 rounds. Run from the repo root.
set -u
DIR=${1:?the folder with cohort and cohort-base}
E=results/raw/pocl-2026-12-03-445e935/peers-base/pocl/mitsuba/conference-exterior-mitsuba.exr
for r in 1 2 3 4 5; do for b in cohort-base cohort; do
  $DIR/$b render gpu-scenes/crytek-sponza/sponza.obj.gz --env $E --camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 \
    --res 128x128 --spp 64 -o /tmp/spm-$b --stats results/raw/pocl-2026-12-07-3c0be70-anyhit/sponza-env/$b-$r.json
done; done
for r in 1 2 3 4 5; do for b in cohort-base cohort; do
  $DIR/$b render ../shared/scenes/dragon-decimated-100k/dragon.ply --env $E --res 128x128 --spp 64 \
    -o /tmp/dr-$b --stats results/raw/pocl-2026-12-07-3c0be70-anyhit/dragon-env/$b-$r.json
done; done
