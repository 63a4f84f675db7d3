#!/usr/bin/env bash
# Plan times of two gplan bundles, runs alternating: `gplan plan` on every shipped scene,
# seeds 1-4, time limit 30 s; one JSON line per run, the build ("before" or "after")
# added. On the GPU machine, from the repository root, with the old build bundled in
# .gpu_before/ (../shared/tools/gpu-bundle -o .gpu_before OLD_BUILD/apps/gplan) and the
# new one in .gpu/ (benchmarks/scripts/reproduce.sh --bundle):
#   benchmarks/scripts/plan_ab.sh OUT.jsonl [BACKEND...]        (default backends: cpu)
# then: python3 benchmarks/scripts/format_plan_ab_table.py OUT.jsonl
set -euo pipefail
out=$1
shift
backends=("${@:-cpu}")
for scene in scenes/*.yaml; do
  for backend in "${backends[@]}"; do
    for seed in 1 2 3 4; do
      for build in before after; do
        if [ "$build" = before ]; then bundle=.gpu_before; else bundle=.gpu; fi
        line=$("$bundle/run" "$bundle/bin/gplan" plan "$scene" --backend "$backend" --seed "$seed" \
          --time-limit 30 --json 2>/dev/null | tail -1) || true
        [ "${line:0:1}" = "{" ] || line='{}'
        echo "{\"build\":\"$build\",\"pass\":1,\"run\":$line}" >> "$out"
      done
    done
  done
done
