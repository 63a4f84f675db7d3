#!/usr/bin/env bash
# Reproduces the tables of benchmarks/RESULTS.md on a GPU machine: runs the programs bundled
# by ../shared/tools/gpu-bundle and writes their raw data into OUT_DIR;
# benchmarks/scripts/format_tables.sh OUT_DIR then prints the Markdown tables.
#
# 1. On the build machine (Debian 12), from the repository root:
#      cmake -B build -DCMAKE_CUDA_ARCHITECTURES=90 && cmake --build build -j
#      benchmarks/scripts/reproduce.sh --bundle [BUILD_DIR]        (BUILD_DIR: default build)
#    --bundle packs into .gpu/ the programs the tables use (BUILD_DIR/apps/gplan,
#    BUILD_DIR/apps/gplan-bench, BUILD_DIR/benchmarks/gplanner_{knn_bench,call_sizes,peak_rates,thread_scaling,
#    link_broad_phase},
#    BUILD_DIR/tests/gplanner_{tests,stability_tests}, BUILD_DIR/benchmarks/tests/gplanner_bench_tests) with the real PR2 and Talos
#    data from ../shared/data, and writes the commit to .gpu/commit ("-dirty" when
#    tracked files differ from it). .gpu/ must travel with the checkout.
# 2. On the GPU machine, from the repository root:
#      benchmarks/scripts/reproduce.sh OUT_DIR [TABLE...]
#    TABLE (default: all of them, in this order)  files written in OUT_DIR
#      gpu-tests  gplanner_tests, gplanner_stability_tests '*Gpu*'  gpu_tests.txt
#      peak       the GPU's peak BV and triangle test rates          peak.json
#      collision  the collision table: every scene, gpu basic,        table.jsonl
#                 packet, balanced, cpu and fcl, medians of 5 calls
#      agreement  gpu (each traversal) and cpu against fcl,           agreement.jsonl
#                 100,000 configurations per scene
#      plan       gplan-bench benchmarks/config/plan_times.yaml: ours      plan_times/
#                 (lazy PRM, PRM) against OMPL's LazyPRM, PRM,
#                 RRTConnect with FCL, 10 runs of up to 60 s
#      knn        100,000 piano milestones, k = 15: GPU, CPU, GNAT    knn.jsonl
#      time-limit gplan plan on every shipped scene, gpu and cpu,     time_limit.jsonl
#                 --time-limit 1 with the scene's milestones and with
#                 --milestones 10000000: wall time, setup, planning
#      hostile    the hostile-input catalogue through gplan (issue  hostile.txt
#                 19), its plan cases on the gpu backend
#      seed-tables the seed's three tables through gplan-bench     seed_collision_queries/,
#                 (benchmarks/config/seed_*.yaml)                          seed_local_planning/,
#                                                                     seed_pr2/
#      regression gplan-bench benchmarks/config/regression.yaml, OMPL's   regression/
#                 single-threaded planners 4 fewer than the CPUs at
#                 a time
#      error-time gplan-bench benchmarks/config/error_time.yaml: error     error_time/
#                 against time for the piano and the helicopter
#                 (issue 21)
#      error-time-articulated  the same for the humanoid and      error_time_articulated/
#                 pr2_reach (benchmarks/config/error_time_articulated.yaml)
#      call-sizes gplanner_call_sizes on every shipped scene: the    call_sizes.md
#                 gpu backend's routing, the cost of a call of each
#                 size and of one OMPL checkMotion (issue 22)
#      ompl-plugin gplan-bench benchmarks/config/ompl_plugin.yaml: OMPL's ompl_plugin/
#                 RRTConnect, PRM and LazyPRM with FCL and through
#                 the plugin on the gpu and cpu backends (issue 22)
#      broad-phase gplan-bench benchmarks/config/broad_phase.yaml: the     broad_phase/
#                 seed's sphere all-pairs table (64 to 320 spheres,
#                 CPU against GPU) and the scalable GPU broad phases
#                 up to 1,000,000 spheres (issue 23); results.md holds
#                 the tables; and the planner's sizes (50 link        link_broad_phase.jsonl
#                 spheres, 1,000 checked pairs, 1,000 to 10,000
#                 obstacle boxes): masked pair tests against
#                 sort-and-sweep (gplanner_link_broad_phase)
#      mbm-agreement  gplan check --compare fcl, gpu backend,       mbm_agreement.jsonl
#                 100,000 configurations, on the first MotionBenchMaker
#                 Panda problem of every scenario (issue 31)
#      mbm        gplan-bench on the MotionBenchMaker Panda set      mbm/
#                 (benchmarks/config/motionbenchmaker_panda.yaml's
#                 planners; MBM_SCENARIOS="a b": those scenario folders
#                 only, MBM_FIRST=N: the first N problems of each;
#                 MBM_SHARD=I/N: every N-th problem from the I-th, gplan-bench's
#                 --shard, for N GPUs or machines; MBM_OUT: the folder's name,
#                 default mbm; MBM_PLANNERS="a@b c@d": those planners instead;
#                 MBM_GPUS=N: gplan-bench --gpus N, default every GPU)
#    Every call also writes OUT_DIR/machine.txt (GPU, driver, CPU, commit, date,
#    tables). Progress goes to stderr. The exit status is 1 when a program failed (the
#    other tables still run). Where one command may run at most 10 minutes, split the
#    tables over calls as the runs in RESULTS.md were split:
#      benchmarks/scripts/reproduce.sh OUT_DIR gpu-tests peak collision agreement
#      benchmarks/scripts/reproduce.sh OUT_DIR knn time-limit hostile
#      benchmarks/scripts/reproduce.sh OUT_DIR seed-tables
#      benchmarks/scripts/reproduce.sh OUT_DIR regression
#      benchmarks/scripts/reproduce.sh OUT_DIR error-time
#      benchmarks/scripts/reproduce.sh OUT_DIR error-time-articulated
#      benchmarks/scripts/reproduce.sh OUT_DIR call-sizes ompl-plugin
#      benchmarks/scripts/reproduce.sh OUT_DIR broad-phase
#      timeout 590 benchmarks/scripts/reproduce.sh OUT_DIR plan   (more than 10 minutes: the runs
#      done stay in OUT_DIR/plan_times/results.partial.csv)
# 3. Back on the build machine: copy OUT_DIR to benchmarks/runs/NAME/ and print the tables
#    with benchmarks/scripts/format_tables.sh benchmarks/runs/NAME [TABLE...].
#
# GPU_BUNDLE: the bundle folder (default .gpu). BENCH_SECONDS: gplan-bench runs are
# stopped (SIGTERM) after this long, keeping their runs done in results.partial.csv.
# BENCH_JOBS: OMPL's single-threaded planners run this many at a time in plan,
# regression, ompl-plugin and mbm (gplan-bench --jobs; default 1: each alone, as its
# users run it). More finish sooner, but each runs slower than alone (on a 16-core H200
# host, RRTConnect with FCL 1.1x to 1.9x slower 12 at a time), so that their times and
# ratios against them are not for comparisons.
set -euo pipefail

usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; }
say() { echo "[reproduce $(date +%H:%M:%S)] $*" >&2; }

root=$(cd "$(dirname "$0")/../.." && pwd)

if [ "${1:-}" = --bundle ]; then
  build=${2:-build}
  cd "$root"
  programs=(apps/gplan apps/gplan-bench benchmarks/gplanner_knn_bench
            benchmarks/gplanner_call_sizes benchmarks/gplanner_peak_rates
            benchmarks/gplanner_thread_scaling benchmarks/gplanner_link_broad_phase
            tests/gplanner_tests tests/gplanner_stability_tests
            benchmarks/tests/gplanner_bench_tests)
  # gpu-bundle takes its options before the programs.
  ../shared/tools/gpu-bundle -d ../shared/data/moveit_resources_pr2_description \
    -d ../shared/data/pr2_moveit_config -d ../shared/data/example-robot-data \
    -d ../shared/data/motionbenchmaker \
    "${programs[@]/#/$build/}"
  if commit=$(git rev-parse --short HEAD 2>/dev/null); then
    git diff --quiet HEAD -- || commit="$commit-dirty"
  else
    commit=unknown
  fi
  echo "$commit" > .gpu/commit
  say "bundled .gpu/ at $commit"
  exit 0
fi
case ${1:-} in ''|-h|--help) usage; exit 2 ;; esac

mkdir -p "$1"
out=$(cd "$1" && pwd)
shift
all=(gpu-tests peak collision agreement knn time-limit hostile seed-tables regression plan
     error-time error-time-articulated call-sizes ompl-plugin broad-phase mbm-agreement mbm)
tables=("$@")
[ ${#tables[@]} -gt 0 ] || tables=("${all[@]}")
for t in "${tables[@]}"; do
  case " ${all[*]} " in
    *" $t "*) ;;
    *) echo "reproduce.sh: no table named '$t'; the tables are: ${all[*]}" >&2; exit 2 ;;
  esac
done

cd "$root"
bundle=${GPU_BUNDLE:-.gpu}
bundle=$(cd "$bundle" && pwd)
run=$bundle/run
bin=$bundle/bin
data=$bundle/data
[ -x "$run" ] || { echo "reproduce.sh: no bundle at $bundle (run benchmarks/scripts/reproduce.sh --bundle on the build machine)" >&2; exit 2; }
export GPLANNER_SHARED_DATA=$data                # tests that read the real PR2 and Talos
export GPLANNER_GPLAN="$run $bin/gplan"          # tests that start gplan
export GPLANNER_GPLAN_BENCH="$run $bin/gplan-bench"  # the harness's tests that start gplan-bench
cores=$(nproc)
jobs=${BENCH_JOBS:-1}

{
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null || echo "no nvidia-smi"
  lscpu | grep -E "Model name|^CPU\(s\)" || true
  echo "commit $(cat "$bundle/commit" 2>/dev/null || echo unknown)"
  echo "jobs $jobs (OMPL's single-threaded planners at a time)"
  echo "date $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "tables ${tables[*]}"
} > "$out/machine.txt"
say "writing into $out: ${tables[*]} ($(head -1 "$out/machine.txt"); $cores CPUs)"

failed=()
gtest() {  # one test program's output between the lines format_gpu_tests.py reads
  local program=$1 status=0
  shift
  echo "== program: $program $*"
  "$run" "$bin/$program" "$@" 2>&1 || status=$?
  echo "== exit status: $status"
  return "$status"
}
time_limit_table() {  # one JSON line per run: the run's --json line and the wall time
  local scene backend milestones start end status line
  for scene in scenes/*.yaml; do
    for backend in gpu cpu; do
      for milestones in "" 10000000; do
        start=$(date +%s.%N)
        status=0
        line=$("$run" "$bin/gplan" plan "$scene" --backend "$backend" --time-limit 1 \
          ${milestones:+--milestones "$milestones"} --json 2>/dev/null | tail -1) || status=$?
        end=$(date +%s.%N)
        [ "${line:0:1}" = "{" ] || line='{}'
        echo "{\"limit\":1,\"milestones_arg\":\"${milestones:-scene}\",\"exit\":$status,\"wall\":$(awk "BEGIN { print $end - $start }"),\"run\":$line}"
        say "time-limit: $scene $backend milestones ${milestones:-of the scene}: exit $status"
      done
    done
  done
}
bench_config() {  # gplan-bench CONFIG into OUT_SUBDIR; its exits 3 and 5 are findings
  local config=$1 dir=$2 status=0
  shift 2
  ${BENCH_SECONDS:+timeout -s TERM "$BENCH_SECONDS"} "$run" "$bin/gplan-bench" "$config" \
    -o "$dir" --no-plots "$@" || status=$?
  case $status in
    0) ;;
    3) say "$config: a returned path failed the FCL re-check (see $dir/summary.txt)" ;;
    5) say "$config: a regression against the baseline (see $dir/summary.txt)" ;;
    *) return "$status" ;;
  esac
}
collision_table() {
  if [ -d "$data/moveit_resources_pr2_description" ]; then
    benchmarks/scripts/collision_table.sh -d "$data" "$run" "$bin/gplan"
  else
    say "no real PR2 data in $data: real_pr2 and real_talos left out"
    benchmarks/scripts/collision_table.sh "$run" "$bin/gplan"
  fi
}

for t in "${tables[@]}"; do
  say "$t"
  case $t in
    gpu-tests)
      { gtest gplanner_tests --gtest_filter='*Gpu*' || failed+=("gplanner_tests")
        gtest gplanner_stability_tests --gtest_filter='*Gpu*' || failed+=("gplanner_stability_tests")
        gtest gplanner_bench_tests --gtest_filter='*Gpu*' || failed+=("gplanner_bench_tests")
      } > "$out/gpu_tests.txt"
      grep -E '^== |^\[  (PASSED|FAILED|SKIPPED) +\] [0-9]' "$out/gpu_tests.txt" >&2 || true
      ;;
    peak)
      "$run" "$bin/gplanner_peak_rates" > "$out/peak.json" || failed+=("$t")
      ;;
    collision)
      collision_table > "$out/table.jsonl" || failed+=("$t")
      ;;
    agreement)
      AGREEMENT=1 collision_table > "$out/agreement.jsonl" || failed+=("$t")
      ;;
    plan)
      bench_config benchmarks/config/plan_times.yaml "$out/plan_times" \
        --jobs "$jobs" || failed+=("$t")
      ;;
    knn)
      "$run" "$bin/gplanner_knn_bench" > "$out/knn.jsonl" || failed+=("$t")
      ;;
    time-limit)
      time_limit_table > "$out/time_limit.jsonl" || failed+=("$t")
      ;;
    hostile)
      gtest gplanner_tests --gtest_filter='*HostileCatalogue*' > "$out/hostile.txt" || failed+=("$t")
      grep -E '^\[  (PASSED|FAILED) +\]' "$out/hostile.txt" >&2 || true
      ;;
    seed-tables)
      # The plots are drawn on the build machine (gplan-bench --report): the GPU
      # machine has no matplotlib.
      for config in seed_collision_queries seed_local_planning seed_pr2; do
        bench_config "benchmarks/config/$config.yaml" "$out/$config" || failed+=("$t ($config)")
      done
      ;;
    regression)
      bench_config benchmarks/config/regression.yaml "$out/regression" \
        --jobs "$jobs" || failed+=("$t")
      ;;
    error-time)
      bench_config benchmarks/config/error_time.yaml "$out/error_time" || failed+=("$t")
      ;;
    error-time-articulated)
      bench_config benchmarks/config/error_time_articulated.yaml "$out/error_time_articulated" \
        || failed+=("$t")
      ;;
    call-sizes)
      for scene in scenes/*.yaml; do
        "$run" "$bin/gplanner_call_sizes" "$scene" --repeat 15 --motions 1000 || failed+=("$t ($scene)")
        echo
      done > "$out/call_sizes.md"
      ;;
    ompl-plugin)
      bench_config benchmarks/config/ompl_plugin.yaml "$out/ompl_plugin" \
        --jobs "$jobs" || failed+=("$t")
      ;;
    broad-phase)
      # Not through bench_config: here exit 3 is a failure, a method whose pairs differed
      # from the reference's (MISMATCH lines in the log). Plots: gplan-bench is run again
      # with matplotlib, or plot_broad_phase.py on results.csv.
      status=0
      "$run" "$bin/gplan-bench" benchmarks/config/broad_phase.yaml -o "$out/broad_phase" \
        --no-plots || status=$?
      if [ "$status" -ne 0 ]; then
        say "broad-phase: exit $status (3: a method's pairs differed from the reference's)"
        failed+=("$t")
      fi
      "$run" "$bin/gplanner_link_broad_phase" > "$out/link_broad_phase.jsonl" \
        || failed+=("$t (link_broad_phase)")
      ;;
    mbm-agreement)
      panda=$data/motionbenchmaker/panda
      scratch=$(mktemp -d)
      for dir in "$panda"/problems/*; do
        s=$(basename "$dir")
        printf 'name: %s.0001\nrobot:\n  urdf: %s\n  srdf: %s\n  packages: {meshes: %s}\nmoveit:\n  scene: %s\n  request: %s\n' \
          "$s" "$panda/robot/panda.urdf" "$panda/robot/panda.srdf" "$panda/robot/meshes" \
          "$dir/scene0001.yaml" "$dir/request0001.yaml" > "$scratch/$s.yaml"
        "$run" "$bin/gplan" check "$scratch/$s.yaml" --n 100000 --seed 1 --backend gpu \
          --compare fcl --json 2> /dev/null | tail -n 1 >> "$out/mbm_agreement.jsonl" \
          || failed+=("$t ($s)")
      done
      rm -rf "$scratch"
      ;;
    mbm)
      panda=$data/motionbenchmaker/panda
      config=$out/${MBM_OUT:-mbm}.yaml
      {
        sed -n '/^name:/,/^motionbenchmaker:/p' benchmarks/config/motionbenchmaker_panda.yaml
        echo "  problems: $panda/problems"
        [ -z "${MBM_FIRST:-}" ] || echo "  first: $MBM_FIRST"
        [ -z "${MBM_SCENARIOS:-}" ] || echo "  scenarios: [$(echo $MBM_SCENARIOS | sed 's/ /, /g')]"
        echo "  robot: {urdf: $panda/robot/panda.urdf, srdf: $panda/robot/panda.srdf, packages: {meshes: $panda/robot/meshes}}"
        if [ -n "${MBM_PLANNERS:-}" ]; then
          echo "planners: [$(echo $MBM_PLANNERS | sed 's/ /, /g')]"
          sed -n '/^planners:/,$p' benchmarks/config/motionbenchmaker_panda.yaml | sed 1d
        else
          sed -n '/^planners:/,$p' benchmarks/config/motionbenchmaker_panda.yaml
        fi
      } > "$config"
      bench_config "$config" "$out/${MBM_OUT:-mbm}" --jobs "$jobs" \
        ${MBM_SHARD:+--shard "$MBM_SHARD"} ${MBM_GPUS:+--gpus "$MBM_GPUS"} || failed+=("$t")
      ;;
  esac
done

for f in "$out"/*; do
  if [ -d "$f" ]; then say "$(basename "$f")/: $(ls "$f" | wc -l) files"; else say "$(basename "$f"): $(wc -l < "$f") lines"; fi
done
if [ ${#failed[@]} -gt 0 ]; then
  say "failed: ${failed[*]}"
  exit 1
fi
say "done; tables: benchmarks/scripts/format_tables.sh $out ${tables[*]}"
