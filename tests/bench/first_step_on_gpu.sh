#!/bin/bash
# first_step_on_gpu.sh — issue 14's first-frame and large-scene figures on a GPU, with an A/B of
# the frame against an earlier build's bench (.gpu/bin/btgpu_bench_prev) alternating on the same
# machine. Pack first, from the repository root:
#   cp OLD_BUILD/tests/bench/btgpu_bench build/btgpu_bench_prev
#   ../shared/gpu/pack build/tests/bench/btgpu_bench build/btgpu_bench_prev && cp tests/bench/first_step_on_gpu.sh .gpu/
# then run  bash .gpu/first_step_on_gpu.sh  with carry [".gpu"]. One line a run goes to $OUT/summary.txt.
# ROUNDS (A/B rounds, 2), M1 (runs at 1,000,000 cubes, 2) and GATES=0 (skip the peers' scenes)
# trim it to a short device lease. The runs after the A/B take the library's default solver (Auto).
export BTGPU_DEVICE=gpu
R="bash .gpu/run"
O=${OUT:-/tmp}
S=$O/summary.txt
nvidia-smi -L > "$S" 2>&1; nproc >> "$S"
line() { # file, label: the backends' rows, then btgpu's first step, state hash and fill
  grep -h -E "^\| (btgpu|bullet|b3gpu) \|" "$1" | awk -F'|' -v l="$2" '{print l, $2, "frame", $7, "step", $5, "wb", $6, "setup/first", $9, "MB", $13}' >> "$S"
  grep -h -oE "first step [0-9]+ ms[^;]*|state hash [0-9a-f]+|of it the manifold fill \| [0-9.]+" "$1" | tr '\n' ' ' >> "$S"; echo >> "$S"
}
t0=$(date +%s)
# the driver's cache warmed (a fresh machine compiles every program once)
timeout 200 $R ./.gpu/bin/btgpu_bench --scene cubes --n 1000 --frames 20 --backends btgpu --no-aabb-sync > "$O/warm.txt" 2>&1
echo "warm-up $(( $(date +%s)-t0 )) s" >> "$S"
if [ -x .gpu/bin/btgpu_bench_prev ]; then
  for r in $(seq 1 "${ROUNDS:-2}"); do
    for b in btgpu_bench_prev btgpu_bench; do
      # the bullet mode on both (an earlier bench's default; this one's takes --bullet-mode)
      m=$([ $b = btgpu_bench ] && echo --bullet-mode)
      timeout 60 $R ./.gpu/bin/$b --scene cubes --n 8000 --frames 200 --backends btgpu --no-aabb-sync $m > "$O/ab8k_${b}_$r.txt" 2>&1
      line "$O/ab8k_${b}_$r.txt" "AB 8000 r$r $b"
      timeout 90 $R ./.gpu/bin/$b --scene cubes --n 32768 --frames 150 --backends btgpu --no-aabb-sync $m > "$O/ab32k_${b}_$r.txt" 2>&1
      line "$O/ab32k_${b}_$r.txt" "AB 32768 r$r $b"
    done
  done
fi
B="$R ./.gpu/bin/btgpu_bench"
for i in $(seq 1 "${M1:-2}"); do
  timeout 150 $B --scene cubes --n 1000000 --frames 30 --backends btgpu --no-aabb-sync > "$O/m1_$i.txt" 2>&1; line "$O/m1_$i.txt" "1M run $i"
done
timeout 90 $B --scene cubes --n 112500 --frames 60 --backends btgpu --no-aabb-sync > "$O/k112.txt" 2>&1; line "$O/k112.txt" "112500"
[ "${GATES:-1}" = 0 ] && { echo "total $(( $(date +%s)-t0 )) s" >> "$S"; exit 0; }
timeout 60 $B --scene cubes --dims 5 5 5 --frames 300 --backends btgpu,bullet,b3gpu --no-aabb-sync > "$O/c125.txt" 2>&1; line "$O/c125.txt" "125"
timeout 60 $B --scene cubes --n 1000 --frames 200 --backends btgpu,b3gpu --no-aabb-sync > "$O/c1k.txt" 2>&1; line "$O/c1k.txt" "1000"
timeout 120 $B --scene cubes --n 32768 --frames 150 --backends b3gpu --no-aabb-sync > "$O/c32k.txt" 2>&1; line "$O/c32k.txt" "32768"
timeout 120 $B --scene mixed --frames 150 --backends btgpu,b3gpu --no-aabb-sync > "$O/mixed.txt" 2>&1; line "$O/mixed.txt" "mixed"
echo "total $(( $(date +%s)-t0 )) s" >> "$S"
