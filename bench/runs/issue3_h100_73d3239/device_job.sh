#!/usr/bin/env bash
# Issue 3's runs at this commit: GPU tests, peak rates, the collision table, agreement.
cd "$(dirname "$0")/.."
export GPLANNER_SHARED_DATA=$PWD/.gpu/data
export GPLANNER_GPLAN="$PWD/.gpu/run $PWD/.gpu/bin/gplan"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/machine.txt
lscpu | grep -E "Model name|^CPU\(s\)" >> $OUT/machine.txt
( .gpu/run .gpu/bin/gplanner_tests --gtest_filter='*Gpu*' 2>&1 | tail -40
  .gpu/run .gpu/bin/gplanner_stability_tests --gtest_filter='*Gpu*' 2>&1 | tail -25 ) > $OUT/gpu_tests.txt
.gpu/run .gpu/bin/gplanner_peak_rates > $OUT/peak.json
bench/collision_table.sh -d .gpu/data .gpu/run .gpu/bin/gplan > $OUT/table.jsonl
wc -l $OUT/table.jsonl
AGREEMENT=1 bench/collision_table.sh -d .gpu/data .gpu/run .gpu/bin/gplan > $OUT/agreement.jsonl
wc -l $OUT/agreement.jsonl
tail -3 $OUT/gpu_tests.txt
