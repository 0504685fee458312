#!/bin/bash
# soft_cost_on_gpu.sh — the device run behind issue 13's cost target: per cube count, build
# b4e1194's bench against this build's soft step and its bullet mode, alternating, two rounds
# (QUADS_OFF=1 adds the soft step with its NVIDIA quads off, BTGPU_SOFT_QUAD=0). GATES=1 then runs
# issue 14's scenes with the peers (stock Bullet, Bullet3's pipeline) in the same process, frames
# 1..300, sleeping on. Pack first, from the repository root:
#   cp <b4e1194's btgpu_bench> build/btgpu_bench_b4
#   ../shared/gpu/pack build/tests/bench/btgpu_bench build/btgpu_bench_b4
#   cp tests/bench/soft_cost_on_gpu.sh tests/bench/gpu_bench_lines.sh .gpu/
# then run  bash .gpu/soft_cost_on_gpu.sh  with carry [".gpu"] (SPECS="n:frames ..." to choose).
# Prints one line a run (median whole frame, step, write-back, the solve stage, the host's
# sync-in and checks, the state hash) and keeps them in $OUT/summary.txt as they come, so a run
# cut short still brings back what it measured.
B=./.gpu/bin/btgpu_bench; B4=./.gpu/bin/btgpu_bench_b4
STAGES='solve|solve_soft|host: sync-in[^|]*|host: checks[^|]*'
. "$(dirname "$0")/gpu_bench_lines.sh"
for spec in ${SPECS:-32768:100 112500:60 1000:150}; do
  n=${spec%%:*}; f=${spec##*:}
  C="--scene cubes --n $n --frames $f --backends btgpu --no-aabb-sync"
  for r in 1 2; do
    one "b4e1194 $n r$r" bash .gpu/run $B4 $C
    one "soft $n r$r" bash .gpu/run $B $C --no-manifolds --soft
    one "bullet $n r$r" bash .gpu/run $B $C --no-manifolds --bullet-mode
    [ -n "$QUADS_OFF" ] && one "soft quads off $n r$r" env BTGPU_SOFT_QUAD=0 bash .gpu/run $B $C --no-manifolds --soft
  done
done
[ -z "$GATES" ] && exit 0
peers() { # label, bench args: one line a backend
  local label=$1; shift
  local out; out=$(timeout 200 bash .gpu/run $B "$@" 2>&1)
  echo "$out" | grep -E '^\| (btgpu|bullet|b3gpu) \|' | awk -F'|' -v l="$label" '{print "== gate", l, $2, "frame", $7, "step", $5, "wb", $6}' | tee -a "$S"
  echo "$out" | grep -iE 'error|invalid|cpu path' | head -3 | tee -a "$S"
}
peers "basic 125" --scene cubes --dims 5 5 5 --frames 300 --backends btgpu,bullet,b3gpu --no-aabb-sync
peers "cubes 1000" --scene cubes --n 1000 --frames 300 --backends btgpu,bullet,b3gpu --no-aabb-sync
peers "cubes 8000" --scene cubes --n 8000 --frames 300 --backends btgpu,bullet,b3gpu --no-aabb-sync --budget-s 40
peers "cubes 32768" --scene cubes --n 32768 --frames 300 --backends btgpu,b3gpu --no-aabb-sync
peers "mixed 32768" --scene mixed --frames 300 --backends btgpu,b3gpu --no-aabb-sync
peers "cubes 32768 aabb-sync" --scene cubes --n 32768 --frames 300 --backends btgpu
exit 0
