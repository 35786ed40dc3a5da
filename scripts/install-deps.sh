#!/usr/bin/env bash
# Installs every Debian package fairshape needs to build, test, render and plot.
# Idempotent: packages already present are skipped, so a second run costs one dpkg query.
# Works as root, or through sudo for a normal user.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev libsuitesparse-dev libceres-dev libtbb-dev nlohmann-json3-dev libx11-dev
  libbenchmark-dev catch2 libvtk9-dev libyaml-cpp-dev libcli11-dev
  libosd-dev libcgal-dev libembree-dev libmeshoptimizer-dev
  libssl-dev python3-matplotlib python3-pandas python3-seaborn python3-vtk9 xvfb xauth  # python3-vtk9: tests read VTP arrays; seaborn: plot.py
  pybind11-dev python3-pybind11 python3-dev python3-numpy python3-scipy python3-pytest  # the Python module and its tests
  python3-jsonschema python3-yaml  # tests/cli/config_schema.sh checks every shipped config against `fairshape schema`
  clang libclang-rt-14-dev
  slurm-wlm munge  # tests/cli/slurm_array.sh starts a single-node cluster of its own (no service is started)
  petsc-dev libhypre-dev openmpi-bin  # the PETSc/hypre solver peers and the mpirun -np 2 test
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} Debian packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "install-deps: missing packages (${missing[*]}) and not root, no sudo: install them as root" >&2
    exit 1
  fi
fi

echo "install-deps: installing ${#missing[@]} Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
