#!/bin/bash
# flows_on_gpu.sh — the measurement that decided the flows (README, "The flows": on an H100,
# 2026-12-05, slower and not bitwise, so BTGPU_SOFT_FLOW / BTGPU_PGS_FLOW now act on CPU devices
# only, and on a GPU this script's flow runs repeat the runs without them; to measure the flows
# there again, lift that rule in softFlow / pgsFlow first). For the device tool: pack first,
# from the repository root,
#   cp <b4e1194's btgpu_bench> build/btgpu_bench_b4
#   ../shared/gpu/pack build/tests/bench/btgpu_bench build/btgpu_bench_b4 build/tests/btgpu_unit_tests
#   cp tests/bench/flows_on_gpu.sh .gpu/
# then run  SPECS="32768:150 1000:300" bash .gpu/flows_on_gpu.sh  with carry [".gpu"].
# First the launch-shape unit tests (bitwise with real concurrency), then per cube count: b4e1194,
# the soft step without and with the flows, the bullet mode without and with its flow; then the
# repeats. Runs past LIMIT seconds (default 400) are skipped, so the call ends within the tool's limit.
export BTGPU_DEVICE=gpu
B=./.gpu/bin/btgpu_bench; B4=./.gpu/bin/btgpu_bench_b4  # b4e1194: the cost yardstick of issue 13
T0=$(date +%s)
run() { # label, cmd...
  local label=$1; shift
  if [ $(( $(date +%s) - T0 )) -gt ${LIMIT:-400} ]; then echo "== $label skipped (time)"; return; fi
  local t0=$(date +%s)
  local out; out=$(timeout 200 "$@" 2>&1)
  echo "== $label ($(( $(date +%s) - t0 )) s)"
  echo "$out" | grep -E '^\| btgpu \|' | awk -F'|' '{print "frame med total:", $7, " step:", $5, " first:", $9}'
  echo "$out" | grep -oE 'state hash [0-9a-f]+|redone steps [0-9]+|colors [0-9]+' | tr '\n' ' '; echo
  echo "$out" | grep -E '^\| (solve_soft|solve_constraints|host: enqueue|color_constraints|narrowphase_sat|host: write-back|host: sync-in) ' | tr '\n' ' '; echo
  [ -n "$FULL" ] && echo "$out" | grep -E '^\| [a-z_:]' | head -30
  echo "$out" | grep -iE "error|timed out|resident" | head -3
}
echo "== unit flows"; timeout 150 bash .gpu/run ./.gpu/bin/btgpu_unit_tests --gtest_filter='*OneResidentLaunch*:*LaunchShapes*:SolveSoft.*:PrepareJoints.SolveWith*' 2>&1 | grep -E "OK \]|FAILED|Failure|timed out|device:" | head -30
for spec in $SPECS; do
  n=${spec%%:*}; f=${spec##*:}
  C="--scene cubes --n $n --frames $f --backends btgpu --no-aabb-sync"
  run "b4 $n" bash .gpu/run $B4 $C
  run "soft $n" bash .gpu/run $B $C --soft --no-manifolds
  run "soft flow2 $n" env BTGPU_SOFT_FLOW=2 bash .gpu/run $B $C --soft --no-manifolds
  run "bullet $n" bash .gpu/run $B $C --no-manifolds
  run "bullet flow $n" env BTGPU_PGS_FLOW=1 bash .gpu/run $B $C --no-manifolds
  run "soft flow1 $n" env BTGPU_SOFT_FLOW=1 bash .gpu/run $B $C --soft --no-manifolds
done
for spec in $SPECS; do
  n=${spec%%:*}; f=${spec##*:}
  C="--scene cubes --n $n --frames $f --backends btgpu --no-aabb-sync"
  run "b4 $n again" bash .gpu/run $B4 $C
  run "soft flow2 $n again" env BTGPU_SOFT_FLOW=2 bash .gpu/run $B $C --soft --no-manifolds
  run "soft $n again" bash .gpu/run $B $C --soft --no-manifolds
  run "bullet flow $n again" env BTGPU_PGS_FLOW=1 bash .gpu/run $B $C --no-manifolds
done
exit 0
