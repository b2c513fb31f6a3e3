#!/usr/bin/env bash
# Install and build (scripts/setup.sh), then run the whole test suite.
# MASTROM_BASELINE_ISA=1 in the environment runs the suite on the baseline copies of the kernels
# that also have an AVX2 + FMA copy (common/cpu_features.hpp), as on a CPU without them.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
# Two tests at a time on the 2-core machine (MASTROM_JOBS to change): the two-rank MPI tests
# reserve both cores (PROCESSORS 2) and the unit tests of one binary share a lock on its scratch
# paths (tests/CMakeLists.txt), so the parallel run is the serial one in about 60 % of the time.
ctest --test-dir build -j"${MASTROM_JOBS:-2}" --output-on-failure
