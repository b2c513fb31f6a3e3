#!/usr/bin/env python3
"""Manufacturing tolerances through the ROM by Monte Carlo, with full-order runs at the tails.

How much does the vibration of the deployed mast scatter when the interfaces are made with the
usual tolerances? Wall thickness 1.5 mm +/- 0.05 mm and Young's modulus 70 GPa +/- 3 %, both
normal and independent, the tolerance taken as one standard deviation (--sigmas changes that).

1. A ROM database over thickness x modulus covering +/- 4.5 sigma. At a fixed radius both enter the
   stiffness and mass exactly affinely, so the database carries exact affine terms (method
   "affine"): no interpolation error between its samples.
2. 10^5 random designs through RomDatabase.screen, split over two Python threads (the screen
   releases the GIL, so both cores work): the distribution of the peak relative end angular
   acceleration (the vibration the drive excites), as a histogram PNG.
3. The full order at a handful of designs: the two tails (lowest and highest 0.1 % quantiles) and
   the median, each compared with the ROM at the same design and output step.

    PYTHONPATH=build/python /usr/bin/python3 examples/tolerance_monte_carlo.py --out mc/
    PYTHONPATH=build/python /usr/bin/python3 examples/tolerance_monte_carlo.py --quick --out /tmp/mc

Options: --designs N (default 100000), --seed S (default 1), --sigmas K (tolerance = K standard
deviations, default 1), --out DIR (histogram and CSV of the samples), --quick (Scheme 1 on a coarse
mesh and a short drive, 2000 designs: a smoke test of the script).
"""

import argparse
import math
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the non-interactive backend)

import mastrom  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DEG = math.pi / 180.0
H0, DH = 1.5e-3, 0.05e-3  # nominal thickness and its tolerance [m]
E0, DE = 70e9, 0.03  # nominal Young's modulus [Pa] and its relative tolerance


def setup(args):
    """The configuration, the number of modes, the backend and the screen's output step."""
    if args.quick:
        cfg = mastrom.Config.load(str(ROOT / "configs" / "scheme1.toml"), set={
            "interface.elements_axial": 1, "interface.elements_circumferential": 6,
            "interface.thickness": H0, "drive.duration": 0.5, "drive.ramp": 0.05,
            "simulation.end_time": 0.6, "simulation.time_step": 5e-5})
        return cfg, 6, "dense", {}
    cfg = mastrom.Config.load(str(ROOT / "configs" / "scheme3.toml"),
                              set={"interface.thickness": H0})
    # The screen at a 1 ms output step: ten times cheaper; peaks are those of the continuous
    # response either way (README, "Peaks"); the full-order checks use the config's 0.1 ms.
    return cfg, 12, None, {"output.every": 10}


def screen_in_threads(db, designs, fixed, threads=2):
    """db.screen over `threads` chunks at once (the screen releases the GIL)."""
    n = len(next(iter(designs.values())))
    bounds = np.linspace(0, n, threads + 1).astype(int)
    chunks = [{k: v[a:b] for k, v in designs.items()} for a, b in zip(bounds[:-1], bounds[1:])]
    with ThreadPoolExecutor(threads) as pool:
        parts = list(pool.map(lambda c: db.screen(c, set=fixed), chunks))
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--designs", type=int, default=100_000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--sigmas", type=float, default=1.0,
                        help="the tolerance is this many standard deviations")
    parser.add_argument("--out", default="monte_carlo", help="output folder")
    parser.add_argument("--quick", action="store_true", help="small model, short drive (smoke test)")
    args = parser.parse_args()
    if args.quick and args.designs == 100_000:
        args.designs = 2000
    out_dir = Path(args.out)
    out_dir.mkdir(parents=True, exist_ok=True)
    cfg, n_modes, backend, screen_set = setup(args)
    sigma_h, sigma_e = DH / args.sigmas, DE * E0 / args.sigmas
    print(f"mastrom {mastrom.__version__}: {cfg!r}")
    print(f"options: {args.designs} designs, seed {args.seed}, h ~ N({H0 * 1e3} mm, "
          f"{sigma_h * 1e3:.4g} mm), E ~ N({E0 / 1e9} GPa, {sigma_e / 1e9:.4g} GPa), out {out_dir}")

    # 1. The database (exact affine terms in thickness and modulus).
    span = 4.5
    start = time.perf_counter()
    db = mastrom.build_database(cfg, modes=n_modes, backend=backend, params={
        "interface.thickness": (H0 - span * sigma_h, H0 + span * sigma_h, 3),
        "material.youngs_modulus": (E0 - span * sigma_e, E0 + span * sigma_e, 3)})
    print(f"database {db!r} built in {time.perf_counter() - start:.1f} s")

    # 2. Monte Carlo through the ROM. Samples beyond the box (beyond 4.5 sigma: ~1e-5 of them)
    # are redrawn rather than extrapolated.
    rng = np.random.default_rng(args.seed)
    (h_lo, h_hi), (e_lo, e_hi) = db.box["interface.thickness"], db.box["material.youngs_modulus"]
    h = np.empty(0)
    e = np.empty(0)
    while len(h) < args.designs:
        hs = rng.normal(H0, sigma_h, args.designs)
        es = rng.normal(E0, sigma_e, args.designs)
        keep = (hs >= h_lo) & (hs <= h_hi) & (es >= e_lo) & (es <= e_hi)
        h, e = np.concatenate([h, hs[keep]]), np.concatenate([e, es[keep]])
    h, e = h[: args.designs], e[: args.designs]
    start = time.perf_counter()
    table = screen_in_threads(db, {"interface.thickness": h, "material.youngs_modulus": e},
                              screen_set)
    wall = time.perf_counter() - start
    peak = table["peak_rel_end_angular_acceleration"] / DEG
    q = np.quantile(peak, [0.001, 0.5, 0.999])
    print(f"screened {len(h)} designs in {wall:.1f} s ({len(h) / wall:.0f} designs/s, 2 threads)")
    print(f"peak |relative end angular acceleration| [deg/s^2]: mean {peak.mean():.3f}, "
          f"std {peak.std():.3f} ({100 * peak.std() / peak.mean():.2f} %), 0.1 % {q[0]:.3f}, "
          f"median {q[1]:.3f}, 99.9 % {q[2]:.3f}, min {peak.min():.3f}, max {peak.max():.3f}")
    np.savetxt(out_dir / "samples.csv", np.column_stack([h, e, peak]), delimiter=",",
               header="thickness_m,youngs_modulus_pa,peak_rel_end_angular_acceleration_deg_s2",
               comments="")

    # 3. Full order at the tails and the median, against the ROM at the same output step.
    picks = [int(np.argmin(np.abs(peak - v))) for v in q]
    checks = []
    for name, i in zip(["0.1 % tail", "median", "99.9 % tail"], picks):
        design = {"interface.thickness": float(h[i]), "material.youngs_modulus": float(e[i])}
        start = time.perf_counter()
        # One thread for the tiny quick model: two threads only pay off on the full-size mast.
        full = mastrom.simulate(cfg.replace(design), threads=1 if args.quick else None)
        full_s = time.perf_counter() - start
        rom = db.evaluate(design)  # at the config's own output step, as the full order
        r_full = full["end/relative_angular_acceleration"]
        r_rom = rom["end/relative_angular_acceleration"]
        p_full, p_rom = np.max(np.abs(r_full)) / DEG, np.max(np.abs(r_rom)) / DEG
        nrmse = np.linalg.norm(r_rom - r_full) / np.linalg.norm(r_full)
        checks.append((peak[i], p_rom, p_full))
        print(f"  {name:>11}: h = {h[i] * 1e3:.4f} mm, E = {e[i] / 1e9:.3f} GPa; screen "
              f"{peak[i]:.3f}; over the samples: ROM {p_rom:.3f}, full order {p_full:.3f} "
              f"({100 * (p_rom / p_full - 1):+.2f} %), NRMSE {100 * nrmse:.2f} % ({full_s:.1f} s)")

    fig, ax = plt.subplots(figsize=(7, 4.2))
    ax.hist(peak, bins=80, color="tab:blue", alpha=0.8)
    # The screen's peaks are those of the continuous ROM response; the full order's are over its
    # output samples, so the ROM is shown over the same samples next to it.
    for screen_peak, rom_peak, full_peak in checks:
        ax.axvline(screen_peak, color="k", lw=0.8, ls="--")
        ax.plot([rom_peak], [0], "k^", ms=7, clip_on=False)
        ax.plot([full_peak], [0], "rv", ms=7, clip_on=False)
    ax.plot([], [], "k--", lw=0.8, label="checked designs (screen, continuous peak)")
    ax.plot([], [], "k^", label="ROM, over the full order's output samples")
    ax.plot([], [], "rv", label="full order, over its output samples")
    ax.set_xlabel("peak |relative end angular acceleration| [deg/s$^2$]")
    ax.set_ylabel("designs")
    ax.set_title(f"{len(h)} designs: h = {H0 * 1e3} ± {DH * 1e3} mm, E ± {100 * DE:.0f} % "
                 f"(±{args.sigmas:g} σ)", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out_dir / "peak_relative_acceleration.png", dpi=120)
    print(f"wrote {out_dir / 'peak_relative_acceleration.png'} and {out_dir / 'samples.csv'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
