#!/usr/bin/env bash
# One run for the issue-4 table: ours (lazy PRM and PRM, GPU) on every shipped scene
# on cores 0-3, while OMPL's LazyPRM, PRM and RRTConnect with FCL run on cores 4-15
# (12 single-threaded processes at a time); then the k-NN benchmark alone.
cd "$(dirname "$0")/.."
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/machine.txt
lscpu | grep -E "Model name|^CPU\(s\)" >> $OUT/machine.txt
git_commit=$(cat .gpu/commit 2>/dev/null); echo "commit $git_commit" >> $OUT/machine.txt
( OMPL_PLANNERS="ompl-lazyprm ompl-prm ompl-rrtconnect" RUNS=10 LIMIT=60 BUDGET=120 \
    OMPL_CORES=4-15 OMPL_JOBS=12 \
    bench/plan_table.sh ompl .gpu/run .gpu/bin/gplanner_plan_bench > $OUT/ompl.jsonl 2> $OUT/ompl.log
) &
RUNS=10 LIMIT=60 BUDGET=60 taskset -c 0-3 bench/plan_table.sh ours .gpu/run .gpu/bin/gplanner_plan_bench > $OUT/ours.jsonl 2> $OUT/ours.log
wait
.gpu/run .gpu/bin/gplanner_knn_bench > $OUT/knn.txt 2>&1
wc -l $OUT/*.jsonl
tail -12 $OUT/knn.txt
