#!/bin/bash
# memory_on_gpu.sh — the device run behind issue 14's memory gate: device bytes a body (the
# world's own count, Report::deviceBytes: device buffers, not the pinned readback) for cubes
# 1,000,000 after 30 frames (still falling) in the default and the bullet mode, and settled
# scenes (300 frames) at 112,500 and 32,768. Pack first, from the repository root:
#   ../shared/gpu/pack build/tests/bench/btgpu_bench
#   cp tests/bench/memory_on_gpu.sh tests/bench/gpu_bench_lines.sh .gpu/
# then run  bash .gpu/memory_on_gpu.sh  with carry [".gpu"] (SPECS="n:frames:mode ..." to
# choose; mode default or bullet). One line a run in $OUT/summary.txt: frame, KB a body, pairs.
B=./.gpu/bin/btgpu_bench
STAGES='none'
. "$(dirname "$0")/gpu_bench_lines.sh"
for spec in ${SPECS:-1000000:30:default 1000000:30:bullet 112500:300:default 32768:300:default}; do
  IFS=: read -r n f mode <<<"$spec"
  csv=${OUT:-/tmp}/memory_${n}_${f}_${mode}.csv
  extra=""; [ "$mode" = bullet ] && extra="--bullet-mode"
  one "memory $n f$f $mode" bash .gpu/run $B --scene cubes --n "$n" --frames "$f" --backends btgpu --no-aabb-sync $extra --csv "$csv"
  # device_bytes and pairs by header name (quoted fields, which may hold commas, folded first)
  awk -v n="$n" '{ gsub(/"[^"]*"/, "q"); nf = split($0, f, ",") } NR == 1 { for (i = 1; i <= nf; ++i) col[f[i]] = i; next }
    END { b = f[col["device_bytes"]]; p = f[col["pairs"]]
          printf "   device %.3f KB a body (%d bytes), pairs %d (%.2f a body)\n", b / n / 1000, b, p, p / n }' "$csv" | tee -a "$S"
done
exit 0
