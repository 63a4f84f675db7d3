#!/usr/bin/env bash
# The collision-query table of the seed (Pan & Manocha, 50,000 queries per rigid scene,
# 100,000 for the PR2): every shipped scene, and the real PR2 when its data is given,
# through gpu (basic, packet, balanced), cpu and fcl (all cores) in one run per scene.
# Prints one JSON line per run (gplan check --json); benchmarks/scripts/format_collision_table.py
# turns them into the Markdown table of benchmarks/RESULTS.md.
#
# usage: [AGREEMENT=1] benchmarks/scripts/collision_table.sh [-d SHARED_DATA] GPLAN...
#   GPLAN: how to start gplan, e.g. build/apps/gplan or ".gpu/run .gpu/bin/gplan"
set -euo pipefail
cd "$(dirname "$0")/../.."
data=""
if [ "${1:-}" = "-d" ]; then data=$(cd "$2" && pwd); shift 2; fi
gplan=("$@")
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

scenes=()
for name in piano large_piano helicopter humanoid piano_detailed; do
  [ -f "scenes/$name.yaml" ] && scenes+=("scenes/$name.yaml:50000")
done
for name in pr2_reach pr2_base_arm; do
  [ -f "scenes/$name.yaml" ] && scenes+=("scenes/$name.yaml:100000")
done
if [ -n "$data" ]; then
  benchmarks/scripts/real_pr2_scene.sh "$data" > "$scratch/real_pr2.yaml"
  scenes+=("$scratch/real_pr2.yaml:100000")
fi
# With --agreement: 100,000 configurations per scene (Talos too), every gpu traversal
# and the cpu backend each compared with fcl instead of the timing table.
if [ "${AGREEMENT:-0}" = 1 ]; then
  [ -n "$data" ] && benchmarks/scripts/real_talos_scene.sh "$data" > "$scratch/real_talos.yaml" && scenes+=("$scratch/real_talos.yaml:0")
  for entry in "${scenes[@]}"; do
    scene=${entry%%:*}
    for run in "gpu --traversal basic" "gpu --traversal packet" "gpu --traversal balanced" "cpu"; do
      echo "$(basename "$scene" .yaml): $run vs fcl" >&2
      # shellcheck disable=SC2086
      "${gplan[@]}" check "$scene" --n 100000 --seed 2 --backend $run --compare fcl --json | tail -n 1 || true
    done
  done
  exit 0
fi

for entry in "${scenes[@]}"; do
  scene=${entry%%:*}
  n=${entry##*:}
  for run in "gpu --traversal basic" "gpu --traversal packet" "gpu --traversal balanced" "cpu" "fcl"; do
    echo "$(basename "$scene" .yaml): $run" >&2
    # shellcheck disable=SC2086
    "${gplan[@]}" check "$scene" --n "$n" --seed 1 --backend $run --repeat 5 --json | tail -n 1
  done
done
