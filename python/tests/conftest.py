"""Shared fixtures of the Python module's tests (run by ctest: python/CMakeLists.txt).

ctest sets PYTHONPATH to the built package, MASTROM_CLI to the `mastrom` executable and
MASTROM_SOURCE_DIR, and runs from the source tree. The models are the coarse ones of the CLI tests
(Scheme 1, one ring of 6 shell elements, 1 ms steps) so that every test file runs in seconds.
"""

import os
import subprocess
from pathlib import Path

import pytest

import mastrom

SOURCE_DIR = Path(os.environ.get("MASTROM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SCHEME1 = str(SOURCE_DIR / "configs" / "scheme1.toml")

# Coarse Scheme 1 (as tests/cli/rom_cli.cmake): 1 x 6 shell mesh, 1 ms output step.
COARSE = {
    "interface.elements_axial": 1,
    "interface.elements_circumferential": 6,
    "simulation.time_step": 1e-3,
}
# A short full-order run of the coarse mast: a 5 degree swing in 80 ms, 100 steps.
SHORT_RUN = dict(
    COARSE,
    **{
        "drive.angle_deg": 5.0,
        "drive.duration": 0.08,
        "drive.ramp": 0.02,
        "simulation.end_time": 0.1,
    },
)
# The database of tests/cli/rom_cli.cmake: thickness x module mass, 3 x 3, 6 modes, dense solves.
DB_PARAMS = {"interface.thickness": (0.001, 0.002, 3), "module.mass": (0.4, 0.6, 3)}
DB_CLI_ARGS = ["--param", "interface.thickness=0.001:0.002:3", "--param", "module.mass=0.4:0.6:3",
               "--modes", "6", "--backend", "dense"]


def set_args(overrides):
    """The command line's --set arguments for a mapping of overrides (values as Python writes them)."""
    args = []
    for key, value in overrides.items():
        args += ["--set", f"{key}={value!r}" if isinstance(value, float) else f"{key}={value}"]
    return args


def run_cli(*args, check=True):
    """Run `mastrom ARGS` from the source tree; returns the CompletedProcess (text mode)."""
    cli = os.environ.get("MASTROM_CLI")
    if not cli:
        pytest.skip("MASTROM_CLI is not set (run the tests through ctest)")
    result = subprocess.run([cli, *map(str, args)], cwd=SOURCE_DIR, capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"mastrom {' '.join(map(str, args))} failed: {result.stderr}")
    return result


@pytest.fixture(scope="session")
def coarse_config():
    return mastrom.Config.load(SCHEME1, set=COARSE)


@pytest.fixture(scope="session")
def cli_database(tmp_path_factory):
    """The test database built by the command line (path)."""
    path = tmp_path_factory.mktemp("db") / "db_cli.h5"
    run_cli("rom", "build", SCHEME1, *set_args(COARSE), *DB_CLI_ARGS, "-q", "-o", path)
    return path


@pytest.fixture(scope="session")
def database(cli_database):
    return mastrom.RomDatabase(str(cli_database))
