#!/usr/bin/env bash
# Installs gplanner from BUILD_DIR to a temporary prefix; checks the library's versioned
# SONAME against the version header and that the CMake package exports gplanner::gplanner
# alone, runs the installed gplan from its prefix (no library path), then builds and runs
# tests/install/downstream (OMPL's RRTConnect from 4 threads on one shared checker, and
# our lazy PRM, every path re-checked) against the prefix with find_package(gplanner)
# only, and again with pkg-config's flags only.
# usage: install_and_use.sh BUILD_DIR SCENE
set -euo pipefail
build=$1
scene=$2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
libdir=$(dirname "$(find "$prefix" -name 'libgplanner.so' | head -1)")
test -f "$libdir/cmake/gplanner/gplannerConfig.cmake"
! grep -rl "cuda_runtime\|__global__" "$prefix/include" || { echo "CUDA in installed headers"; exit 1; }
# A versioned SONAME, and the version header.
soname=$(readelf -d "$libdir/libgplanner.so" | sed -n 's/.*SONAME.*\[\(.*\)\]/\1/p')
version=$(sed -n 's/#define GPLANNER_VERSION_STRING "\(.*\)"/\1/p' "$prefix/include/gplanner/version.h")
case $soname in libgplanner.so.[0-9]*.[0-9]*) ;; *) echo "SONAME '$soname' is not versioned"; exit 1;; esac
test -e "$libdir/$soname" || { echo "no $soname beside libgplanner.so"; exit 1; }
case $version in "${soname#libgplanner.so.}".*) ;; *) echo "SONAME $soname, version $version"; exit 1;; esac
# The package: gplanner::gplanner alone, nothing internal (object libraries, helpers).
exported=$(sed -n 's/^add_library(\([^ ]*\) .*/\1/p' "$libdir"/cmake/gplanner/gplannerTargets.cmake)
test "$exported" = "gplanner::gplanner" || { echo "exported targets: $exported"; exit 1; }
! grep -l "gplanner_common\|gplanner_collision_gpu\|gplanner_knn_gpu\|gplanner_ompl" \
  "$libdir"/cmake/gplanner/*.cmake || { echo "internal targets in the package"; exit 1; }
# The installed gplan runs from its prefix, no library path set.
env -u LD_LIBRARY_PATH "$prefix/bin/gplan" info > "$work/gplan_info.log"
env -u LD_LIBRARY_PATH "$prefix/bin/gplan" plan "$scene" --backend cpu --time-limit 60 \
  > "$work/gplan_plan.log" || { cat "$work/gplan_plan.log"; echo "the installed gplan failed"; exit 1; }
# find_package(gplanner).
cmake -S "$here/downstream" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/build" -j 2 > "$work/build.log"
# It runs with no library path set: CMake's build RUNPATH names the installed library.
env -u LD_LIBRARY_PATH "$work/build/downstream" "$scene"
# pkg-config: the same program built with its flags alone.
export PKG_CONFIG_PATH="$libdir/pkgconfig"
libs=$(pkg-config --libs gplanner)
case " $libs " in *" -lgplanner "*) ;; *) echo "pkg-config --libs gplanner: '$libs'"; exit 1;; esac
test "$(pkg-config --modversion gplanner)" = "$version"
# shellcheck disable=SC2046  # the flags are words
c++ -std=c++17 -O1 "$here/downstream/main.cpp" -o "$work/downstream_pkg_config" \
    $(pkg-config --cflags gplanner) $libs
# It runs with no library path set: pkg-config's flags give it a RUNPATH.
env -u LD_LIBRARY_PATH "$work/downstream_pkg_config" "$scene"
# The header paths of 0.1.0 still compile, each saying it is deprecated.
# shellcheck disable=SC2046
c++ -std=c++17 -fsyntax-only "$here/downstream/old_paths.cpp" $(pkg-config --cflags gplanner) \
    2> "$work/old_paths.log" || { cat "$work/old_paths.log"; echo "0.1.0's header paths fail"; exit 1; }
test "$(grep -c "is deprecated (gplanner 0.2.0)" "$work/old_paths.log")" -ge 29 ||
  { cat "$work/old_paths.log"; echo "a forwarding header says nothing"; exit 1; }
# The Python module, where it was built: installed into the prefix's site directory, it
# imports from there with Debian's python3 (no library path: its RUNPATH names the
# installed library) and checks the scene's start.
if [ -f "$build/python/gplanner/__init__.py" ]; then
  site=$(dirname "$(find "$prefix" -path '*/gplanner/__init__.py' | head -1)")
  case $site in "$prefix"/lib/python3*/dist-packages/gplanner) ;; *)
    echo "the Python module is installed at '$site'"; exit 1;; esac
  env -u LD_LIBRARY_PATH PYTHONPATH="$(dirname "$site")" /usr/bin/python3 -c "
import sys, gplanner
assert gplanner.__file__.startswith('$prefix'), gplanner.__file__
scene = gplanner.load_scene(sys.argv[1])
assert scene.checker('cpu').check(scene.start).tolist() == [False]
" "$scene"
fi
