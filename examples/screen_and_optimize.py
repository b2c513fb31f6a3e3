#!/usr/bin/env python3
"""Screen a design space with the ROM, optimise the interface thickness, check with the full order.

The question: how thin may the interfaces of the paper's Scheme 3 be (the lightest mast) while the
vibration of the end module stays below a limit? A thinner shell is lighter but softer. The screen
answers the first half at once: under the paper's trapezoidal law the vibration (the relative end
angular acceleration) is ten times larger than under the smooth laws, and it does not even fall
monotonically with the thickness — it depends on the phase at which the deceleration jump meets
the ongoing vibration. Under the cubic law it is small and falls smoothly with the thickness, so
the lightest admissible thickness is a well-posed 1-D optimisation.

1. Build (or read) a ROM database over the interface thickness.
2. Screen thickness x drive law with the ROM: 4 laws x 41 thicknesses in about two seconds.
3. Optimise: minimise the interfaces' mass over the thickness subject to RMS relative end angular
   acceleration <= limit under the chosen law (default cubic), with scipy.optimize (SLSQP; the ROM is cheap enough to call it inside
   the optimiser's loop, finite-difference gradients included).
4. Check the optimum with the nonlinear full order (one run, ~10-20 s) and compare.

    PYTHONPATH=build/python /usr/bin/python3 examples/screen_and_optimize.py
    PYTHONPATH=build/python /usr/bin/python3 examples/screen_and_optimize.py --quick   # seconds

Options: --database PATH (reuse or write the database there), --law NAME (default cubic),
--limit DEG_S2 (RMS, default 1.5 deg/s^2),
--quick (Scheme 1 on a coarse mesh and a short drive: a smoke test of the script).
"""

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy import optimize

import mastrom

ROOT = Path(__file__).resolve().parents[1]
DEG = math.pi / 180.0


def setup(args):
    """The base configuration, the thickness range and the drive laws of the study."""
    if args.quick:
        cfg = mastrom.Config.load(str(ROOT / "configs" / "scheme1.toml"), set={
            "interface.elements_axial": 1, "interface.elements_circumferential": 6,
            "drive.duration": 0.5, "drive.ramp": 0.05, "simulation.end_time": 0.6,
            "simulation.time_step": 5e-5})
        return cfg, (0.5e-3, 2e-3, 3), 6, "dense"
    cfg = mastrom.Config.load(str(ROOT / "configs" / "scheme3.toml"))
    return cfg, (0.5e-3, 2e-3, 5), 12, None


def interface_mass(cfg, thickness):
    """Mass of all the interfaces [kg]: (modules - 1) cylinders of wall `thickness`."""
    area = 2.0 * math.pi * cfg["interface.radius"] * cfg["interface.length"]
    return (cfg["mast.modules"] - 1) * cfg["material.density"] * area * thickness


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--database", help="ROM database file (read if present, else written)")
    parser.add_argument("--law", default="cubic", help="drive law of the optimisation")
    parser.add_argument("--limit", type=float, default=1.5,
                        help="allowed RMS relative end angular acceleration [deg/s^2]")
    parser.add_argument("--quick", action="store_true", help="small model, short drive (smoke test)")
    args = parser.parse_args()
    cfg, (h_lo, h_hi, n_h), n_modes, backend = setup(args)
    print(f"mastrom {mastrom.__version__}: {cfg!r}")
    print(f"options: law {args.law}, RMS limit {args.limit} deg/s^2, thickness {h_lo * 1e3}-{h_hi * 1e3} mm, "
          f"{'quick' if args.quick else 'full-size'} case")

    # 1. The database: one modal solve per sample.
    start = time.perf_counter()
    if args.database and Path(args.database).exists():
        db = mastrom.RomDatabase(args.database)
    else:
        db = mastrom.build_database(cfg, params={"interface.thickness": (h_lo, h_hi, n_h)},
                                    modes=n_modes, backend=backend, path=args.database)
    print(f"database {db!r} ready in {time.perf_counter() - start:.1f} s; "
          f"its own error estimate: {db.error_estimate}")
    h_lo, h_hi = db.box["interface.thickness"]

    # 2. Screen thickness x drive law (the designs as columns: first axis fastest, like the CLI).
    laws = ["trapezoidal", "cubic", "quintic", "cycloidal"]
    h_grid = np.linspace(h_lo, h_hi, 41)
    hh, ll = np.meshgrid(h_grid, laws, indexing="ij")
    start = time.perf_counter()
    table = db.screen({"interface.thickness": hh.ravel(), "drive.law": ll.ravel()})
    print(f"\nscreened {hh.size} designs in {time.perf_counter() - start:.2f} s")
    peak = table["peak_rel_end_angular_acceleration"].reshape(hh.shape) / DEG
    rms = table["rms_rel_end_angular_acceleration"].reshape(hh.shape) / DEG
    print("relative end angular acceleration [deg/s^2], peak / RMS:")
    print(f"{'h [mm]':>8}" + "".join(f"{law:>22}" for law in laws))
    for i in range(0, len(h_grid), 5):
        print(f"{h_grid[i] * 1e3:8.3f}" +
              "".join(f"{p:12.4g} / {r:7.3g}" for p, r in zip(peak[i], rms[i])))

    # 3. The lightest interface that keeps the trapezoidal drive's vibration below the limit.
    def rms_rel(h_mm):
        out = db.screen({"interface.thickness": [float(h_mm[0]) * 1e-3]},
                        set={"drive.law": args.law})
        return out["rms_rel_end_angular_acceleration"][0] / DEG

    limit = args.limit
    if rms_rel([h_hi * 1e3]) > limit:
        sys.exit(f"even h = {h_hi * 1e3} mm exceeds {limit} deg/s^2: raise --limit")
    if rms_rel([h_lo * 1e3]) <= limit:
        print(f"\nthe whole box meets {limit} deg/s^2: the optimum is the thinnest sample")
    start = time.perf_counter()
    result = optimize.minimize(
        lambda x: interface_mass(cfg, x[0] * 1e-3), x0=[h_hi * 1e3], method="SLSQP",
        bounds=[(h_lo * 1e3, h_hi * 1e3)],
        constraints=[{"type": "ineq", "fun": lambda x: limit - rms_rel(x)}],
        options={"ftol": 1e-10})
    h_opt = result.x[0] * 1e-3
    print(f"\nSLSQP: {result.message} ({result.nfev} objective, {result.nit} iterations, "
          f"{time.perf_counter() - start:.2f} s)")
    print(f"optimum: h = {h_opt * 1e3:.4f} mm, interfaces {interface_mass(cfg, h_opt):.4f} kg "
          f"(vs {interface_mass(cfg, h_hi):.4f} kg at {h_hi * 1e3:.2f} mm), "
          f"ROM RMS rel {rms_rel([h_opt * 1e3]):.4f} deg/s^2")

    # 4. The optimum with the nonlinear full order, against the ROM at the same output step.
    opt_cfg = cfg.replace({"interface.thickness": h_opt, "drive.law": args.law})
    start = time.perf_counter()
    # One thread for the tiny quick model: two threads only pay off on the full-size mast.
    full = mastrom.simulate(opt_cfg, threads=1 if args.quick else None)
    full_s = time.perf_counter() - start
    rom = db.evaluate({"interface.thickness": h_opt},
                      set={"drive.law": args.law,
                           "simulation.time_step": opt_cfg["simulation.time_step"],
                           "output.every": opt_cfg["output.every"]})
    r_full = full["end/relative_angular_acceleration"]
    r_rom = rom["end/relative_angular_acceleration"]
    nrmse = np.linalg.norm(r_rom - r_full) / np.linalg.norm(r_full)
    rms_full = full["metrics"]["rms_rel_end_angular_acceleration"] / DEG
    rms_rom = rom["metrics"]["rms_rel_end_angular_acceleration"] / DEG
    peak_full = np.max(np.abs(r_full)) / DEG
    peak_rom_samples = np.max(np.abs(r_rom)) / DEG
    print(f"\nfull order at the optimum ({full_s:.1f} s, {len(r_full)} samples, time step "
          f"{opt_cfg['simulation.time_step']} s): RMS rel {rms_full:.4f} deg/s^2, ROM "
          f"{rms_rom:.4f} ({100 * (rms_rom / rms_full - 1):+.2f} %); peak |rel| over the samples "
          f"{peak_full:.3f}, ROM {peak_rom_samples:.3f} "
          f"({100 * (peak_rom_samples / peak_full - 1):+.2f} %); NRMSE of the relative "
          f"acceleration {100 * nrmse:.2f} %")
    print("peak joint force: full {:.4f} N, ROM {:.4f} N".format(
        full["metrics"]["peak_joint_force"], rom["metrics"]["peak_joint_force"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
