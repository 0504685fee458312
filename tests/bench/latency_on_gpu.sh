#!/bin/bash
# latency_on_gpu.sh — the device run that measures the solvers' per-contact latency changes of
# 2026-12-05 (README, "Where a GPU's soft step goes"), for the device tool: pack first, from the
# repository root,
#   cp <b4e1194's btgpu_bench> build/btgpu_bench_b4
#   ../shared/gpu/pack build/tests/bench/btgpu_bench build/btgpu_bench_b4
#   cp tests/bench/latency_on_gpu.sh .gpu/
# then run  bash .gpu/latency_on_gpu.sh  with carry [".gpu"]. Prints the solve kernels' registers
# and stack frames (ptxas), then per cube count b4e1194, the bullet mode and the soft step, each
# solver also with BTG_LOAD_CG (ld.global.cg for other groups' data): its state hash must be the
# default's (else the loads are not coherent), its solve stage says what the loads cost.
export BTGPU_DEVICE=gpu
B=./.gpu/bin/btgpu_bench; B4=./.gpu/bin/btgpu_bench_b4
BTGPU_CL_OPTIONS="-cl-nv-verbose" BTGPU_CL_LOG=1 timeout 100 bash .gpu/run $B --scene cubes --n 1000 --frames 3 \
  --backends btgpu --no-aabb-sync --no-manifolds --soft > /tmp/ptxas.txt 2>&1
grep -A3 -E "entry function '(soft_resident|solve_resident)'" /tmp/ptxas.txt | grep -E "entry|stack|Used"
# every function ptxas compiled on its own (one not inlined keeps its pointer arguments' structs in
# local memory: the 1,392-byte stack frame of 2026-12-06 is still unexplained); all of it under $OUT
grep -E "Function properties|stack frame" /tmp/ptxas.txt | grep -B1 -E "[1-9][0-9]* bytes stack" | head -40
[ -n "$OUT" ] && cp /tmp/ptxas.txt "$OUT/" 2>/dev/null
one() { local label=$1; shift; local out; out=$(timeout 100 bash .gpu/run "$@" 2>&1)
  echo "== $label: $(echo "$out" | grep -E '^\| btgpu \|' | awk -F'|' '{print "frame", $7, "step", $5}')" \
       "$(echo "$out" | grep -E '^\| (solve|solve_soft|solve_constraints) ' | awk -F'|' '{print $2, $3}' | tr '\n' ' ')" \
       "$(echo "$out" | grep -oE 'state hash [0-9a-f]+')" "$(echo "$out" | grep -iE 'error|invalid' | head -3)"; }
for spec in ${SPECS:-32768:100 1000:150 112500:60}; do
  n=${spec%%:*}; f=${spec##*:}
  C="--scene cubes --n $n --frames $f --backends btgpu --no-aabb-sync"
  one "b4e1194 $n" $B4 $C
  one "bullet $n" $B $C --no-manifolds
  one "bullet cg $n" env BTGPU_CL_OPTIONS="-DBTG_LOAD_CG=1" bash .gpu/run $B $C --no-manifolds
  one "soft $n" $B $C --no-manifolds --soft
  one "soft cg $n" env BTGPU_CL_OPTIONS="-DBTG_LOAD_CG=1" bash .gpu/run $B $C --no-manifolds --soft
done
exit 0
