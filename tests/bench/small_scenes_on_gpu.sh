#!/bin/bash
# small_scenes_on_gpu.sh — where a small scene's frame goes on a GPU (issue 14: BasicDemo's 125
# boxes and cubes 1,000 against stock's frame): per scene, the frame as it runs and with the
# resident solves on one work-group (BTGPU_RESIDENT_GROUPS=1: local barriers only) at a few group
# sizes, both solver modes; then one profiled run each (BTGPU_PROFILE_KERNELS=1: per-kernel
# medians, their sum against the step, the launches a step). Pack first, from the repository root:
#   ../shared/gpu/pack build/tests/bench/btgpu_bench && cp tests/bench/small_scenes_on_gpu.sh .gpu/
# then run  bash .gpu/small_scenes_on_gpu.sh  with carry [".gpu"]. Lines go to $OUT/summary.txt too.
export BTGPU_DEVICE=gpu
B="bash .gpu/run ./.gpu/bin/btgpu_bench"  # .gpu/run makes the packed libraries and the driver visible
S=${OUT:-/tmp}/summary.txt
nvidia-smi -L 2>/dev/null | tee -a "$S"
one() { # label, env..., -- bench args
  local label=$1; shift
  local out; out=$(timeout 120 env "$@" 2>&1)
  local line="== $label: $(echo "$out" | grep -E '^\| (btgpu|bullet) \|' | awk -F'|' '{print $2, "frame", $7, "step", $5, "wb", $6}' | tr '\n' ' ')"
  line="$line $(echo "$out" | grep -oE 'state hash [0-9a-f]+') $(echo "$out" | grep -iE 'error|invalid|resident' | head -2)"
  echo "$line" | tee -a "$S"
}
prof() {
  local label=$1; shift
  local out; out=$(timeout 120 env BTGPU_PROFILE_KERNELS=1 "$@" 2>&1)
  echo "== profile $label" | tee -a "$S"
  echo "$out" | grep -E '^\| btgpu \|' | awk -F'|' '{print "frame", $7, "step", $5}' | tee -a "$S"
  echo "$out" | awk -F'|' '/stage \| median/{on=1; next} on && /^\| [a-z]/{gsub(/ /,"",$3); n++; if ($2 !~ /host/) s+=$3; print} END{print "kernels", n, "device sum", s}' | head -60 | tee -a "$S"
}
if [ -n "$GROUPS_SWEEP" ]; then
  # the bullet mode's resident solve over BTGPU_RESIDENT_GROUPS groups (one per unit: the default), twice
  for r in 1 2; do
    for spec in "125:--dims 5 5 5" "1000:--n 1000" "8000:--n 8000" "32768:--n 32768"; do
      n=${spec%%:*}; a=${spec#*:}
      for g in $GROUPS_SWEEP; do
        one "sweep r$r $n groups $g" BTGPU_RESIDENT_GROUPS=$g $B --scene cubes $a --frames 200 --backends btgpu --no-aabb-sync --no-manifolds
      done
    done
  done
  exit 0
fi
for spec in "125:--dims 5 5 5" "1000:--n 1000" "8000:--n 8000"; do
  n=${spec%%:*}; a=${spec#*:}
  C="--scene cubes $a --frames 300 --backends btgpu --no-aabb-sync --no-manifolds"
  for mode in "" "--soft"; do
    one "$n $mode default" $B $C $mode
    one "$n $mode 1 group" BTGPU_RESIDENT_GROUPS=1 $B $C $mode
    one "$n $mode 1 group of 1024" BTGPU_RESIDENT_GROUPS=1 BTGPU_RESIDENT_GROUP_SIZE=1024 $B $C $mode
    one "$n $mode 8 groups" BTGPU_RESIDENT_GROUPS=8 $B $C $mode
  done
  [ "$n" = 8000 ] && continue
  prof "$n bullet" $B $C
  prof "$n bullet 1 group" BTGPU_RESIDENT_GROUPS=1 $B $C
done
one "125 with stock" $B --scene cubes --dims 5 5 5 --frames 300 --backends btgpu,bullet --no-aabb-sync
exit 0
