#!/usr/bin/env bash
# Installs the Debian packages the project needs, if any is missing. Needs root (apt-get).
#   scripts/install-deps.sh           what building and testing need (the Python module's tests and
#                                     example too: pytest, scipy, matplotlib)
#   scripts/install-deps.sh --bench   and povray for the pictures, Open3D for the Python peer
#   scripts/install-deps.sh --fuzz    and clang with its sanitizer and libFuzzer runtimes
set -euo pipefail
packages=(cmake g++ make libfcl-dev libccd-dev libeigen3-dev liboctomap-dev libgtest-dev
          libbenchmark-dev libcli11-dev libbullet-dev nlohmann-json3-dev libtbb-dev libhwy-dev
          libceres-dev pybind11-dev python3-dev python3-numpy python3-pytest python3-scipy python3-matplotlib)
case "${1:-}" in
  --bench) packages+=(povray python3-open3d) ;;
  --fuzz) packages+=(clang libclang-rt-dev) ;;
esac
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "Installing missing Debian packages: ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "error: need root to apt-get install: ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
