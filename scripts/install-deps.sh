#!/usr/bin/env bash
# Installs the Debian 12 packages groom builds against, skipping what is already present.
# Safe to run repeatedly; needs root (or sudo) only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libopenvdb-dev libopenvdb-tools libboost-iostreams-dev libblosc-dev
  libcgal-dev libopenmesh-dev libeigen3-dev libtbb-dev
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev libpng-dev nlohmann-json3-dev
  python3-dev pybind11-dev python3-numpy python3-pytest
)
# Extra tools only some scripts use (sanitizers need clang's runtime; the add-on test needs Blender,
# its screenshot Xvfb). Pass --with-tools to add them.
# --with-slurm adds a one-machine Slurm (slurmctld + slurmd + munge) for scripts/slurm-frames.sh and
# its test; scripts/slurm-local.sh configures and starts it.
for arg in "$@"; do
  case "$arg" in
    --with-tools) packages+=(clang libclang-rt-14-dev python3-openvdb blender xvfb xauth xdotool) ;;
    --with-slurm) packages+=(slurm-wlm munge) ;;
    *) echo "install-deps: unknown option $arg (expected --with-tools, --with-slurm)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
