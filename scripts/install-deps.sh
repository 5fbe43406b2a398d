#!/usr/bin/env bash
# Installs the Debian 12 packages Fastron needs, and only those that are missing.
# Idempotent and silent when everything is already installed. Runs apt-get as root, or via sudo.
set -euo pipefail

packages=(
  # toolchain; Clang with its sanitizer and libFuzzer runtimes for the fuzz targets
  g++ make cmake ninja-build pkg-config clang-format clang-tidy clang libclang-rt-14-dev
  libfuzzer-14-dev
  # core
  libeigen3-dev zlib1g-dev
  # geometry: robots, meshes, scenes, exact collision checking
  liburdfdom-dev libtinyxml-dev libconsole-bridge-dev libassimp-dev libyaml-cpp-dev
  libfcl-dev libccd-dev liboctomap-dev
  # baselines
  libsvm-dev
  # planning (OMPL's CMake config names Boost libraries its package does not pull in)
  libompl-dev libboost-serialization-dev libboost-filesystem-dev libboost-system-dev
  # command line, tests, benchmarks
  libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  # plots (scripts/*.py run with /usr/bin/python3)
  python3 python3-matplotlib python3-numpy
  # the Python module and its tests (for /usr/bin/python3)
  pybind11-dev python3-dev python3-pytest
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

if [[ $(id -u) -eq 0 ]]; then
  sudo=()
elif command -v sudo >/dev/null; then
  sudo=(sudo)
else
  echo "install-deps: missing packages (${missing[*]}) and not root, and sudo is not available" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
