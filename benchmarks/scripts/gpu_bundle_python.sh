#!/usr/bin/env bash
# Adds Debian's Python 3 with numpy, pytest and Dask distributed, and the built module
# (build/python), to a GPU bundle made by ../shared/tools/gpu-bundle (default .gpu), for
# the GPU machine, which has none of them: the interpreter and its standard library
# (tests, Tk, IDLE and the like left out), numpy, pytest, dask and distributed (with the
# packages they import) from dist-packages, and the libraries their extensions load
# (into the bundle's lib/, which its run wrapper searches).
#
#   benchmarks/scripts/gpu_bundle_python.sh [BUNDLE] [BUILD_DIR]
#   then on the GPU machine: BUNDLE/python/run -m pytest python/tests   (or any script;
#   BUNDLE/python/run -m gplanner.distributed bench CONFIG -o OUT --local-gpus)
set -euo pipefail
out=${1:-.gpu}
build=${2:-build}
[ -x "$out/run" ] || { echo "gpu_bundle_python.sh: no bundle at $out (run gpu-bundle first)" >&2; exit 2; }
[ -f "$build/python/gplanner/__init__.py" ] || { echo "gpu_bundle_python.sh: no module in $build/python" >&2; exit 2; }
version=$(/usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])')
home=$out/python
rm -rf "$home" && mkdir -p "$home/lib" "$home/packages"
tar -C /usr/lib -cf - --exclude=__pycache__ --exclude="python$version/test" \
    --exclude="python$version/idlelib" --exclude="python$version/tkinter" \
    --exclude="python$version/turtledemo" --exclude="python$version/ensurepip" \
    --exclude="python$version/lib2to3" --exclude="python$version/config-*" \
    --exclude="python$version/unittest/test" --exclude="lib-dynload/_tkinter*" \
    --exclude="lib-dynload/_dbm*" --exclude="lib-dynload/_gdbm*" "python$version" |
  tar -C "$home/lib" -xf -
site=/usr/lib/python3/dist-packages
# numpy and pytest; dask and distributed (gplanner.distributed, docs/distributed.md) and
# what they import (Debian's python3-distributed's dependencies, pandas and lz4 left out:
# optional).
for p in numpy _pytest pytest pluggy iniconfig packaging py.py attr attrs \
         dask distributed cloudpickle toolz tlz tornado msgpack psutil sortedcontainers \
         tblib zict heapdict.py yaml _yaml click jinja2 markupsafe locket partd fsspec urllib3; do
  [ -e "$site/$p" ] && tar -C "$site" -cf - --exclude=__pycache__ --exclude=tests --exclude=test "$p" |
    tar -C "$home/packages" -xf -
done
# Their metadata (distributed's and dask's version, the versions the cluster compares).
for d in numpy pytest pluggy iniconfig packaging py attrs dask distributed cloudpickle toolz \
         tornado msgpack psutil sortedcontainers tblib zict HeapDict PyYAML click Jinja2 \
         MarkupSafe locket partd fsspec urllib3; do
  for m in "$site/$d"-*.egg-info "$site/$d"-*.dist-info; do
    [ -e "$m" ] && cp -r "$m" "$home/packages/"
  done
done
cp -r "$build/python/gplanner" "$home/packages/"
cp -L "/usr/bin/python$version" "$out/bin/python3"
find "$home" /usr/bin/python$version -name '*.so' -o -name "python$version" -type f | while read -r f; do
  ldd "$f" 2>/dev/null | awk '/=> \//{print $3}'
done | sort -u | while read -r lib; do cp -Ln "$lib" "$out/lib/" 2>/dev/null || true; done
rm -f "$out"/lib/libcuda.so* "$out"/lib/libnvidia-*
strip --strip-unneeded "$out"/bin/python3 "$out"/lib/*.so* 2>/dev/null || true
cat > "$home/run" <<'RUN'
#!/usr/bin/env bash
# Debian's Python from the bundle: its standard library, numpy, pytest, dask, distributed
# and gplanner.
here=$(cd "$(dirname "$0")" && pwd)
export PYTHONHOME=$here PYTHONPATH=$here/packages${PYTHONPATH:+:$PYTHONPATH}
export PYTHONDONTWRITEBYTECODE=1
exec "$here/../run" "$here/../bin/python3" "$@"
RUN
chmod +x "$home/run"
echo "gpu_bundle_python.sh: $home holds Python $version ($(du -sm "$home" | cut -f1) MiB), bundle $(du -sm "$out" | cut -f1) MiB"
