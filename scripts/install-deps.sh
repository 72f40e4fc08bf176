#!/usr/bin/env bash
# Installs the Debian packages packlab needs to build, test and plot; does nothing when they
# are all present (idempotent). Run as root or with sudo available.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libfmt-dev libeigen3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libsuitesparse-dev libopenblas-openmp-dev
  python3 python3-dev pybind11-dev python3-numpy python3-matplotlib python3-pytest
  python3-distributed  # `packlab study --scheduler`: the Dask cluster (docs/study.md); the local pool needs nothing
)
# The static solver's distributed backend (docs/static-solver.md, "Distributed solve with PETSc"):
# PETSc with MUMPS over Open MPI, only when asked (PACKLAB_PETSC=1) and in CI, which tests it.
if [ "${PACKLAB_PETSC:-0}" = "1" ] || [ "${CI:-false}" = "true" ]; then
  packages+=(libpetsc-real-dev openmpi-bin)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
