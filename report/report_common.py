"""Pieces of `mastrom report` that need neither numpy nor h5py: the error type, the display units
and the number format of the tables.

Files store SI units (README.md, "Outputs and units"); a person reads angles in degrees, so the report
converts rad, rad/s and rad/s^2 to °, °/s and °/s² for display and nothing else. Tables print every number
with SIGNIFICANT_DIGITS significant digits of the displayed value, and carry the exact SI value from
the file in the cell's `data-si` attribute (shortest round-trip text) and its `title` tooltip.
"""

import math
import re

#: Significant digits of every number in the HTML tables (printf "%.7g" of the displayed value).
SIGNIFICANT_DIGITS = 7

#: Exit codes, chosen so that `mastrom report` can forward them unchanged (cli/main.cpp: 2 = bad
#: input or file, 1 = anything else).
EXIT_OK = 0
EXIT_FAILURE = 1
EXIT_INPUT = 2


class ReportError(Exception):
    """A failure the user can act on; printed as one line, exit code `exit_code`."""

    def __init__(self, message, exit_code=EXIT_INPUT):
        super().__init__(message)
        self.exit_code = exit_code


RAD_TO_DEG = 180.0 / math.pi

#: SI unit text as the files write it -> (display text, factor display/SI).
_DISPLAY_UNITS = {
    "rad/s^2": ("°/s²", RAD_TO_DEG),
    "rad/s": ("°/s", RAD_TO_DEG),
    "rad": ("°", RAD_TO_DEG),
    "N*m": ("N·m", 1.0),
    "m/s^2": ("m/s²", 1.0),
    "kg*m^2": ("kg·m²", 1.0),
    "kg/m^3": ("kg/m³", 1.0),
    "Pa": ("MPa", 1e-6),
    "1": ("–", 1.0),
    "": ("–", 1.0),
}


def display_unit(si_unit):
    """(display text, factor) for a value stored in `si_unit`: only angles change (to degrees)."""
    return _DISPLAY_UNITS.get(si_unit, (si_unit, 1.0))


#: Units of the /metrics attributes of a deployment file (fullorder/deployment_result.hpp); HDF5
#: attributes carry no `units` attribute of their own. "flag" = an int 0/1 shown as yes/no.
METRIC_UNITS = {
    "peak_abs_end_angular_acceleration": "rad/s^2",
    "peak_rel_end_angular_acceleration": "rad/s^2",
    "rms_rel_end_angular_acceleration": "rad/s^2",
    "residual_rel_end_angular_acceleration": "rad/s^2",
    "settling_time": "s",
    "settled": "flag",
    "peak_joint_force": "N",
    "peak_drive_torque": "N*m",
    "drive_end_time": "s",
    "settling_band": "rad/s^2",
    "max_peak_von_mises": "Pa",
    "min_margin_of_safety": "1",
}

#: Human names of the metrics, in the order README.md ("Outputs and units") lists them.
METRIC_TITLES = {
    "peak_abs_end_angular_acceleration": "peak |absolute| end angular acceleration",
    "peak_rel_end_angular_acceleration": "peak |relative| end angular acceleration",
    "rms_rel_end_angular_acceleration": "RMS relative end angular acceleration",
    "residual_rel_end_angular_acceleration": "residual |relative| after the drive stops",
    "settling_time": "settling time",
    "settled": "settled within the band",
    "peak_joint_force": "peak joint force ‖F‖",
    "peak_drive_torque": "peak |drive torque|",
    "drive_end_time": "drive end time",
    "settling_band": "settling band",
    "max_peak_von_mises": "largest peak von Mises stress of the interfaces",
    "min_margin_of_safety": "smallest margin of safety (yield / peak − 1)",
}


def metric_unit(name):
    """SI unit of a metric: the table above, else a guess from the name, else "" (dimensionless)."""
    if name in METRIC_UNITS:
        return METRIC_UNITS[name]
    if "angular_acceleration" in name or name.endswith("_band"):
        return "rad/s^2"
    if "von_mises" in name or name == "yield_strength":
        return "Pa"
    if "margin_of_safety" in name:
        return "1"
    if name.endswith("_time") or name == "time":
        return "s"
    if name.endswith("_frequency") or name.endswith("_hz"):
        return "Hz"
    if "torque" in name:
        return "N*m"
    if "force" in name:
        return "N"
    return ""


def metric_order(names):
    """Known metrics in the order above, then any others alphabetically."""
    known = [n for n in METRIC_UNITS if n in names]
    return known + sorted(n for n in names if n not in METRIC_UNITS)


#: SI units of the configuration keys (README.md, "Configuration"), for axis labels and label hints.
CONFIG_UNITS = {
    "mast.modules": "",
    "module.side": "m",
    "module.mass": "kg",
    "interface.length": "m",
    "interface.radius": "m",
    "interface.inner_diameter": "m",
    "interface.thickness": "m",
    "interface.elements_axial": "",
    "interface.elements_circumferential": "",
    "material.youngs_modulus": "Pa",
    "material.poisson_ratio": "",
    "material.density": "kg/m^3",
    "material.damping": "s",
    "drive.angle_deg": "deg",
    "drive.duration": "s",
    "drive.ramp": "s",
    "simulation.end_time": "s",
    "simulation.time_step": "s",
    "modes.angle_deg": "deg",
}


#: Lengths shown in mm (the interface's dimensions and the module's side).
MILLIMETRE_KEYS = ("interface.thickness", "interface.inner_diameter", "interface.radius",
                   "interface.length", "module.side")

_ITEM_KEY = re.compile(r"^(module|interface)\.[0-9]+\.")


def generic_key(key):
    """The mast-wide key an item's key refines ("interface.1.thickness" -> "interface.thickness",
    the tables [module.K] and [interface.K] of docs/user_guide.md §4), for its unit and display;
    any other key unchanged."""
    return _ITEM_KEY.sub(r"\1.", key)


def format_number(value):
    """The text a table shows for a displayed value: SIGNIFICANT_DIGITS significant digits."""
    value = float(value)
    if not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    return "%.*g" % (SIGNIFICANT_DIGITS, value)


def format_si(value):
    """Exact text of an SI value (shortest round-trip form: float(text) == value)."""
    return repr(float(value))
