#!/usr/bin/env bash
# Installs bounce's build and run dependencies from Debian 12 packages.
# Skips everything when all packages are already installed, so `make` stays fast.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libgbm1
  libglfw3-dev libglm-dev libassimp-dev
  libembree-dev libtbb-dev libcgal-dev libnanoflann-dev
  libstb-dev libopenexr-dev libimgui-dev
  libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth
  # the viewer's input test drives real mouse and key events into Xvfb (tests/viewer/input.sh)
  xdotool
  # studies: `bounce sweep --emit parallel|slurm` (tested against a local single-node Slurm),
  # `bounce report` (matplotlib plots) and its test in headless Chromium
  parallel munge slurmctld slurmd slurm-client
  python3 python3-matplotlib chromium
  # `import bounce` (python/, docs/python.md): the pybind11 module, numpy arrays, its pytest tests
  pybind11-dev python3-dev python3-numpy python3-pytest
  # issue 29: every shader variant through Khronos' reference compiler (tests/portable/glslang_test.py)
  glslang-tools
  # the sanitizer and fuzz build (CMakePresets.json `sanitize`): clang with ASan, UBSan and libFuzzer
  clang-14 libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "install-deps: missing packages (${missing[*]}) and not root; install them or run as root" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
