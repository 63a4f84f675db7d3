#!/usr/bin/env bash
# Writes a scene around the real Talos humanoid (../shared/data) to stdout: floating
# base and its 32 joints (38 DOF) over a floor, beside a table.
# usage: benchmarks/scripts/real_talos_scene.sh SHARED_DATA
set -euo pipefail
data=$(cd "$1" && pwd)
urdf=$data/example-robot-data/robots/talos_data/robots/talos_reduced.urdf
joints=$(grep -o '<joint name="[^"]*" type="\(revolute\|continuous\|prismatic\)"' "$urdf" | sed 's/<joint name="\([^"]*\)".*/\1/' | paste -sd, | sed 's/,/, /g')
# The zero pose puts the hands inside the thighs: lift the arms sideways.
rest=$(echo "$joints" | tr ',' '\n' | sed 's/ //g' | awk '{v=0} $1=="arm_left_2_joint"{v=0.4} $1=="arm_right_2_joint"{v=-0.4} {printf "%s%s: %s", (NR>1?", ":""), $1, v}')
cat <<YAML
name: real_talos
description: The real Talos (example-robot-data talos_reduced.urdf, talos.srdf) over a floor beside a table.
narrowest_passage: none stated; a collision-checking benchmark scene
robot:
  urdf: $urdf
  srdf: $data/example-robot-data/robots/talos_data/srdf/talos.srdf
  packages: {example-robot-data: $data/example-robot-data}
  base: floating
  planned_joints: [$joints]
obstacles:
  - {name: floor, box: [6, 6, 0.02], pose: {xyz: [0, 0, -0.011]}}
  - {name: table, box: [0.8, 1.5, 0.05], pose: {xyz: [1.0, 0, 0.75]}}
bounds: {min: [-1, -1, 0.9], max: [1, 1, 1.2]}
start: {base: {xyz: [-0.5, 0, 1.1], quat_wxyz: [1, 0, 0, 0]}, joints: {$rest}}
goal: {base: {xyz: [0.3, 0.5, 1.1], quat_wxyz: [1, 0, 0, 0]}, joints: {$rest}}
YAML
