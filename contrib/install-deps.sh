#!/usr/bin/env bash
# Install everything granular_dg needs from Debian packages. Idempotent: packages
# already present are not reinstalled, and apt's lists are refreshed only when
# something is missing.
set -euo pipefail

packages=(
  build-essential cmake g++ make
  libdeal.ii-dev          # deal.II 9.4.1 with MPI, p4est, Trilinos, HDF5, SUNDIALS, Boost
  libboost-dev            # Boost.Math (Bessel, quadrature, roots), Boost.odeint
  zlib1g-dev              # CRC-32 of checkpoints (crc32_combine over MPI ranks)
  openmpi-bin libopenmpi-dev
  numdiff                 # regression-test comparison
  libdeal.ii-doc          # deal.II's examples: step-67, the throughput comparator of contrib/benchmark.py
  paraview python3-paraview xvfb  # pvpython: a real-client test of the VTU/PVD output
  python3-matplotlib python3-numpy  # figures in doc/ (run with /usr/bin/python3)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
