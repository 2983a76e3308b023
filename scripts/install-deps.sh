#!/usr/bin/env bash
# Installs rigflex's dependencies from Debian 12 packages.
#   install-deps.sh        what the build, the tests and the benchmarks need
#                          (GoogleTest, Google Benchmark and the tests'
#                          oracles: CalculiX, SciPy, headless Chromium), the
#                          Python module's (pybind11, pytest, matplotlib) and
#                          the MPI eigen backend's (SLEPc, PETSc, Open MPI)
#   install-deps.sh demo   what building rigflex and running it needs (the
#                          demo: scripts/demo.sh builds without tests)
# Idempotent: packages already present are skipped by apt; safe to re-run.
set -euo pipefail

profile=${1:-all}
case "$profile" in
  all|demo) ;;
  *) echo "install-deps: unknown profile '$profile' (all, demo)" >&2; exit 2 ;;
esac

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libsuitesparse-dev libopenblas0-pthread libopenblas-dev
  libvtk9-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libmatio-dev
  libsundials-dev libboost-dev libfftw3-dev zlib1g-dev
)
if [ "$profile" = all ]; then
  packages+=(
    libgtest-dev libgmock-dev libbenchmark-dev
    calculix-ccx python3-scipy python3-numpy
    chromium
    pybind11-dev python3-dev python3-pytest python3-matplotlib
    slepc-dev petsc-dev libopenmpi-dev openmpi-bin
  )
fi
# npm fetches the plotting library of the HTML reports (third_party/js). A
# node/npm already installed (e.g. from NodeSource) is used as it is: Debian's
# npm package would conflict with it.
if ! command -v npm >/dev/null 2>&1; then packages+=(npm); fi
# More packages on request: .ci/run's sanitizer and fuzzing pass adds clang
# and its runtimes (EXTRA_PACKAGES="clang libclang-rt-14-dev").
read -r -a extra <<< "${EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

if [ "${#missing[@]}" -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "install-deps: all packages present"
fi

# CHOLMOD's supernodal factorization runs 3-4x faster on OpenBLAS than on the
# reference BLAS that Debian selects by default; point the alternatives at it.
arch_triplet=$(gcc -dumpmachine)
for lib in libblas.so.3 liblapack.so.3; do
  cand=$(update-alternatives --list "${lib}-${arch_triplet}" 2>/dev/null | grep openblas-pthread | head -n1 || true)
  if [ -n "$cand" ]; then
    $SUDO update-alternatives --set "${lib}-${arch_triplet}" "$cand" >/dev/null
  fi
done

# Chart.js, inlined into the HTML reports (docs/reports.md), from the npm
# registry at the version pinned by third_party/js/package-lock.json.
js_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/third_party/js"
if [ ! -f "$js_dir/node_modules/chart.js/dist/chart.umd.js" ]; then
  echo "install-deps: installing the report's JavaScript into third_party/js/node_modules"
  if [ -f "$js_dir/package-lock.json" ]; then
    npm ci --prefix "$js_dir" --no-audit --no-fund >/dev/null
  else
    npm install --prefix "$js_dir" --no-audit --no-fund >/dev/null
  fi
fi
