#!/usr/bin/env bash
# The main job: install and build (scripts/setup.sh), then run the paper's Scheme 3 case.
# For now it shows the resolved Scheme 3 configuration; the deployment run will be added here.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
build/cli/mastrom config configs/scheme3.toml
