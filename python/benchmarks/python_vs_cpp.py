#!/usr/bin/env python3
"""Speed of the Python module against the C++ it wraps, as ratios (targets: within 10 %).

1. One 8 s deployment from the ROM: RomDatabase.evaluate against the same library call in C++
   (build/benchmarks/bench_rom_evaluate), median of REPEATS runs each, same database and point.
2. A screen of 10^4 designs: RomDatabase.screen against `mastrom screen` on the same 100 x 100 grid
   at a 1 ms output step (output.every = 10, as the user guide advises for large screens; the
   designs passed to Python are the CLI table's own parameter columns), both on one core;
   the CLI's time is reported twice, the screen alone (its printed time) and the whole process.

    PYTHONPATH=build/python /usr/bin/python3 python/benchmarks/python_vs_cpp.py [BUILD_DIR]

The database (Scheme 3 defaults, thickness x inner diameter 3 x 3, 10 modes, dense solves, as
benchmarks/bench_rom_deployment.cpp) is built once into BUILD_DIR/python_vs_cpp_db.h5. CPU load
from other processes moves both sides alike only when they run close together: the measurements
alternate between the two sides.
"""

import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np

import mastrom

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build"
REPEATS = 40
ROUNDS = 3


def database():
    path = BUILD / "python_vs_cpp_db.h5"
    if not path.exists():
        cfg = mastrom.Config()
        mastrom.build_database(cfg, params={"interface.thickness": (1e-3, 2e-3, 3),
                                            "interface.inner_diameter": (0.085, 0.1, 3)},
                               modes=10, backend="dense", path=str(path))
    return path


def cpp_evaluate(db_path):
    out = subprocess.run([str(BUILD / "benchmarks" / "bench_rom_evaluate"), str(db_path),
                          str(REPEATS), "--set", "interface.thickness=0.00137", "--set",
                          "interface.inner_diameter=0.0912"], capture_output=True, text=True,
                         check=True).stdout
    return float(re.search(r"median_s (\S+)", out).group(1))


def python_evaluate(db):
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        db.evaluate({"interface.thickness": 0.00137, "interface.inner_diameter": 0.0912})
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def cli_screen(db_path, out):
    start = time.perf_counter()
    result = subprocess.run([str(BUILD / "cli" / "mastrom"), "screen", str(db_path), "--grid",
                             "interface.thickness=0.001:0.002:100", "--grid",
                             "interface.inner_diameter=0.085:0.1:100", "--set", "output.every=10",
                             "-q", "-o", str(out)],
                            capture_output=True, text=True, check=True,
                            env=dict(os.environ, OMP_NUM_THREADS="1"))
    process = time.perf_counter() - start
    screen = float(re.search(r"on 1 rank: (\S+) s", result.stdout).group(1))
    return screen, process


def main():
    sys.stdout.reconfigure(line_buffering=True)  # each round's line as it comes
    db_path = database()
    db = mastrom.RomDatabase(str(db_path))
    print(f"database {db!r}; evaluate: 8 s at 0.1 ms, median of {REPEATS}; "
          f"{ROUNDS} alternating rounds")
    ratios = []
    for r in range(ROUNDS):
        cpp = cpp_evaluate(db_path)
        py = python_evaluate(db)
        ratios.append(py / cpp)
        print(f"  evaluate round {r + 1}: C++ {1e3 * cpp:.3f} ms, Python {1e3 * py:.3f} ms, "
              f"Python / C++ = {py / cpp:.3f}")
    print(f"evaluate: Python / C++ = {statistics.median(ratios):.3f} (median of rounds)")

    with tempfile.TemporaryDirectory() as tmp:
        table_path = Path(tmp) / "screen.h5"
        screen_ratios, process_ratios = [], []
        for r in range(ROUNDS):
            screen_s, process_s = cli_screen(db_path, table_path)
            with h5py.File(table_path, "r") as f:
                parameters = f["screen/parameters"][()]
                expected = f["screen/metrics"][()]
            designs = {"interface.thickness": parameters[:, 0],
                       "interface.inner_diameter": parameters[:, 1]}
            start = time.perf_counter()
            table = db.screen(designs, set={"output.every": 10})
            py = time.perf_counter() - start
            same = np.array_equal(table["peak_rel_end_angular_acceleration"], expected[:, 1])
            screen_ratios.append(py / screen_s)
            process_ratios.append(py / process_s)
            print(f"  screen round {r + 1}: 10^4 designs, mastrom screen {screen_s:.3f} s "
                  f"(process {process_s:.3f} s), Python {py:.3f} s; Python / CLI screen = "
                  f"{py / screen_s:.3f}, / CLI process = {py / process_s:.3f}; "
                  f"tables equal: {same}")
    print(f"screen: Python / mastrom screen = {statistics.median(screen_ratios):.3f} "
          f"(screen time), {statistics.median(process_ratios):.3f} (whole process)")


if __name__ == "__main__":
    main()
