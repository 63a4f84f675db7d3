#!/usr/bin/env bash
# Adds Debian's Python 3 with numpy and pytest, and the built module (build/python), to a
# GPU bundle made by ../shared/tools/gpu-bundle (default .gpu), for the GPU machine,
# which has none of them: the interpreter and its standard library (tests, Tk, IDLE and
# the like left out), numpy and pytest from dist-packages, and the libraries their
# extensions load (into the bundle's lib/, which its run wrapper searches).
#
#   benchmarks/scripts/gpu_bundle_python.sh [BUNDLE] [BUILD_DIR]
#   then on the GPU machine: BUNDLE/python/run -m pytest python/tests   (or any script)
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
for p in numpy _pytest pytest pluggy iniconfig packaging py.py attr attrs; do
  [ -e "$site/$p" ] && tar -C "$site" -cf - --exclude=__pycache__ --exclude=tests "$p" | tar -C "$home/packages" -xf -
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
# Debian's Python from the bundle: its standard library, numpy, pytest and gplanner.
here=$(cd "$(dirname "$0")" && pwd)
export PYTHONHOME=$here PYTHONPATH=$here/packages${PYTHONPATH:+:$PYTHONPATH}
export PYTHONDONTWRITEBYTECODE=1
exec "$here/../run" "$here/../bin/python3" "$@"
RUN
chmod +x "$home/run"
echo "gpu_bundle_python.sh: $home holds Python $version ($(du -sm "$home" | cut -f1) MiB), bundle $(du -sm "$out" | cut -f1) MiB"
