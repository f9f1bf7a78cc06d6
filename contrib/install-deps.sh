#!/usr/bin/env bash
# Install what granular_dg needs from Debian packages. Idempotent: packages
# already present are not reinstalled, and apt's lists are refreshed only when
# something is missing.
#
#   bash contrib/install-deps.sh          what building and running needs
#   bash contrib/install-deps.sh --tests  that, and what the test suite, the
#                                         figures and the comparisons need
set -euo pipefail

packages=(
  build-essential cmake g++ make
  libdeal.ii-dev          # deal.II 9.4.1 with MPI, p4est, Trilinos, HDF5, SUNDIALS, Boost
  libboost-dev            # Boost.Math (Bessel, quadrature, roots), Boost.odeint
  zlib1g-dev              # CRC-32 of checkpoints (crc32_combine over MPI ranks)
  openmpi-bin libopenmpi-dev
)
test_packages=(
  numdiff                 # regression-test comparison
  python3-matplotlib python3-numpy  # figures in doc/ (run with /usr/bin/python3)
  python3-scipy           # the hopper's independent radial-field reference (tests/hopper)
  libdeal.ii-doc          # deal.II's examples: step-67, the throughput comparator of contrib/benchmark.py
  paraview python3-paraview xvfb  # pvpython: a real-client test of the VTU/PVD output
)

case "${1:-}" in
  "") ;;
  --tests) packages+=("${test_packages[@]}") ;;
  *) echo "install-deps: unknown argument '$1' (none, or --tests)" >&2; exit 2 ;;
esac

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
