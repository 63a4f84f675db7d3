#!/usr/bin/env bash
# The MotionBenchMaker Panda run (reproduce.sh's `mbm` table) spread over the GPUs of one
# host: shards of gplan-bench --shard, one per GPU at a time, each pinned to its own
# share of the cores (taskset), so that every shard runs as on a machine of one GPU and
# cores/GPUs cores. Then, or later, the shards joined into one run and summarised.
#
#   benchmarks/scripts/mbm_shards.sh run OUT_DIR FIRST LAST TOTAL
#       shards FIRST..LAST of TOTAL (1-based), round after round over the visible GPUs,
#       into OUT_DIR/shard_I/ (reproduce.sh's output: mbm/, machine.txt, the log)
#   benchmarks/scripts/mbm_shards.sh join OUT_DIR
#       OUT_DIR/mbm/results.csv: every shard's records (one header), and gplan-bench
#       --report over them (summary.txt, plots); a shard whose run was stopped counts
#       with the runs it had done (results.partial.csv), and the join says so
#
# Environment: as reproduce.sh (GPU_BUNDLE, MBM_FIRST, MBM_SCENARIOS, BENCH_SECONDS: a
# shard is stopped after this long, its runs done kept); join: MBM_CONFIG, the
# configuration summarised (default benchmarks/config/motionbenchmaker_panda.yaml),
# GPLAN_BENCH, the program (default build/apps/gplan-bench).
set -euo pipefail

say() { echo "[mbm_shards $(date +%H:%M:%S)] $*" >&2; }
root=$(cd "$(dirname "$0")/../.." && pwd)
mode=${1:-}
case $mode in
  run)
    [ $# -eq 5 ] || { echo "usage: $0 run OUT_DIR FIRST LAST TOTAL" >&2; exit 2; }
    out=$2 first=$3 last=$4 total=$5
    mkdir -p "$out"
    gpus=$(nvidia-smi -L 2>/dev/null | wc -l)
    [ "$gpus" -gt 0 ] || { echo "mbm_shards.sh: no GPU (nvidia-smi -L lists none)" >&2; exit 2; }
    cores=$(nproc)
    per=$((cores / gpus))
    say "$gpus GPUs, $cores cores: $per cores a shard"
    shard=$first
    while [ "$shard" -le "$last" ]; do
      pids=()
      for ((g = 0; g < gpus && shard <= last; g++, shard++)); do
        dir=$out/shard_$shard
        mkdir -p "$dir"
        say "shard $shard/$total on GPU $g, cores $((g * per))-$((g * per + per - 1))"
        (
          cd "$root"
          CUDA_VISIBLE_DEVICES=$g MBM_SHARD=$shard/$total \
            taskset -c $((g * per))-$((g * per + per - 1)) \
            benchmarks/scripts/reproduce.sh "$dir" mbm > "$dir/log.txt" 2>&1
        ) &
        pids+=($!)
      done
      for p in "${pids[@]}"; do wait "$p" || say "a shard ended with status $? (see its log.txt)"; done
    done
    ;;
  join)
    [ $# -eq 2 ] || { echo "usage: $0 join OUT_DIR" >&2; exit 2; }
    out=$2
    joined=$out/mbm
    mkdir -p "$joined"
    : > "$joined/results.csv"
    config=${MBM_CONFIG:-$root/benchmarks/config/motionbenchmaker_panda.yaml}
    found=0
    for dir in "$out"/shard_*/mbm; do
      csv=$dir/results.csv
      if [ ! -f "$csv" ]; then
        csv=$dir/results.partial.csv
        [ -f "$csv" ] || continue
        say "$dir: stopped before its end; its runs done are joined ($csv)"
      fi
      found=1
      if [ -s "$joined/results.csv" ]; then tail -n +2 "$csv"; else cat "$csv"; fi >> "$joined/results.csv"
    done
    [ "$found" -eq 1 ] || { echo "mbm_shards.sh: no shard results under $out" >&2; exit 2; }
    say "$(($(wc -l < "$joined/results.csv") - 1)) records joined"
    GPLAN_BENCH=${GPLAN_BENCH:-$root/build/apps/gplan-bench}
    status=0
    "$GPLAN_BENCH" "$config" --report "$joined" || status=$?
    [ "$status" -eq 0 ] || [ "$status" -eq 3 ] || exit "$status"
    ;;
  *)
    awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0" >&2
    exit 2
    ;;
esac
