#!/usr/bin/env bash
# Install mastrom's Debian 12 packages and build it into build/.
# Idempotent: apt is skipped entirely when every package is already installed, and a second run
# only re-checks the CMake configuration and rebuilds what changed.
#
#   bash scripts/setup.sh          # from anywhere; run as root (or with sudo available)
#   CI=true bash scripts/setup.sh  # warnings are errors (-DMASTROM_WERROR=ON)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

packages=(
  g++ cmake make pkg-config
  libeigen3-dev libarpack2-dev petsc-dev slepc-dev libhdf5-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libtomlplusplus-dev libcli11-dev
  # GSL: the Sobol sequence, inverse CDFs and statistics of `mastrom uq` (common/statistics).
  libgsl-dev
  # Constrained optimisation on the ROM (mastrom optimize): NLopt's C++ library.
  libnlopt-cxx-dev
  hdf5-tools python3-h5py python3-matplotlib
  # The Python module (python/) and its tests and examples; the build skips it without them.
  python3-dev pybind11-dev python3-numpy python3-pytest python3-scipy
  # libFuzzer targets (scripts/run_fuzzers.sh): the fuzzer/ASan runtimes are only a Recommends.
  clang libclang-rt-14-dev
  # OpenMP for clang too, so the sanitizer build runs the threaded element loop like the gcc build.
  libomp-dev
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} > 0)); then
  echo "setup: installing ${missing[*]}"
  sudo=()
  if [[ $(id -u) -ne 0 ]]; then sudo=(sudo); fi
  apt_get=("${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600)
  # Only refresh the package lists when there are none (fresh image) or the install fails on
  # stale ones.
  if ! compgen -G "/var/lib/apt/lists/*_Packages*" > /dev/null; then
    "${apt_get[@]}" update
  fi
  if ! "${apt_get[@]}" install -y --no-install-recommends "${missing[@]}"; then
    "${apt_get[@]}" update
    "${apt_get[@]}" install -y --no-install-recommends "${missing[@]}"
  fi
fi

# Open MPI refuses to run as root without these (CI runs as root); one thread per process.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1

werror=OFF
if [[ "${CI:-}" == "true" ]]; then werror=ON; fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMASTROM_WERROR="$werror"
cmake --build build -j2
