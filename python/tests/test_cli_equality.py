"""The module and the command line run the same code: every array equals the CLI's file bit for bit.

Each test runs one command of `mastrom` on a small case, reads its HDF5 output with h5py, runs the
module on the same case and compares with np.array_equal (exact equality, no tolerance).
"""

import h5py
import numpy as np
import pytest

import mastrom
from conftest import COARSE, DB_PARAMS, SCHEME1, SHORT_RUN, set_args, run_cli

SERIES = ["time", "drive/angle", "drive/rate", "drive/acceleration", "end/angular_acceleration",
          "end/relative_angular_acceleration", "end/position", "end/acceleration", "joint/force",
          "joint/torque", "solver/newton_iterations", "solver/constraint_residual"]


def assert_same_deployment(result, path):
    with h5py.File(path, "r") as f:
        for name in SERIES:
            expected = f[name][()]
            assert result[name].shape == expected.shape, name
            assert np.array_equal(result[name], expected), f"{name} differs from the CLI's"
        for key, value in f["metrics"].attrs.items():
            if isinstance(value, bytes):  # text attributes (how the peaks were resolved, …)
                value = value.decode()
            assert result["metrics"][key] == value, f"metric {key}"
        assert mastrom.Config.from_toml(f.attrs["config"]) == result["config"]


def assert_same_files(first, second):
    """Every dataset and every metric of two deployment files are equal."""
    with h5py.File(first, "r") as a, h5py.File(second, "r") as b:
        for name in SERIES:
            assert np.array_equal(a[name][()], b[name][()]), name
        assert dict(a["metrics"].attrs) == dict(b["metrics"].attrs)
        for key in ["config", "source", "mastrom_version"]:
            assert a.attrs[key] == b.attrs[key], key


def test_simulate_equals_cli(tmp_path):
    path = tmp_path / "full.h5"
    run_cli("simulate", SCHEME1, *set_args(SHORT_RUN), "-q", "-o", path)
    # The CLI runs two threads (its default here), the module one: the results do not depend on it.
    result = mastrom.simulate(mastrom.Config.load(SCHEME1, set=SHORT_RUN), threads=1,
                              path=str(tmp_path / "python.h5"))
    assert len(result["time"]) == 101
    assert_same_deployment(result, path)
    assert_same_files(tmp_path / "python.h5", path)


@pytest.mark.parametrize("backend", ["dense", "slepc"])
def test_modes_equal_cli(tmp_path, backend):
    path = tmp_path / "modes.h5"
    overrides = dict(SHORT_RUN, **{"modes.count": 8})
    run_cli("modes", SCHEME1, *set_args(overrides), "--backend", backend, "-q", "-o", path)
    result = mastrom.modes(mastrom.Config.load(SCHEME1, set=overrides), backend=backend)
    names = {"frequencies_hz": "frequency_hz"}
    with h5py.File(path, "r") as f:
        for key in ["frequencies_hz", "damping_ratio", "participation", "effective_mass_fraction",
                    "centrifugal_participation", "translation_participation", "coriolis",
                    "shapes", "end_rotation", "end_displacement", "residual", "reference"]:
            expected = f["modes/" + names.get(key, key)][()]
            assert np.array_equal(result[key], expected), f"{key} differs from the CLI's"
        assert result["labels"] == [s.decode() for s in f["modes/labels"][()]]
    assert result["shapes"].shape == (8, len(result["reference"]))


def test_build_database_equals_cli(tmp_path, cli_database, coarse_config):
    db = mastrom.build_database(coarse_config, params=DB_PARAMS, modes=6, backend="dense",
                                path=str(tmp_path / "db.h5"))
    with h5py.File(cli_database, "r") as f:
        checksum = f.attrs["checksum"]
    assert db.checksum == (checksum.decode() if isinstance(checksum, bytes) else checksum)
    assert mastrom.RomDatabase(str(tmp_path / "db.h5")).checksum == db.checksum


def test_adaptive_build_equals_cli(tmp_path, coarse_config):
    # The command line's adaptive test case (tests/cli/rom_cli.cmake) on one rank: the same
    # design, hence the same samples and checksum; progress once per round.
    box = {"interface.thickness": (0.001, 0.002), "module.mass": (0.4, 0.6)}
    cli_path = tmp_path / "adaptive_cli.h5"
    run_cli("rom", "build", SCHEME1, *set_args(COARSE), "--param", "interface.thickness=0.001:0.002",
            "--param", "module.mass=0.4:0.6", "--modes", "6", "--backend", "dense", "-q",
            "--adaptive", "--tolerance", "0.0001", "--max-samples", "7", "-o", cli_path)
    rounds = []
    db = mastrom.build_adaptive_database(coarse_config, params=box, tolerance=1e-4, max_samples=7,
                                         modes=6, backend="dense", path=str(tmp_path / "py.h5"),
                                         progress=lambda n, estimate: rounds.append((n, estimate)))
    with h5py.File(cli_path, "r") as f:
        checksum = f.attrs["checksum"]
    assert db.checksum == (checksum.decode() if isinstance(checksum, bytes) else checksum)
    assert db.method == "rbf"
    assert [n for n, _ in rounds] == [5, 7]  # rounds of 2 samples on any number of ranks
    assert all(estimate > 1e-4 for _, estimate in rounds)  # the budget ended it, not the tolerance
    # Its estimate was measured at held-out probes: the last round's 12 and 12 fresh ones, the
    # worst of all; at a point, the typical value e and the upper value e+ of (4.14).
    assert db.error_estimate["response_nrmse"] >= rounds[-1][1]
    at = db.evaluate({"interface.thickness": 1.3e-3, "module.mass": 0.45})["error_estimate"]
    assert 0 < at["response_nrmse"] <= at["response_nrmse_upper"]


def test_adaptive_build_refuses_bad_options_with_the_cli_message(tmp_path, coarse_config):
    # The same line, with the option named as each caller gives it.
    box = {"interface.thickness": (0.001, 0.002)}
    with pytest.raises(mastrom.InputError) as caught:
        mastrom.build_adaptive_database(coarse_config, params=box, tolerance=1.5)
    cli = run_cli("rom", "build", SCHEME1, "--param", "interface.thickness=0.001:0.002",
                  "--adaptive", "--tolerance", "1.5", "-o", tmp_path / "unused.h5", check=False)
    assert str(caught.value).startswith("tolerance = 1.5 is out of range")
    assert cli.returncode == 2
    assert cli.stderr == f"mastrom: error: --{caught.value}\n"
    with pytest.raises(TypeError, match=r"takes \(low, high\)"):
        mastrom.build_adaptive_database(coarse_config, params={"module.mass": (0.4, 0.6, 3)},
                                        tolerance=0.03)


def test_evaluate_equals_rom_eval(tmp_path, cli_database, database):
    path = tmp_path / "eval.h5"
    run_cli("rom", "eval", cli_database, "--set", "interface.thickness=0.0015", "--set",
            "module.mass=0.45", "--set", "drive.law=cubic", "-o", path)
    result = database.evaluate({"interface.thickness": 0.0015, "module.mass": 0.45},
                               set={"drive.law": "cubic"}, path=str(tmp_path / "python.h5"))
    assert_same_deployment(result, path)
    assert_same_files(tmp_path / "python.h5", path)


def test_screen_equals_cli_screen(tmp_path, cli_database, database):
    path = tmp_path / "screen.h5"
    run_cli("screen", cli_database, "--grid", "interface.thickness=0.001:0.002:4", "--grid",
            "drive.law=trapezoidal,cubic,cycloidal", "--set", "module.mass=0.45", "-q", "-o", path)
    with h5py.File(path, "r") as f:
        parameters = f["screen/parameters"][()]
        metrics = f["screen/metrics"][()]
        metric_names = [s.decode() for s in f["screen/metric_names"][()]]
    laws = np.array(["trapezoidal", "cubic", "cycloidal"])[parameters[:, 1].astype(int)]
    table = database.screen({"interface.thickness": parameters[:, 0], "drive.law": laws},
                            set={"module.mass": 0.45})
    for j, name in enumerate(metric_names):
        assert np.array_equal(table[name].astype(np.float64), metrics[:, j]), name


def test_divergence_raises_numerical_error_with_the_cli_message(tmp_path):
    # A 4 ms step on a 1 MPa shell (the CLI's own divergence test).
    diverging = {"interface.elements_axial": 1, "interface.elements_circumferential": 6,
                 "material.youngs_modulus": 1e6, "simulation.time_step": 0.004,
                 "simulation.adaptive": False,
                 "simulation.end_time": 0.05, "drive.duration": 0.02, "drive.ramp": 0.005}
    with pytest.raises(RuntimeError) as caught:
        mastrom.simulate(mastrom.Config.load(SCHEME1, set=diverging), threads=1)
    assert isinstance(caught.value, mastrom.NumericalError)
    assert str(caught.value).startswith("generalized-alpha: step to t = ")
    cli = run_cli("simulate", SCHEME1, *set_args(diverging), "-q", "-o", tmp_path / "out.h5",
                  check=False)
    assert cli.returncode == 3 and not (tmp_path / "out.h5").exists()
    assert cli.stderr == f"mastrom: error: {caught.value}\n"


def test_unwritable_path_fails_before_the_run_with_the_cli_message():
    cfg = mastrom.Config.load(SCHEME1, set=SHORT_RUN)
    with pytest.raises(OSError) as caught:
        mastrom.simulate(cfg, path="no/such/folder/out.h5")
    assert isinstance(caught.value, mastrom.FileError)
    cli = run_cli("simulate", SCHEME1, *set_args(SHORT_RUN), "-q", "-o", "no/such/folder/out.h5",
                  check=False)
    assert cli.returncode == 2 and cli.stderr == f"mastrom: error: {caught.value}\n"


def test_uq_equals_cli_uq(tmp_path, cli_database, database):
    # The same study through the command and through db.uq: the same samples, metrics, summaries,
    # probabilities and Sobol indices, bit for bit.
    study = {"drive.duration": 0.3, "drive.ramp": 0.05, "drive.angle_deg": 10.0,
             "simulation.end_time": 0.4,
             "uncertainty.interface.thickness.distribution": "uniform",
             "uncertainty.interface.thickness.lower": 0.0012,
             "uncertainty.interface.thickness.upper": 0.0018,
             "uncertainty.module.mass.distribution": "uniform",
             "uncertainty.module.mass.lower": 0.45, "uncertainty.module.mass.upper": 0.55}
    limit = "peak_rel_end_angular_acceleration > 0.2"
    path = tmp_path / "uq.h5"
    run_cli("uq", cli_database, SCHEME1, *set_args(dict(COARSE, **study)), "--samples", "32",
            "--limit", limit, "--no-tail-runs", "-q", "-o", path)
    result = database.uq(mastrom.Config.load(SCHEME1, set=dict(COARSE, **study)), limits=[limit],
                         samples=32, tail_runs=False)
    with h5py.File(path, "r") as f:
        assert np.array_equal(result["inputs"], f["uq/inputs"][()])
        assert np.array_equal(result["metrics"], f["uq/metrics"][()])
        assert np.array_equal(result["mean"][:, 0], f["uq/summary/mean"][()])
        assert np.array_equal(result["sobol_total"], f["uq/sobol/total"][()])
        assert result["limits"][0]["probability"][0] == f["uq/limits/probability"][0]
    assert result["inputs"].shape == (32 * 4, 2)
