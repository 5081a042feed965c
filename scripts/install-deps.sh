#!/usr/bin/env bash
# Installs every Debian package that curvemesh's build, tests, benchmarks and scripts use.
# Non-interactive and idempotent; run as root (or through sudo) on Debian 12.
set -euo pipefail

packages=(
  # build
  build-essential cmake ninja-build pkg-config
  # libraries
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libpugixml-dev libcli11-dev nlohmann-json3-dev libtbb-dev libsuitesparse-dev libpng-dev libhdf5-dev zlib1g-dev
  # text as glyphs: fontconfig chooses a font, FreeType reads it, HarfBuzz shapes; a font to draw with
  libharfbuzz-dev libfreetype-dev libfontconfig-dev fonts-dejavu-core
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # fuzzing (libFuzzer with ASan/UBSan)
  clang libclang-rt-14-dev
  # the Python module and its tests
  pybind11-dev python3-dev python3-pytest
  # independent readers used by the tests
  python3 python3-numpy python3-svgelements python3-meshio python3-gmsh librsvg2-bin
  # real solvers on the meshes: dolfinx reads the .msh and the XDMF (the FEniCSx test), deal.II's
  # own reader the linear .msh of --msh-boundary-only (the deal.II test)
  python3-dolfinx libdeal.ii-dev
  # the drawings the corpus tests and scripts read (~8,100 SVGs, 180 MB)
  openclipart-svg
  # peak-memory measurement in the corpus scripts
  time
  # a one-node Slurm cluster for scripts/slurm-batch's test and scripts/slurm-compare
  slurm-wlm munge
  # the C++ API reference (cmake --build build --target doc) and its test, docs_cpp_api
  doxygen
)

if [ $# -gt 0 ]; then
  echo "usage: scripts/install-deps.sh   (takes no options)" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps.sh: all ${#packages[@]} packages already installed"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
