#!/usr/bin/env bash
# The behaviour of one build of gplan on every shipped scene, as digests: for a change that
# must not change behaviour, run it with the old build and the new (on the same machine,
# or where the two cannot travel together, in two runs) and diff the two outputs. Each
# line: what ran, its exit code, and the sha256 of what it wrote (gplan check's verdict
# file, gplan plan's path file). compare_builds.sh does the same with both builds at hand,
# timing them too.
#
# usage: benchmarks/scripts/behaviour_digest.sh GPLAN > DIGESTS.txt
#   GPLAN: how to start gplan, e.g. ".gpu/run .gpu/bin/gplan"
#   environment: SCENES (default: scenes/*.yaml), SEEDS (plan seeds, default "1 2 3"),
#   CHECK_BACKENDS (default: the three gpu traversals and cpu), PLAN_BACKENDS (gpu cpu)
set -uo pipefail
cd "$(dirname "$0")/../.."
[ $# -eq 1 ] || { sed -n 2,13p "$0"; exit 2; }
read -r -a gplan <<< "$1"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
IFS=',' read -r -a checks <<< "${CHECK_BACKENDS:-gpu --traversal basic,gpu --traversal packet,gpu --traversal balanced,cpu}"
digest() { if [ -f "$1" ]; then sha256sum < "$1" | cut -c1-16; else echo "none"; fi; }
for scene in ${SCENES:-scenes/*.yaml}; do
  name=$(basename "$scene" .yaml)
  n=50000
  case $name in pr2_*) n=100000 ;; esac
  for run in "${checks[@]}"; do
    rm -f "$scratch/out"
    # shellcheck disable=SC2086
    "${gplan[@]}" check "$scene" --n "$n" --seed 1 --backend $run --out "$scratch/out" \
        > /dev/null 2>&1
    echo "check $name $run: exit $? verdicts $(digest "$scratch/out")"
  done
  for backend in ${PLAN_BACKENDS:-gpu cpu}; do
    for seed in ${SEEDS:-1 2 3}; do
      rm -f "$scratch/path.yaml"
      "${gplan[@]}" plan "$scene" --backend "$backend" --seed "$seed" \
          --out "$scratch/path.yaml" > /dev/null 2>&1
      echo "plan $name $backend seed $seed: exit $? path $(digest "$scratch/path.yaml")"
    done
  done
done
