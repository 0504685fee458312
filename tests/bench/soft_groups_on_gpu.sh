#!/bin/bash
# soft_groups_on_gpu.sh — the soft step's resident groups in small scenes on a GPU (issue 14:
# BasicDemo's 125 boxes and cubes 1,000 against stock's frame, on the library's default solver):
# each scene at BTGPU_SOFT_CONTACTS_PER_GROUP = 0 (a group per compute unit, as before) and
# smaller counts down to one group, alternating rounds, median frame and the state hash (the
# groups split the same colour ranges: the hashes must agree along a line). Pack first, from the
# repository root:
#   ../shared/gpu/pack build/tests/bench/btgpu_bench && cp tests/bench/soft_groups_on_gpu.sh tests/bench/gpu_bench_lines.sh .gpu/
# then run  bash .gpu/soft_groups_on_gpu.sh  with carry [".gpu"]. Lines go to $OUT/summary.txt.
# ROUNDS (2), PER_GROUP ("0 4096 2048 1024 512 1000000000"), SCENES (below) override. One group
# takes solve_soft's one-group build (plain loads: BTG_SOFT_ONE_GROUP); a line "one group,
# usual build" (BTGPU_SOFT_ONE_GROUP_PLAIN=0) follows each scene's lines.
. "$(dirname "$0")/gpu_bench_lines.sh"
B=${B:-"bash .gpu/run ./.gpu/bin/btgpu_bench"}
ROUNDS=${ROUNDS:-2}
PER_GROUP=${PER_GROUP:-"0 4096 2048 1024 512 1000000000"}
SCENES=${SCENES:-"cubes125:--scene cubes --dims 5 5 5|cubes512:--scene cubes --dims 8 8 8|cubes1000:--scene cubes --n 1000|ragdolls20:--scene ragdolls --ragdolls 20|voronoi:--scene voronoi|cubes8000:--scene cubes --n 8000"}
STAGES="soft_resident"
for r in $(seq "$ROUNDS"); do
  IFS='|' read -ra specs <<< "$SCENES"
  for spec in "${specs[@]}"; do
    name=${spec%%:*}; args=${spec#*:}
    for k in $PER_GROUP; do
      one "r$r $name per-group $k" env BTGPU_SOFT_CONTACTS_PER_GROUP=$k $B $args --frames 300 --backends btgpu --no-aabb-sync --no-manifolds
    done
    one "r$r $name one group, usual build" env BTGPU_SOFT_CONTACTS_PER_GROUP=1000000000 BTGPU_SOFT_ONE_GROUP_PLAIN=0 $B $args --frames 300 --backends btgpu --no-aabb-sync --no-manifolds
  done
done
exit 0
