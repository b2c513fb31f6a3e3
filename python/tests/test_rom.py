"""mastrom.RomDatabase: properties, evaluate and screen (shapes, dtypes, broadcasting), and errors."""

import numpy as np
import pytest

import mastrom
from conftest import run_cli

METRICS = ["peak_abs_end_angular_acceleration", "peak_rel_end_angular_acceleration",
           "rms_rel_end_angular_acceleration", "residual_rel_end_angular_acceleration",
           "settling_time", "settled", "peak_joint_force", "peak_drive_torque", "drive_end_time",
           "settling_band"]
# The strength metrics of a database with stress modes (the fixture's Scheme 1: one interface).
STRESS = ["peak_von_mises_interface_1"]
# The design's mass and its 3 lowest natural frequencies at the deployed angle (docs/theory.md §1.7).
DESIGN = ["mass", "mass_module_1", "mass_module_2", "mass_interface_1", "frequency_1",
          "frequency_2", "frequency_3", "frequency_1_error", "frequency_2_error",
          "frequency_3_error"]


def test_database_properties(database, cli_database):
    assert database.parameters == ["interface.thickness", "module.mass"]
    assert database.box == {"interface.thickness": (0.001, 0.002), "module.mass": (0.4, 0.6)}
    assert np.array_equal(database.grid["module.mass"], [0.4, 0.5, 0.6])
    assert database.modes_per_sample == 6 and database.sample_count == 9
    assert database.method in ("tracked", "manifold", "cubic")
    assert database.path == str(cli_database)
    assert database.base_config["mast.modules"] == 2
    assert set(database.error_estimate) == {"frequency", "response_nrmse"}


def test_evaluate_shapes_and_dtypes(database):
    out = database.evaluate({"interface.thickness": 1.2e-3})
    n = len(out["time"])
    assert n == 8001  # 8 s at the database's 1 ms output step
    for key in ["time", "drive/angle", "end/relative_angular_acceleration", "joint/torque"]:
        assert out[key].shape == (n,) and out[key].dtype == np.float64
    for key in ["end/angular_acceleration", "end/position", "end/acceleration", "joint/force"]:
        assert out[key].shape == (n, 3) and out[key].dtype == np.float64
    assert out["solver/newton_iterations"].dtype == np.int32
    assert out["point"] == {"interface.thickness": 1.2e-3, "module.mass": 0.5}
    assert out["frequencies_hz"].shape == (6,) and np.all(np.diff(out["frequencies_hz"]) >= 0)
    assert out["inside_box"] and out["source"] == "rom"
    # The fixture's 3 x 3 grid tracks cleanly: cubic by default, its error measured at the cells'
    # centres, hence an estimate at the point (and none for another method).
    assert database.method == "cubic" and out["method"] == "cubic"
    assert set(out["error_estimate"]) == {"frequency", "response_nrmse", "response_nrmse_upper"}
    assert 0 < out["error_estimate"]["response_nrmse"] <= 2 * database.error_estimate["response_nrmse"]
    assert database.evaluate({"interface.thickness": 1.2e-3}, method="manifold")["error_estimate"] is None
    assert set(out["metrics"]) == set(METRICS + STRESS + DESIGN)
    assert out["metrics"]["peak_von_mises_interface_1"] > 0.0
    # The history only when asked; its largest sample never above the (polished) peak, which is
    # the same either way.
    assert "max_von_mises" not in out
    full = database.evaluate({"interface.thickness": 1.2e-3}, stress_history=True)
    assert full["metrics"] == out["metrics"]
    assert full["max_von_mises"]["interface_1"].shape == (n,)
    assert np.max(full["max_von_mises"]["interface_1"]) <= out["metrics"]["peak_von_mises_interface_1"]
    # Without gravity the modes at the deployed angle are the interpolated model's; the mass is
    # the modules' plus the shell's volume times its density, docs/theory.md (1.12).
    assert out["metrics"]["frequency_1"] == out["frequencies_hz"][0]
    assert 0 <= out["metrics"]["frequency_1_error"] < 0.01
    assert out["metrics"]["mass"] == (out["metrics"]["mass_module_1"] + out["metrics"]["mass_module_2"]
                                      + out["metrics"]["mass_interface_1"])
    assert len(database.evaluate({"interface.thickness": 1.2e-3}, frequencies=0)["metrics"]) == \
        len(METRICS + STRESS) + 4
    # The relative acceleration is Z minus the drive's (the ROM computes it directly, so equal to
    # round-off of the absolute one): the columns fit together.
    scale = np.max(np.abs(out["end/angular_acceleration"][:, 2]))
    assert np.allclose(out["end/relative_angular_acceleration"],
                       out["end/angular_acceleration"][:, 2] - out["drive/acceleration"],
                       rtol=0, atol=1e-12 * scale)


def test_evaluate_and_screen_agree_bit_for_bit(database):
    out = database.evaluate({"interface.thickness": 1.37e-3, "module.mass": 0.53},
                            set={"drive.law": "quintic"})
    # The vibration metrics are stepped at a screen's default 2 ms (coarser than the database's
    # 1 ms output step): a default screen's numbers.
    assert out["metrics_step_s"] == 2e-3
    point = {"interface.thickness": [1.37e-3], "module.mass": 0.53, "drive.law": "quintic"}
    table = database.screen(point)
    for name in METRICS + DESIGN:
        assert table[name][0] == out["metrics"][name], name
    # The stress peaks too: found in the same pass and refined between its samples, as the screen
    # finds them.
    for name in STRESS:
        assert table[name][0] == out["metrics"][name], name
    assert table["max_peak_von_mises"][0] == out["metrics"]["peak_von_mises_interface_1"]
    # Stepped at the output step instead (the output interval set), the peaks of the continuous
    # response move by no more than the peak refinement's tolerance (3.9e-4 of max(peak, settling
    # band), rom/model/deployment_metrics.hpp) plus the first-order hold's O(step²) (measured
    # 2.1e-4 between 2 ms and 10 us screens): 5e-4.
    fine = database.evaluate({"interface.thickness": 1.37e-3, "module.mass": 0.53},
                             set={"drive.law": "quintic", "output.every": 1})
    assert fine["metrics_step_s"] == pytest.approx(1e-3)
    band = out["metrics"]["settling_band"]  # rad/s², the floor of the angular accelerations' scale
    for name, floor in [("peak_abs_end_angular_acceleration", band),
                        ("peak_rel_end_angular_acceleration", band), ("peak_joint_force", 0.0),
                        ("peak_drive_torque", 0.0)]:
        value = out["metrics"][name]
        assert abs(fine["metrics"][name] - value) <= 5e-4 * max(abs(value), floor), name
    # With a yield strength (a free key) both give the margin of safety.
    out = database.evaluate({"interface.thickness": 1.37e-3}, set={"material.yield_strength": 2.7e8})
    table = database.screen({"interface.thickness": [1.37e-3]},
                            set={"material.yield_strength": 2.7e8})
    assert table["min_margin_of_safety"][0] == out["metrics"]["min_margin_of_safety"]
    assert out["metrics"]["min_margin_of_safety"] == pytest.approx(
        2.7e8 / out["metrics"]["peak_von_mises_interface_1"] - 1.0, rel=1e-12)


def test_screen_broadcasts_and_keeps_columns(database):
    h = np.linspace(1e-3, 2e-3, 7)
    table = database.screen({"interface.thickness": h, "module.mass": 0.45,
                             "drive.law": ["cubic", "trapezoidal"] * 3 + ["cubic"]},
                            set={"simulation.end_time": 7.0})
    assert np.array_equal(table["interface.thickness"], h)
    assert np.array_equal(table["module.mass"], np.full(7, 0.45))
    assert list(table["drive.law"]) == ["cubic", "trapezoidal"] * 3 + ["cubic"]
    for name in METRICS:
        assert table[name].shape == (7,)
    assert table["settled"].dtype == np.bool_
    assert table["peak_rel_end_angular_acceleration"].dtype == np.float64
    # A thinner interface vibrates more under the same (trapezoidal) drive.
    trapezoidal = table["peak_rel_end_angular_acceleration"][1::2]
    assert np.all(np.diff(trapezoidal) < 0)


def test_screen_outside_the_box_names_the_key(database, cli_database):
    with pytest.raises(ValueError) as caught:
        database.screen({"interface.thickness": [1.5e-3, 3e-3]})
    assert "design 1" in str(caught.value)
    assert "interface.thickness = 0.003 lies outside the database's range [0.001, 0.002]" in str(
        caught.value)
    table = database.screen({"interface.thickness": [1.5e-3, 2.1e-3]}, extrapolate=True)
    assert table["peak_rel_end_angular_acceleration"].shape == (2,)


@pytest.mark.parametrize("call, fragment", [
    (lambda db: db.screen({"interface.thickness": [1e-3, 2e-3], "module.mass": [0.5]}),
     "has 1 values"),
    (lambda db: db.screen({"material.density": [3000.0]}), "not a parameter of this database"),
    (lambda db: db.screen({"drive.law": ["cubic", "linear"]}), "drive.law"),
    (lambda db: db.screen({"interface.thickness": [np.nan]}), "not a finite number"),
    (lambda db: db.screen({"interface.thickness": 1e-3}, method="spline"), "spline"),
    (lambda db: db.screen({"interface.thickness": 1e-3}, peaks="max"), "peaks"),
    (lambda db: db.screen({"interface.thickness": 1e-3}, step=-1.0), "step = -1 s; allowed: > 0"),
    (lambda db: db.screen({"interface.thickness": 1e-3}, step=2e-3, set={"output.every": 2}),
     "both set the ROM step"),
    (lambda db: db.evaluate({"drive.law": "cubic"}), "not a parameter of this database"),
    (lambda db: db.evaluate(set={"material.density": 3000.0}), "material.density"),
    (lambda db: db.evaluate(method="affine"), "no affine terms"),
])
def test_bad_input_raises_input_error(database, call, fragment):
    with pytest.raises(mastrom.InputError, match=fragment):
        call(database)


def test_evaluate_error_message_equals_cli(database, cli_database):
    # The same line, with the option named as each caller gives it.
    with pytest.raises(mastrom.InputError) as caught:
        database.evaluate({"interface.thickness": 0.003})
    cli = run_cli("rom", "eval", cli_database, "--set", "interface.thickness=0.003", check=False)
    assert cli.returncode == 2
    assert cli.stderr.replace("--extrapolate", "extrapolate=True") == \
        f"mastrom: error: {caught.value}\n"


@pytest.mark.parametrize("call, argument", [
    (lambda db, _: db.evaluate({"interface.thickness": 0.003}), "needs extrapolate=True)"),
    (lambda db, _: db.screen({"interface.thickness": [0.003]}), "needs extrapolate=True)"),
    (lambda db, _: db.evaluate(set={"material.density": 3000.0}),
     "rom: set= material.density is not a parameter"),
    (lambda db, _: db.evaluate(method="affine"),
     "methods that work for it: tracked, manifold, cubic, rbf; choose one with method=)"),
    (lambda db, _: db.screen({"interface.thickness": 1e-3}, step=2e-3, set={"output.every": 2}),
     "and set= output.every=2 both set the ROM step"),
    (lambda _, config: mastrom.build_database(config, params={"module.mass": (0.6, 0.4, 3)}),
     "params 'module.mass=0.6:0.4:3': LO = 0.6 must be less than HI = 0.4"),
    (lambda _, config: mastrom.build_adaptive_database(
        config, params={"interface.thickness": (1e-3, 2e-3)}, tolerance=0.03, max_samples=2),
     "max_samples = 2 is out of range (3 to"),
    (lambda _, config: mastrom.build_database(config, params={"modes.count": (4, 6, 2)}),
     "the mode count is given by modes="),
])
def test_messages_name_the_python_arguments(database, coarse_config, call, argument):
    # A Python caller reads its own keyword arguments, never a command-line flag.
    with pytest.raises(mastrom.InputError) as caught:
        call(database, coarse_config)
    assert argument in str(caught.value)
    assert "--" not in str(caught.value)


def test_missing_and_foreign_files_are_file_errors(tmp_path):
    with pytest.raises(mastrom.FileError, match="no such file"):
        mastrom.RomDatabase(str(tmp_path / "missing.h5"))
    with pytest.raises(OSError, match="not an HDF5 file"):
        mastrom.RomDatabase(__file__)


def test_built_database_in_memory_and_saved(tmp_path, coarse_config):
    db = mastrom.build_database(coarse_config, params=["interface.thickness=0.001:0.002:2"],
                                modes=4, backend="dense")
    assert db.path is None and db.parameters == ["interface.thickness"]
    db.save(str(tmp_path / "saved.h5"))
    assert mastrom.RomDatabase(str(tmp_path / "saved.h5")).checksum == db.checksum
    with pytest.raises(mastrom.InputError, match="interface.elements_axial"):
        mastrom.build_database(coarse_config, params={"interface.elements_axial": (1, 2, 2)})


def test_built_database_with_the_cubic_method(coarse_config):
    # The database's default method is the one asked for, and its cubic estimate (5 samples) is
    # the one stored; a name that is not a method is refused before any solve.
    db = mastrom.build_database(coarse_config, params={"interface.thickness": (1e-3, 2e-3, 5)},
                                modes=4, backend="dense", method="cubic")
    assert db.method == "cubic"
    assert 0.0 <= db.error_estimate["response_nrmse"] < 0.01
    with pytest.raises(mastrom.InputError, match="cubic"):
        mastrom.build_database(coarse_config, params={"interface.thickness": (1e-3, 2e-3, 3)},
                               method="quintic")
