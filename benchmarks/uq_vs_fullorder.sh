#!/usr/bin/env bash
# `mastrom uq` against plain Monte Carlo with the full order (docs/theory.md §7.6, benchmarks/README.md
# "Uncertainty: ROM against the full order"): Scheme 1 on a coarse mesh (1 x 6) with a short drive
# (10 deg in 0.3 s, 0.4 s record), two uncertain inputs (thickness, module mass); a 3 x 3 database over
# their box, then bench_rom_uq_fullorder: FULL full-order runs (default 200) against a Sobol study
# of ROM samples (default 4096). Exit 0 when the ROM's mean, standard deviation and 95 % quantile
# of every metric lie inside the full-order sample's 95 % intervals.
#   benchmarks/uq_vs_fullorder.sh [BUILD_DIR] [FULL] [ROM] [--set KEY=VALUE]...
# (the extra --set go to the study, e.g. --set simulation.tolerance=1.25e-6 for the full order's
# own convergence on the same Monte Carlo samples).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
full=${2:-200}
rom=${3:-4096}
extra=("${@:4}")
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
case=(--set interface.elements_axial=1 --set interface.elements_circumferential=6
      --set drive.duration=0.3 --set drive.ramp=0.05 --set drive.angle_deg=10
      --set simulation.end_time=0.4 --set material.yield_strength=2.7e8)
inputs=(--set uncertainty.interface.thickness.distribution=truncated_normal
        --set uncertainty.interface.thickness.mean=0.0015 --set uncertainty.interface.thickness.std=1e-4
        --set uncertainty.interface.thickness.lower=0.0011 --set uncertainty.interface.thickness.upper=0.0019
        --set uncertainty.module.mass.distribution=uniform --set uncertainty.module.mass.lower=0.42
        --set uncertainty.module.mass.upper=0.58)
start=$(date +%s)
"$build/cli/mastrom" rom build configs/scheme1.toml "${case[@]}" --modes 8 --backend dense \
  --param interface.thickness=0.001:0.002:3 --param module.mass=0.4:0.6:3 -q -o "$work/db.h5"
"$build/benchmarks/bench_rom_uq_fullorder" "$work/db.h5" configs/scheme1.toml "$full" "$rom" \
  "${case[@]}" "${inputs[@]}" "${extra[@]}"
echo "uq_vs_fullorder: $(( $(date +%s) - start )) s wall (load: $(cut -d' ' -f1-3 /proc/loadavg))"
