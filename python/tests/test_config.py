"""mastrom.Config: loading with overrides, reading keys, TOML round trip, and the error paths."""

import numpy as np
import pytest

import mastrom
from conftest import SCHEME1, SOURCE_DIR, run_cli


def test_load_with_overrides_reads_keys_in_si_units():
    cfg = mastrom.Config.load(str(SOURCE_DIR / "configs" / "scheme3.toml"),
                              set={"interface.thickness": 1.5e-3, "drive.law": "cubic"})
    assert cfg["interface.thickness"] == 1.5e-3
    assert cfg["drive.law"] == "cubic"
    assert cfg["mast.modules"] == 4 and isinstance(cfg["mast.modules"], int)
    assert cfg["simulation.gravity"] == [0.0, 0.0, 0.0]
    assert cfg["interface.radius"] == 0.041
    side, mass = cfg["module.side"], cfg["module.mass"]
    assert cfg["module.inertia"] == pytest.approx([mass * side**2 / 6] * 3, rel=1e-15)
    assert "drive.law" in cfg and "drive.nothing" not in cfg
    assert cfg.keys()[0] == "mast.modules"
    assert cfg.to_dict()["material.youngs_modulus"] == 70e9


def test_overrides_as_command_line_strings_and_numpy_scalars():
    a = mastrom.Config.load(SCHEME1, set=["interface.thickness=0.0015", "drive.law=cubic"])
    b = mastrom.Config.load(SCHEME1, set={"interface.thickness": np.float64(0.0015),
                                          "drive.law": "cubic"})
    assert a == b
    c = b.replace({"simulation.gravity": np.array([0.0, -9.81, 0.0]), "mast.modules": np.int64(3)})
    assert c["simulation.gravity"] == [0.0, -9.81, 0.0] and c["mast.modules"] == 3
    assert b["mast.modules"] == 2  # replace returns a copy


def test_toml_round_trip_is_exact():
    cfg = mastrom.Config.load(SCHEME1, set={"interface.inner_diameter": 0.0873,
                                            "material.damping": 1.234567890123e-5})
    text = cfg.to_toml()
    assert mastrom.Config.from_toml(text) == cfg
    assert cfg["interface.inner_diameter"] == 0.0873
    assert cfg["interface.radius"] == (0.0873 + 0.002) / 2
    assert mastrom.Config() == mastrom.Config.from_toml("")


def test_same_config_text_as_the_command_line():
    cfg = mastrom.Config.load(SCHEME1, set={"interface.thickness": 0.0015})
    printed = run_cli("config", SCHEME1, "--set", "interface.thickness=0.0015").stdout
    # The command line puts two comment lines (version, source and overrides) in front.
    assert cfg.to_toml() == printed[printed.index("[mast]"):]


def test_bad_value_raises_value_error_with_the_cli_message():
    with pytest.raises(ValueError) as caught:
        mastrom.Config.load(SCHEME1, set={"interface.thickness": -0.001})
    assert isinstance(caught.value, mastrom.InputError)
    assert isinstance(caught.value, mastrom.Error)
    cli = run_cli("config", SCHEME1, "--set", "interface.thickness=-0.001", check=False)
    assert cli.returncode == 2
    assert cli.stderr == f"mastrom: error: {caught.value}\n"
    assert "interface.thickness = -0.001 is out of range" in str(caught.value)


@pytest.mark.parametrize("overrides, fragment", [
    ({"drive.law": "linear"}, "drive.law"),
    ({"mast.nothing": 1}, "mast.nothing"),
    ({"mast.modules": 2.5}, "mast.modules"),
    ({"simulation.time_step": float("nan")}, "simulation.time_step"),
    (["interface.thickness"], "interface.thickness"),
])
def test_every_bad_override_names_its_key(overrides, fragment):
    with pytest.raises(mastrom.InputError, match=fragment.replace(".", r"\.")):
        mastrom.Config.load(SCHEME1, set=overrides)


def test_missing_file_is_an_os_error():
    with pytest.raises(OSError) as caught:
        mastrom.Config.load("no/such/config.toml")
    assert isinstance(caught.value, mastrom.FileError)
    assert "no/such/config.toml" in str(caught.value)


def test_unknown_key_and_wrong_types():
    cfg = mastrom.Config()
    with pytest.raises(KeyError, match="interface.nothing"):
        cfg["interface.nothing"]
    with pytest.raises(KeyError, match="interface.radius"):
        cfg["interface.inner_diameter"]
    with pytest.raises(TypeError):
        mastrom.Config.load(SCHEME1, set={"interface.thickness": object()})
    with pytest.raises(TypeError):
        mastrom.Config.load(SCHEME1, set="interface.thickness=0.001")


def test_per_item_keys_through_set_and_lookup():
    cfg = mastrom.Config.load(str(SOURCE_DIR / "configs" / "scheme3.toml"),
                              set={"module.4.mass": 1.2, "interface.1.thickness": 1.5e-3})
    assert cfg["module.4.mass"] == 1.2
    assert cfg["module.3.mass"] == 0.5  # not given for item 3: [module]'s value
    assert cfg["interface.1.thickness"] == 1.5e-3
    assert "[module.4]" in cfg.to_toml()
    with pytest.raises(ValueError, match=r"\[module.5\] is out of range"):
        cfg.replace({"module.5.mass": 1.0})
