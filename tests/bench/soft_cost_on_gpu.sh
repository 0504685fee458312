#!/bin/bash
# soft_cost_on_gpu.sh — the device run behind issue 13's cost target: per cube count, build
# b4e1194's bench against this build's soft step (as it runs, and with its NVIDIA quads off,
# BTGPU_SOFT_QUAD=0), alternating, two rounds. Pack first, from the repository root:
#   cp <b4e1194's btgpu_bench> build/btgpu_bench_b4
#   ../shared/gpu/pack build/tests/bench/btgpu_bench build/btgpu_bench_b4
#   cp tests/bench/soft_cost_on_gpu.sh .gpu/
# then run  bash .gpu/soft_cost_on_gpu.sh  with carry [".gpu"] (SPECS="n:frames ..." to choose).
# Prints one line a run (median whole frame, step, write-back, the solve stage, the host's
# sync-in and checks, the state hash) and keeps them in $OUT/summary.txt as they come, so a run
# cut short still brings back what it measured.
export BTGPU_DEVICE=gpu
B=./.gpu/bin/btgpu_bench; B4=./.gpu/bin/btgpu_bench_b4
S=${OUT:-/tmp}/summary.txt
nvidia-smi -L 2>/dev/null | tee -a "$S"
one() {
  local label=$1; shift
  local out; out=$(timeout 150 "$@" 2>&1)
  local line="== $label: $(echo "$out" | grep -E '^\| btgpu \|' | awk -F'|' '{print "frame", $7, "step", $5, "wb", $6}')"
  line="$line $(echo "$out" | grep -E '^\| (solve|solve_soft|host: sync-in[^|]*|host: checks[^|]*) \|' | awk -F'|' '{print $2, $3}' | tr '\n' ' ')"
  line="$line $(echo "$out" | grep -oE 'state hash [0-9a-f]+') $(echo "$out" | grep -iE 'error|invalid' | head -3)"
  echo "$line" | tee -a "$S"
}
for spec in ${SPECS:-32768:100 112500:60 1000:150}; do
  n=${spec%%:*}; f=${spec##*:}
  C="--scene cubes --n $n --frames $f --backends btgpu --no-aabb-sync"
  for r in 1 2; do
    one "b4e1194 $n r$r" bash .gpu/run $B4 $C
    one "soft $n r$r" bash .gpu/run $B $C --no-manifolds --soft
    one "soft quads off $n r$r" env BTGPU_SOFT_QUAD=0 bash .gpu/run $B $C --no-manifolds --soft
  done
done
exit 0
