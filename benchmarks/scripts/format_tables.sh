#!/usr/bin/env bash
# Prints the Markdown tables of benchmarks/RESULTS.md from a folder of raw data that
# benchmarks/scripts/reproduce.sh wrote (or a kept run under benchmarks/runs/): first the machine, then
# each table under a line naming it and its files.
#
# usage: benchmarks/scripts/format_tables.sh DIR [TABLE...]
#   TABLE: collision (with DIR/peak.json: the work at peak rates too), agreement,
#   gpu-tests, knn, time-limit; default: every one whose files DIR holds.
#   peak, which reproduce.sh runs apart, is printed with collision. The tables of gplan
#   bench's folders (seed-tables, regression, plan) come from
#   benchmarks/scripts/format_bench_tables.py.
set -euo pipefail
[ $# -ge 1 ] || { sed -n '2,9s/^# \{0,1\}//p' "$0"; exit 2; }
dir=${1%/}
shift
bench=$(cd "$(dirname "$0")" && pwd)
all=(collision agreement gpu-tests knn time-limit)
files() {  # the files a table is made from
  case $1 in
    collision) echo table.jsonl ;;
    agreement) echo agreement.jsonl ;;
    gpu-tests) echo gpu_tests.txt ;;
    knn) echo knn.jsonl ;;
    time-limit) echo time_limit.jsonl ;;
    peak) echo peak.json ;;
    *) echo "format_tables.sh: no table named '$1'; the tables are: ${all[*]}" >&2; return 2 ;;
  esac
}
tables=("$@")
for t in "${tables[@]}"; do files "$t" > /dev/null || exit 2; done
if [ ${#tables[@]} -eq 0 ]; then
  for t in "${all[@]}"; do
    first=$(files "$t" | cut -d' ' -f1)
    [ -f "$dir/$first" ] && tables+=("$t")
  done
fi
[ ${#tables[@]} -gt 0 ] || { echo "format_tables.sh: no raw data in $dir" >&2; exit 1; }

if [ -f "$dir/machine.txt" ]; then
  python3 - "$dir/machine.txt" <<'EOF'
import sys
gpu, cpu, cpus, commit = "", "", "", "not recorded"
for i, line in enumerate(open(sys.argv[1])):
    line = line.strip()
    if i == 0:
        gpu = line.replace(", ", ", driver ", 1)
    elif line.startswith("Model name:"):
        cpu = line.split(":", 1)[1].strip()
    elif line.startswith("CPU(s):"):
        cpus = line.split(":", 1)[1].strip()
    elif line.startswith("commit "):
        commit = line.split(" ", 1)[1]
print("Machine (%s): GPU %s; CPU %s, %s CPUs; commit %s." % (sys.argv[1], gpu, cpu, cpus, commit))
EOF
  echo
fi

for t in "${tables[@]}"; do
  [ "$t" = peak ] && continue  # printed with collision
  read -ra names <<< "$(files "$t")"
  paths=()
  for n in "${names[@]}"; do
    [ -f "$dir/$n" ] || { echo "format_tables.sh: $t: $dir/$n is missing" >&2; exit 1; }
    paths+=("$dir/$n")
  done
  case $t in
    collision)
      peak=""
      [ -f "$dir/peak.json" ] && peak=$dir/peak.json && paths+=("$peak")
      echo "$t (${paths[*]}):"; echo
      python3 "$benchmarks/scripts/format_collision_table.py" "${paths[0]}" "" "$peak" ;;
    agreement)
      echo "$t (${paths[*]}):"; echo
      python3 "$benchmarks/scripts/format_collision_table.py" "" "${paths[0]}" ;;
    gpu-tests)
      echo "$t (${paths[*]}):"; echo
      python3 "$benchmarks/scripts/format_gpu_tests.py" "${paths[0]}" ;;
    knn)
      echo "$t (${paths[*]}):"; echo
      python3 "$benchmarks/scripts/format_knn_table.py" "${paths[0]}" ;;
    time-limit)
      echo "$t (${paths[*]}):"; echo
      python3 "$benchmarks/scripts/format_time_limit_table.py" "${paths[0]}" ;;
  esac
  echo
done
