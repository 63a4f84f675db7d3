#!/usr/bin/env bash
# Installs the Debian packages the build needs (only those missing), then configures
# and builds gplanner in build/ (BUILD_DIR overrides; extra arguments go to cmake).
# CUDA is used when nvcc is found (on PATH or in /usr/local/cuda/bin).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ cmake make libeigen3-dev libyaml-cpp-dev liburdfdom-dev libtinyxml2-dev
          libassimp-dev libfcl-dev libccd-dev libgtest-dev libompl-dev ompl-demos nlohmann-json3-dev
          python3-matplotlib python3-dev python3-numpy pybind11-dev python3-pytest chromium
          python3-distributed)
# The viewer (gplan plan --html) is bundled with npm at build time: Debian's where the
# machine has no Node.js of its own.
command -v npm >/dev/null || packages+=(nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if ! command -v nvcc >/dev/null && [ -x /usr/local/cuda/bin/nvcc ]; then
  export PATH="/usr/local/cuda/bin:$PATH"
fi
build=${BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j "$(nproc)"
