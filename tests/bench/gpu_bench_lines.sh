# gpu_bench_lines.sh — sourced by the device-run scripts beside it (soft_cost_on_gpu.sh,
# aabb_sync_on_gpu.sh; copy it into .gpu/ with them): `one LABEL COMMAND...` runs a bench and
# prints one line (median whole frame, step, write-back, the stages whose names match $STAGES,
# the state hash, any error) into $S as it comes, so a run cut short keeps what it measured.
export BTGPU_DEVICE=gpu
S=${OUT:-/tmp}/summary.txt
nvidia-smi -L 2>/dev/null | tee -a "$S"
one() {
  local label=$1; shift
  local out; out=$(timeout 150 "$@" 2>&1)
  local line="== $label: $(echo "$out" | grep -E '^\| btgpu \|' | awk -F'|' '{print "frame", $7, "step", $5, "wb", $6}')"
  line="$line $(echo "$out" | grep -E "^\| ($STAGES) \|" | awk -F'|' '{print $2, $3}' | tr '\n' ' ')"
  line="$line $(echo "$out" | grep -oE 'state hash [0-9a-f]+') $(echo "$out" | grep -iE 'error|invalid' | head -3)"
  echo "$line" | tee -a "$S"
}
