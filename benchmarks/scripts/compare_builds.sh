#!/usr/bin/env bash
# Compares two builds of gplan on every shipped scene, for changes that must not change
# behaviour (a refactor, a move): the verdicts of `gplan check` on every backend and
# traversal must be the same row for row, and the path files of `gplan plan` the same
# byte for byte for the same seeds; the check times of both builds are recorded in
# alternating passes (old, new, old, new), so that a difference can be set against
# each build's own run-to-run spread.
#
# usage: benchmarks/scripts/compare_builds.sh OUT_DIR OLD_GPLAN NEW_GPLAN
#   OLD_GPLAN, NEW_GPLAN: how to start each gplan, e.g. ".gpu_before/run .gpu_before/bin/gplan"
#   environment: SCENES (default: scenes/*.yaml), SEEDS (plan seeds, default "1 2 3"),
#   BACKENDS (check runs, default: the three gpu traversals and cpu), PLAN_BACKEND (gpu)
# writes OUT_DIR/times.jsonl (one `gplan check --json` line per run, with the build and
# pass added) and OUT_DIR/summary.txt (one line per comparison: same or DIFFERENT);
# exits 1 when anything differs.
set -uo pipefail
cd "$(dirname "$0")/../.."
[ $# -eq 3 ] || { sed -n 2,17p "$0"; exit 2; }
out=$1
read -r -a old <<< "$2"
read -r -a new <<< "$3"
mkdir -p "$out"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
scenes=${SCENES:-$(ls scenes/*.yaml)}
seeds=${SEEDS:-1 2 3}
plan_backend=${PLAN_BACKEND:-gpu}
IFS=',' read -r -a runs <<< "${BACKENDS:-gpu --traversal basic,gpu --traversal packet,gpu --traversal balanced,cpu}"
summary=$out/summary.txt
: > "$summary"
: > "$out/times.jsonl"
status=0

same() {  # same LABEL FILE_A FILE_B
  if cmp -s "$2" "$3"; then
    echo "same       $1" >> "$summary"
  else
    echo "DIFFERENT  $1" >> "$summary"
    status=1
  fi
}

for scene in $scenes; do
  name=$(basename "$scene" .yaml)
  n=50000
  case $name in pr2_*) n=100000 ;; esac
  for run in "${runs[@]}"; do
    tag=$(echo "$run" | sed 's/--traversal //; s/ /_/g')
    for pass in 1 2; do
      for build in old new; do
        echo "$name: $run, $build build, pass $pass" >&2
        if [ $build = old ]; then gplan=("${old[@]}"); else gplan=("${new[@]}"); fi
        # shellcheck disable=SC2086
        "${gplan[@]}" check "$scene" --n "$n" --seed 1 --backend $run --repeat 5 --json \
            --out "$scratch/$name.$tag.$build.$pass.txt" 2> /dev/null | tail -n 1 |
          sed "s/^{/{\"build\":\"$build\",\"pass\":$pass,/" >> "$out/times.jsonl"
      done
      same "check $name $run pass $pass: verdicts" \
           "$scratch/$name.$tag.old.$pass.txt" "$scratch/$name.$tag.new.$pass.txt"
    done
  done
  for seed in $seeds; do
    for build in old new; do
      echo "$name: plan seed $seed, $build build" >&2
      if [ $build = old ]; then gplan=("${old[@]}"); else gplan=("${new[@]}"); fi
      "${gplan[@]}" plan "$scene" --backend "$plan_backend" --seed "$seed" \
          --out "$scratch/$name.plan$seed.$build.yaml" > "$scratch/$name.plan$seed.$build.log" 2>&1
      echo "exit $?" >> "$scratch/$name.plan$seed.$build.exit"
    done
    same "plan $name seed $seed ($plan_backend): exit code" \
         "$scratch/$name.plan$seed.old.exit" "$scratch/$name.plan$seed.new.exit"
    if [ -f "$scratch/$name.plan$seed.old.yaml" ] || [ -f "$scratch/$name.plan$seed.new.yaml" ]; then
      same "plan $name seed $seed ($plan_backend): path file" \
           "$scratch/$name.plan$seed.old.yaml" "$scratch/$name.plan$seed.new.yaml"
    fi
  done
done
cat "$summary"
exit $status
