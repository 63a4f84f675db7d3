#!/usr/bin/env bash
# Installs gplanner from BUILD_DIR to a temporary prefix, then configures, builds and
# runs tests/install/downstream against it with find_package(gplanner) only.
# usage: install_and_use.sh BUILD_DIR SCENE
set -euo pipefail
build=$1
scene=$2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
test -f "$work/prefix/lib/cmake/gplanner/gplannerConfig.cmake"
! grep -rl "cuda_runtime\|__global__" "$work/prefix/include" || { echo "CUDA in installed headers"; exit 1; }
cmake -S "$here/downstream" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/build" -j 2 > "$work/build.log"
LD_LIBRARY_PATH="$work/prefix/lib" "$work/build/downstream" "$scene"
