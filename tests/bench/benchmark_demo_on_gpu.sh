#!/bin/bash
# benchmark_demo_on_gpu.sh — issue 14's gate "Bullet's BenchmarkDemo 1-8 >= stock each" on a GPU:
# btgpu_demos runs each of BenchmarkDemo's eight tests (the scene library's, tests/scenes) on
# stock btDiscreteDynamicsWorld and on btGpuDynamicsWorld in the same process, 300 steps, median
# ms a step each (btgpu's first step apart; the whole stepSimulation: manifolds filled, Bullet's
# broadphase kept current, as an app gets them), on the library's default solver and the bullet
# mode, sleeping on (Bullet's) and off (--no-sleep). Pack first, from the repository root:
#   ../shared/gpu/pack build/demos/btgpu_demos && cp tests/bench/benchmark_demo_on_gpu.sh .gpu/
# then run  bash .gpu/benchmark_demo_on_gpu.sh  with carry [".gpu"]. Lines go to $OUT/summary.txt.
# DEMOS, RUNS ("auto:|bullet:|auto:--no-sleep|bullet:--no-sleep") and STEPS (300) override.
S=${OUT:-/tmp}/summary.txt
nvidia-smi -L 2>/dev/null | tee -a "$S"
D=${D:-"bash .gpu/run ./.gpu/bin/btgpu_demos"}
DEMOS=${DEMOS:-"pile stacks ragdolls hulls mixed landscape raycast voronoi"}
RUNS=${RUNS:-"auto:|bullet:|auto:--no-sleep|bullet:--no-sleep"}
STEPS=${STEPS:-300}
IFS='|' read -ra runs <<< "$RUNS"
for run in "${runs[@]}"; do
  solver=${run%%:*}; extra=${run#*:}
  for d in $DEMOS; do
    out=$(timeout 200 $D --demo "$d" --steps "$STEPS" --no-chaos --device "${DEVICE:-gpu}" --solver "$solver" $extra 2>&1)
    stock=$(echo "$out" | awk '/^stock /{print $2}')
    gpu=$(echo "$out" | awk '/^btgpu /{print $2}')
    ratio=$(awk -v s="$stock" -v g="$gpu" 'BEGIN{if (g > 0) printf "%.2f", s / g; else print "-"}')
    echo "== $d $solver $extra: stock $stock btgpu $gpu ms/step (stock/btgpu $ratio) $(echo "$out" | grep -E '^(path|solver|ray ms|state hash)' | tr -s ' ' | tr '\n' ';') $(echo "$out" | grep -iE 'error|invalid' | head -2)" | tee -a "$S"
  done
done
exit 0
