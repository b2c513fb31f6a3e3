#!/usr/bin/env python3
"""Manufacturing tolerances as a `mastrom uq` study: probabilities, Sobol indices, full-order tails.

Wall thickness 1.5 mm +/- 0.05 mm and Young's modulus 70 GPa +/- 3 % (configs/scheme3_tolerances.toml:
truncated normals at +/- 4 sigma). The example builds a ROM database over that box, runs the command
(it prints the moments, quantiles, exceedance probabilities with and without the ROM's error, the
Sobol indices and the full order at the tails) and draws a histogram from its HDF5 file.

    PYTHONPATH=build/python /usr/bin/python3 examples/tolerance_uq.py --out uq/
    /usr/bin/python3 examples/tolerance_uq.py --quick --out /tmp/uq    # Scheme 1, coarse, short

Options: --samples N (base samples, default 4096), --limit V (rad/s^2, the peak relative end
angular acceleration not to exceed; default 0.6), --mastrom PATH (default build/cli/mastrom),
--out DIR.
"""

import argparse
import subprocess
import sys
from pathlib import Path

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the non-interactive backend)

ROOT = Path(__file__).resolve().parents[1]
CONFIG = ROOT / "configs" / "scheme3_tolerances.toml"
# The quick variant: Scheme 1 on a 1 x 6 mesh with a short, small drive (seconds, not minutes).
QUICK = ["--set", "mast.modules=2", "--set", "interface.elements_axial=1",
         "--set", "interface.elements_circumferential=6", "--set", "drive.duration=0.3",
         "--set", "drive.ramp=0.05", "--set", "drive.angle_deg=10", "--set", "simulation.end_time=0.4"]


def run(*command):
    print("$", " ".join(str(c) for c in command), flush=True)
    subprocess.run([str(c) for c in command], check=True, cwd=ROOT)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--samples", type=int, default=4096)
    parser.add_argument("--limit", type=float, default=0.6)
    parser.add_argument("--mastrom", default=str(ROOT / "build" / "cli" / "mastrom"))
    parser.add_argument("--out", default="uq")
    parser.add_argument("--quick", action="store_true", help="small model, short drive")
    args = parser.parse_args()
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    extra = QUICK if args.quick else []
    samples = min(args.samples, 256) if args.quick else args.samples
    limit = 0.2 if args.quick and args.limit == 0.6 else args.limit
    db, result = out / "db.h5", out / "uq.h5"
    run(args.mastrom, "rom", "build", CONFIG, *extra, "--modes", 8 if args.quick else 12,
        "--param", "interface.thickness=0.0013:0.0017:3",
        "--param", "material.youngs_modulus=61.6e9:78.4e9:3", "-q", "-o", db)
    metric = "peak_rel_end_angular_acceleration"
    run(args.mastrom, "uq", db, CONFIG, *extra, "--samples", samples, "--limit",
        f"{metric} > {limit}", "-q", "-o", result, "--csv", out / "uq.csv")

    with h5py.File(result, "r") as f:
        names = [n.decode() for n in f["/uq/metric_names"][:]]
        rows = f["/uq/statistic_rows"][:].astype(int)
        values = f["/uq/metrics"][:, names.index(metric)][rows]
        p = f["/uq/limits/probability"][0], f["/uq/limits/conservative"][0]
    fig, ax = plt.subplots(figsize=(7, 4.2))
    ax.hist(values, bins=60, color="tab:blue", alpha=0.8)
    ax.axvline(limit, color="r", lw=1.2, label=f"limit {limit} rad/s$^2$: P = {p[0]:.3g} "
               f"(conservative {p[1]:.3g})")
    ax.set_xlabel("peak |relative end angular acceleration| [rad/s$^2$]")
    ax.set_ylabel("samples")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "peak_relative_acceleration.png", dpi=120)
    print(f"wrote {out / 'peak_relative_acceleration.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
