#!/usr/bin/env bash
# Installs everything roller needs from Debian 12's packages. Idempotent: re-running it only
# checks that the packages are present. Needs root (or sudo) and network access to Debian's mirrors.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ninja-build clang-format
  coinor-libipopt-dev libmumps-seq-dev   # interior-point NLP solver + sparse direct solver
  libopenblas0-pthread                   # optimised BLAS/LAPACK for MUMPS (replaces the reference
                                         # BLAS through Debian's alternatives: faster Ipopt
                                         # increments, docs/benchmarks.md, "BLAS under MUMPS")
  liblapack-dev                          # dsytrf for Ipopt's small dense KKT systems
  libeigen3-dev                          # dense/sparse linear algebra
  catch2                                 # unit tests (v2)
  libcli11-dev                           # command-line parsing
  libtomlplusplus-dev                    # scene files (TOML)
  libfmt-dev                             # formatting
  nlohmann-json3-dev                     # summary.json, state files
  zlib1g-dev                             # compressed VTU output
  python3 python3-numpy python3-matplotlib  # figures (PNG)
  python3-dev pybind11-dev               # rollerpy._roller, roller in the Python process
  python3-venv python3-setuptools        # pip install ./python into a venv (docs/python.md)
  python3-distributed python3-tqdm       # studies: Dask LocalCluster or a cluster, progress bar
  python3-pytest python3-flake8          # the Python tests (CTest) and their lint (check_format.sh)
  paraview python3-paraview xvfb         # the outputs checked in ParaView's pvpython, headless (CTest)
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
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
