#!/usr/bin/env bash
# Plan times on every shipped scene (bench/RESULTS.md, issues 4 and 5), in phases that
# keep the timed runs of one kind from disturbing each other:
#   ours     our lazy PRM and PRM on the gpu backend, one scene after another, alone;
#   ompl     OMPL's LazyPRM, PRM and RRTConnect as OMPL users run them (FCL on the
#            planning thread), one single-threaded process per scene and planner, up
#            to OMPL_JOBS at once (default 14) on the cores given by OMPL_CORES;
#   plugin   the same OMPL planners with our checker on the gpu backend (the OMPL
#            plugin), one after another on the cores given by PLUGIN_CORES; with
#            phase "ompl+plugin" the two run side by side (different cores).
# Prints gplanner_plan_bench's JSON lines; bench/format_plan_table.py makes the tables.
#
# usage: bench/plan_table.sh PHASE PLAN_BENCH... (PLAN_BENCH: how to start
#        gplanner_plan_bench, e.g. build/bench/gplanner_plan_bench or
#        ".gpu/run .gpu/bin/gplanner_plan_bench")
#   SCENES (default: every shipped scene), RUNS (10), LIMIT (30 s per run),
#   BUDGET (seconds per planner and scene after which no new run starts; default 120),
#   PLUGIN_SCENES and PLUGIN_BUDGET (the plugin phase's; default SCENES and BUDGET),
#   OMPL_PLANNERS (the ompl phase's; default "ompl-lazyprm ompl-prm ompl-rrtconnect")
set -euo pipefail
cd "$(dirname "$0")/.."
phase=$1
shift
bench=("$@")
scenes=${SCENES:-"piano large_piano helicopter humanoid piano_detailed pr2_reach pr2_base_arm"}
runs=${RUNS:-10}
limit=${LIMIT:-30}
budget=${BUDGET:-120}
plugin_scenes=${PLUGIN_SCENES:-$scenes}
plugin_budget=${PLUGIN_BUDGET:-$budget}
ompl_cores=${OMPL_CORES:-2-15}
ompl_jobs=${OMPL_JOBS:-14}
plugin_cores=${PLUGIN_CORES:-0-1}
ompl_planners=${OMPL_PLANNERS:-"ompl-lazyprm ompl-prm ompl-rrtconnect"}
pin() {  # pin to cores where taskset exists
  local cores=$1
  shift
  if command -v taskset >/dev/null; then taskset -c "$cores" "$@"; else "$@"; fi
}
common=(--runs "$runs" --time-limit "$limit" --slow "$limit" --slow-runs 2)

run_ours() {
  for s in $scenes; do
    echo "ours: $s" >&2
    "${bench[@]}" "scenes/$s.yaml" --planners ours-lazyprm,ours-prm "${common[@]}" --budget "$budget"
  done
}
run_ompl() {
  local pids=()
  for s in $scenes; do
    for p in $ompl_planners; do
      while [ "$(jobs -rp | wc -l)" -ge "$ompl_jobs" ]; do wait -n || true; done
      pin "$ompl_cores" "${bench[@]}" "scenes/$s.yaml" --planners "$p" "${common[@]}" \
        --budget "$budget" &
      pids+=($!)
    done
  done
  for pid in "${pids[@]}"; do wait "$pid" || true; done
}
run_plugin() {
  for s in $plugin_scenes; do
    echo "plugin: $s" >&2
    pin "$plugin_cores" "${bench[@]}" "scenes/$s.yaml" \
      --planners ompl-rrtconnect@gpu,ompl-lazyprm@gpu,ompl-prm@gpu "${common[@]}" \
      --budget "$plugin_budget"
  done
}

case $phase in
  ours) run_ours ;;
  ompl) run_ompl ;;
  plugin) run_plugin ;;
  ompl+plugin)
    run_ompl &
    ompl_pid=$!
    run_plugin
    wait "$ompl_pid"
    ;;
  *) sed -n 2,19p "$0"; exit 2 ;;
esac
