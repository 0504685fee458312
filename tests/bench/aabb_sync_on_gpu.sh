#!/bin/bash
# aabb_sync_on_gpu.sh — the default config's cost on a GPU's host (issue 14's gate: the frame
# with Bullet's broadphase kept current <= 1.2x the frame without it): an older build's bench
# (before the side-thread AABB sync) against this build's, alternating, two rounds, cubes 32,768
# and 8,000 with and without the sync; then one profiled run of this build per size
# (BTGPU_PROFILE_KERNELS=1: every stage's median, in $OUT/profile_<n>.txt). Pack first:
#   cp <older btgpu_bench> build/btgpu_bench_base
#   ../shared/gpu/pack build/tests/bench/btgpu_bench build/btgpu_bench_base [build/tests/btgpu_unit_tests]
#   cp tests/bench/aabb_sync_on_gpu.sh tests/bench/gpu_bench_lines.sh .gpu/
# then run  bash .gpu/aabb_sync_on_gpu.sh  with carry [".gpu"]. Lines go to $OUT/summary.txt.
B=./.gpu/bin/btgpu_bench; BB=./.gpu/bin/btgpu_bench_base
STAGES="host: (Bullet.s broadphase AABB sync|write-back, of it the manifold fill)[^|]*"
. "$(dirname "$0")/gpu_bench_lines.sh"
# the unit tests of the kernels a build changed, on the GPU (packed beside the benches: UNITS)
if [ -x ./.gpu/bin/btgpu_unit_tests ]; then
  timeout 300 bash .gpu/run ./.gpu/bin/btgpu_unit_tests --gtest_filter="${UNITS:-*}" > "${OUT:-/tmp}/units.txt" 2>&1
  grep -E "PASSED|FAILED|tests ran" "${OUT:-/tmp}/units.txt" | tee -a "$S"
fi
for spec in ${SPECS:-32768:200 8000:200}; do
  n=${spec%%:*}; f=${spec##*:}
  C="--scene cubes --n $n --frames $f --backends btgpu"
  for r in 1 2; do
    one "base $n sync r$r" bash .gpu/run $BB $C
    one "head $n sync r$r" bash .gpu/run $B $C
    one "base $n nosync r$r" bash .gpu/run $BB $C --no-aabb-sync
    one "head $n nosync r$r" bash .gpu/run $B $C --no-aabb-sync
  done
done
[ -n "$NO_PROFILE" ] && exit 0
for n in 8000 32768; do
  timeout 150 env BTGPU_PROFILE_KERNELS=1 bash .gpu/run $B --scene cubes --n $n --frames 200 --backends btgpu --no-aabb-sync > "${OUT:-/tmp}/profile_$n.txt" 2>&1
done
exit 0
