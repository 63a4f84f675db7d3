#!/usr/bin/env bash
# Writes a scene around the real PR2 (../shared/data) to stdout: planar base, torso and
# both arms (18 DOF), a table and a shelf. usage: bench/real_pr2_scene.sh SHARED_DATA
set -euo pipefail
data=$(cd "$1" && pwd)
arm() { for j in shoulder_pan shoulder_lift upper_arm_roll elbow_flex forearm_roll wrist_flex wrist_roll; do printf '%s_%s_joint, ' "$1" "$j"; done; }
values() { printf '%s_shoulder_pan_joint: %s, %s_shoulder_lift_joint: 0, %s_upper_arm_roll_joint: 0, %s_elbow_flex_joint: -0.5, %s_forearm_roll_joint: 0, %s_wrist_flex_joint: -0.5, %s_wrist_roll_joint: 0' "$1" "$2" "$1" "$1" "$1" "$1" "$1" "$1"; }
joints="torso_lift_joint, $(arm r)$(arm l)"
cat <<YAML
name: real_pr2
description: The real PR2 (moveit_resources_pr2_description, pr2_moveit_config SRDF) by a table and a shelf.
narrowest_passage: none stated; a collision-checking benchmark scene
robot:
  urdf: $data/moveit_resources_pr2_description/urdf/robot.xml
  srdf: $data/pr2_moveit_config/config/pr2.srdf
  packages: {moveit_resources_pr2_description: $data/moveit_resources_pr2_description}
  base: planar
  planned_joints: [${joints%, }]
obstacles:
  - {name: table, box: [0.8, 1.5, 0.05], pose: {xyz: [1.1, 0, 0.72]}}
  - {name: table_leg, box: [0.05, 0.05, 0.7], pose: {xyz: [0.75, 0.7, 0.35]}}
  - {name: shelf_side, box: [0.4, 0.03, 1.8], pose: {xyz: [0, -1.4, 0.9]}}
  - {name: shelf_board, box: [0.4, 1.0, 0.03], pose: {xyz: [0, -1.9, 1.1]}}
  - {name: floor, box: [6, 6, 0.02], pose: {xyz: [0, 0, -0.011]}}
bounds: {min: [-1.5, -1.5], max: [1.5, 1.5]}
start: {base: {xy: [-1, 0.8], theta: 0}, joints: {torso_lift_joint: 0.1, $(values r 0), $(values l 0)}}
goal: {base: {xy: [0.2, 0], theta: 0}, joints: {torso_lift_joint: 0.2, $(values r -0.5), $(values l 0.5)}}
YAML
