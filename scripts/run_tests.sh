#!/usr/bin/env bash
# Install and build (scripts/setup.sh), then run the whole test suite.
# MASTROM_BASELINE_ISA=1 in the environment runs the suite on the baseline copies of the kernels
# that also have an AVX2 + FMA copy (common/cpu_features.hpp), as on a CPU without them.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
ctest --test-dir build --output-on-failure
