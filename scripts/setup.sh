#!/usr/bin/env bash
# Installs the Debian packages clipblur needs, only those missing; safe to run again.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libembree-dev libtbb-dev
  libopenimageio-dev openimageio-tools openexr libopenexr-dev libpng-dev
  libglm-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libtinygltf-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox
  valgrind  # the perf gate counts instructions under callgrind
)
if [ "${CLIPBLUR_FUZZ:-0}" = 1 ]; then
  packages+=(clang libclang-rt-14-dev)
fi
if [ "${CLIPBLUR_SLURM:-0}" = 1 ]; then
  packages+=(slurmctld slurmd slurm-client)
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [ "$status" = "install ok installed" ] || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get -o DPkg::Lock::Timeout=600 update -qq
$sudo apt-get -o DPkg::Lock::Timeout=600 install -y -qq --no-install-recommends "${missing[@]}"
