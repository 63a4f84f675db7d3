#!/usr/bin/env bash
# Final runs of this stop: GPU tests, then plan times (ours alone on cores 0-11 while
# OMPL's LazyPRM/PRM run on cores 12-15).
cd "$(dirname "$0")/.."
export GPLANNER_SHARED_DATA=$PWD/.gpu/data
export GPLANNER_GPLAN="$PWD/.gpu/run $PWD/.gpu/bin/gplan"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/machine.txt
lscpu | grep -E "Model name|^CPU\(s\)" >> $OUT/machine.txt
( .gpu/run .gpu/bin/gplanner_tests --gtest_filter='*Gpu*' 2>&1 | tail -40
  .gpu/run .gpu/bin/gplanner_stability_tests --gtest_filter='*Gpu*' 2>&1 | tail -25 ) > $OUT/gpu_tests.txt
( SCENES="pr2_base_arm" OMPL_PLANNERS="ompl-lazyprm ompl-prm" RUNS=10 LIMIT=30 BUDGET=60 OMPL_CORES=12-14 OMPL_JOBS=2 \
    bench/plan_table.sh ompl .gpu/run .gpu/bin/gplanner_plan_bench > $OUT/ompl_pr2.jsonl 2>/dev/null
) &
( SCENES="humanoid" OMPL_PLANNERS="ompl-prm" RUNS=10 LIMIT=30 BUDGET=60 OMPL_CORES=15 OMPL_JOBS=1 \
    bench/plan_table.sh ompl .gpu/run .gpu/bin/gplanner_plan_bench > $OUT/ompl_humanoid.jsonl 2>/dev/null
) &
SCENES="humanoid pr2_base_arm" RUNS=10 LIMIT=30 BUDGET=35 taskset -c 0-11 bench/plan_table.sh ours .gpu/run .gpu/bin/gplanner_plan_bench > $OUT/ours.jsonl 2>/dev/null
wait
wc -l $OUT/*.jsonl
tail -3 $OUT/gpu_tests.txt
