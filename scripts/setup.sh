#!/usr/bin/env bash
# Installs what dtlab needs from Debian packages; does nothing when everything is present.
set -euo pipefail
packages=(
  build-essential cmake pkg-config git
  libcgal-dev libboost-dev libgmp-dev libmpfr-dev libtbb-dev
  librapidcheck-dev libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev liblzma-dev zlib1g-dev
  clang libclang-rt-dev
  python3 python3-matplotlib xz-utils
  # dtlab experiment peers: the other meshers it judges; GNU parallel for sharded studies
  libqhull-dev tetgen parallel
  # import dtlab (python/): the binding, its tests, and the readers its files are checked with
  pybind11-dev python3-dev python3-numpy python3-pytest python3-scipy python3-meshio python3-vtk9
)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi
echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
"${sudo_cmd[@]}" apt-get update
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
