#!/usr/bin/python3
"""Tests of `mastrom report` (report/mastrom_report.py and cli/cmd_report.cpp).

    /usr/bin/python3 tests/report/test_report.py [-v] [SyntheticTests|RealRunTests|ErrorTests]

Environment: MASTROM_EXE = the built `mastrom` executable (the CLI checks and RealRunTests are
skipped without it); MASTROM_SOURCE_DIR = the repository (default: two folders up from this file).
Registered as ctest entries report.* by tests/cli/report_cli.cmake.

What is checked: the synthetic files (deployment full-order + rom, modes, screen, validation)
written here with h5py (and a `mastrom uq` file: histograms, exceedance curves, Sobol bars, tail
table) and a real short Scheme 1 run give non-empty PNGs (signature, > 1 kB) with SVG twins
and an index.html whose every table number equals the HDF5 value to the printed precision (7
significant digits of the displayed unit, rad -> degrees); the output is byte-for-byte reproducible;
every failure is exactly one line on stderr with a non-zero exit code.
"""

import base64
import html
import html.parser
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

import h5py
import numpy as np

SOURCE_DIR = os.environ.get("MASTROM_SOURCE_DIR") or os.path.dirname(
    os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(SOURCE_DIR, "report", "mastrom_report.py")
MASTROM_EXE = os.environ.get("MASTROM_EXE", "")
PYTHON = "/usr/bin/python3"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
DEGREES = 180.0 / math.pi
#: Display unit -> factor from the SI value in the file (independent of report_common.py).
DISPLAY_FACTORS = {"°/s²": DEGREES, "°/s": DEGREES, "°": DEGREES, "MPa": 1e-6}

SYNTHETIC_CONFIG = """[mast]
modules = 4

[interface]
length = 0.05
radius = 0.041
thickness = {thickness}

[material]
youngs_modulus = 7e+10

[drive]
law = "{law}"
duration = 0.4

[simulation]
end_time = 0.5
time_step = {time_step}

[output]
file = "{name}"
"""


# --- synthetic files ------------------------------------------------------------------------------

def write_deployment(path, source="full-order", thickness=0.002, law="cubic", time_step=1e-3,
                     scale=1.0, fixed_strings=True, items=""):
    """A deployment file with the layout of fullorder/results_io.hpp and awkward numbers; `items`:
    TOML tables [module.K] / [interface.K] appended to the configuration."""
    n = 401
    t = np.linspace(0.0, 0.4, n)
    theta_dd = 3.0 * np.sin(2 * np.pi * t / 0.4)
    vibration = scale * 123.456789012345 * np.exp(-8.0 * t) * np.sin(2 * np.pi * 37.0 * t)
    alpha = np.zeros((n, 3))
    alpha[:, 0] = 1e-3 * np.cos(5 * t)
    alpha[:, 2] = theta_dd + vibration
    force = np.stack([4.0 * np.cos(3 * t), 55.5 * np.sin(3 * t) + vibration / 10, 1e-9 * t], axis=1)
    torque = 14.4702081813604 * np.cos(3 * t)
    text = (lambda s: np.bytes_(s.encode())) if fixed_strings else (lambda s: s)
    with h5py.File(path, "w") as f:
        def put(name, data, units):
            f[name] = data
            f[name].attrs["units"] = text(units)
        put("/time", t, "s")
        put("/drive/angle", np.cumsum(theta_dd) * 1e-6, "rad")
        put("/drive/rate", np.cumsum(theta_dd) * 1e-3, "rad/s")
        put("/drive/acceleration", theta_dd, "rad/s^2")
        put("/end/angular_acceleration", alpha, "rad/s^2")
        put("/end/relative_angular_acceleration", vibration, "rad/s^2")
        put("/end/position", np.zeros((n, 3)), "m")
        put("/end/acceleration", np.zeros((n, 3)), "m/s^2")
        put("/joint/force", force, "N")
        put("/joint/torque", torque, "N*m")
        put("/solver/newton_iterations", np.full(n, 3, dtype=np.int32), "1")
        put("/solver/constraint_residual", np.full(n, 1e-13), "1")
        metrics = f.create_group("/metrics")
        metrics.attrs["peak_abs_end_angular_acceleration"] = float(np.max(np.abs(alpha[:, 2])))
        metrics.attrs["peak_rel_end_angular_acceleration"] = float(np.max(np.abs(vibration)))
        metrics.attrs["rms_rel_end_angular_acceleration"] = 0.1234567890123456 * scale
        metrics.attrs["residual_rel_end_angular_acceleration"] = 9.87654321098765e-5
        metrics.attrs["settling_time"] = 0.3999999999
        metrics.attrs["settled"] = np.int32(1)
        metrics.attrs["peak_joint_force"] = float(np.max(np.linalg.norm(force, axis=1)))
        metrics.attrs["peak_drive_torque"] = 14.4702081813604
        metrics.attrs["drive_end_time"] = 0.4
        metrics.attrs["settling_band"] = math.pi / 180.0
        f.attrs["config"] = text(SYNTHETIC_CONFIG.format(thickness=thickness, law=law,
                                                         time_step=time_step,
                                                         name=os.path.basename(path)) + items)
        f.attrs["mastrom_version"] = text("0.1.0")
        f.attrs["source"] = text(source)
        f.attrs["wall_time_s"] = 1.23456789


#: Mode order of the second synthetic modes file: its mode j has the shape of mode ORDER_B[j] of the
#: first (sign and size changed), so the MAC between them is a permutation matrix.
ORDER_B = (1, 0, 2, 3, 5, 4)


def write_visualization(f, k, order):
    """/visualization as modes/xdmf_writer.hpp writes it: a 1 × 4 shell ring between two cube
    modules along x; mode j's displacement is a random field (seed order[j]), scaled and signed
    per mode (the MAC ignores both)."""
    ring = [(x, 0.041 * math.cos(p), 0.041 * math.sin(p))
            for x in (0.05, 0.1) for p in np.arange(4) * math.pi / 2]
    shell_points = np.array(ring)
    shell_cells = np.array([[i, (i + 1) % 4, 4 + (i + 1) % 4, 4 + i] for i in range(4)])
    cube = np.array([(x, y, z) for z in (-0.05, 0.05) for y, x in
                     ((-0.05, -0.05), (-0.05, 0.05), (0.05, 0.05), (0.05, -0.05))])
    module_points = np.concatenate([cube, cube + [0.15, 0.0, 0.0]])
    module_cells = np.array([np.arange(8), np.arange(8, 16)])
    f["/visualization/shell/points"] = shell_points
    f["/visualization/shell/connectivity"] = shell_cells.astype(np.int32)
    f["/visualization/modules/points"] = module_points
    f["/visualization/modules/connectivity"] = module_cells.astype(np.int32)
    f["/visualization"].attrs["relative_amplitude"] = 0.1
    for j in range(k):
        rng = np.random.default_rng(order[j])
        size = 1e-3 * (j + 1) * (-1) ** j
        shell = size * rng.normal(size=shell_points.shape)
        modules = size * rng.normal(size=module_points.shape)
        for part, values in (("shell", shell), ("modules", modules)):
            name = "/visualization/%s/mode_%03d" % (part, j + 1)
            f[name] = values
            f[name].attrs["scale"] = 0.0123456789 * (j + 1)


def write_modes(path, thickness, with_mac, shapes_seed=None, angle_rad=0.3,
                order=tuple(range(6)), unstable=False):
    """A modes file with the layout of modes/modes_file.hpp /modes/* (variable-length strings, as
    h5py) and /visualization; with `shapes_seed`, random /modes/shapes of 40 DOFs."""
    k = 6
    scale = math.sqrt(thickness / 0.002)
    frequency = np.array([12.3456789, 45.678901234, 45.9, 130.25, 411.0, 987.654321]) * scale
    with h5py.File(path, "w") as f:
        def put(name, data, units):
            f[name] = data
            f[name].attrs["units"] = units
        put("/modes/frequency_hz", frequency, "Hz")
        put("/modes/damping_ratio", 1e-5 * np.pi * frequency, "1")
        put("/modes/participation", np.array([0.3, -0.02, 1e-7, 0.15, -0.004, 2e-3]), "kg*m^2")
        put("/modes/effective_mass_fraction", np.array([0.8, 0.01, 0.0, 0.12, 0.001, 0.0005]), "1")
        put("/modes/end_rotation", np.arange(k * 3, dtype=float).reshape(k, 3) * 0.0123 - 0.1,
            "rad")
        f["/modes/labels"] = ["bending y", "ovalling 2", "ovalling 2'", "torsion", "axial",
                              "bending z"]
        if with_mac:
            mac = np.eye(k) * 0.9 + 0.1 * np.abs(np.sin(np.arange(k * k).reshape(k, k)))
            put("/modes/mac", np.clip(mac, 0.0, 1.0), "1")
        put("/modes/angle_rad", np.array([angle_rad]), "rad")
        if shapes_seed is not None:
            put("/modes/shapes", np.random.default_rng(shapes_seed).normal(size=(k, 40)), "1")
        write_visualization(f, k, order)
        f["/modes"].attrs["stable"] = np.int32(0 if unstable else 1)
        f["/modes"].attrs["instability"] = ("1 unstable direction: lowest eigenvalue omega^2 = "
                                            "-1.2e+07 rad^2/s^2 (f = -551.3 Hz), shape 'shell n=3'"
                                            if unstable else "")
        f.attrs["config"] = SYNTHETIC_CONFIG.format(thickness=thickness, law="cubic",
                                                    time_step=1e-4, name="modes.h5")
        f.attrs["mastrom_version"] = "0.1.0"
        f.attrs["source"] = "modes"
        f.attrs["wall_time_s"] = 0.5


def write_screen(path):
    """A screen file: 3 thicknesses × 4 inner diameters, two metrics (the designed layout)."""
    thickness = np.array([0.0005, 0.001, 0.0015])
    diameter = np.array([0.085, 0.09, 0.095, 0.1])
    points = np.array([(h, d) for h in thickness for d in diameter])
    peak_rel = 0.4 / points[:, 0] * points[:, 1] ** 2 / 3.0
    force = 50.0 + 1e3 * points[:, 0] + points[:, 1]
    with h5py.File(path, "w") as f:
        f["/screen/parameter_names"] = ["interface.thickness", "interface.inner_diameter"]
        f["/screen/metric_names"] = ["peak_rel_end_angular_acceleration", "peak_joint_force"]
        f["/screen/parameters"] = points
        f["/screen/parameters"].attrs["units"] = ["m", "m"]
        f["/screen/metrics"] = np.stack([peak_rel, force], axis=1)
        f["/screen/metrics"].attrs["units"] = ["rad/s^2", "N"]
        f.attrs["config"] = SYNTHETIC_CONFIG.format(thickness=0.001, law="quintic", time_step=1e-4,
                                                    name="screen.h5")
        f.attrs["mastrom_version"] = "0.1.0"
        f.attrs["source"] = "screen"
        f.attrs["wall_time_s"] = 2.0


def write_pareto_screen(path):
    """A screen marked by `--pareto mass:min,frequency_1:max`: 12 designs whose front is known by
    construction (designs 1, 4, 7 and 10 of the file: no other is lighter and stiffer)."""
    mass = np.array([1.0, 1.2, 1.5, 2.0, 2.1, 2.5, 3.0, 3.2, 3.1, 4.0, 4.2, 4.1])
    f1 = np.array([10.0, 9.0, 8.0, 20.0, 15.0, 19.0, 30.0, 25.0, 29.0, 40.0, 39.0, 35.0])
    front = np.array([1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0], dtype=float)
    thickness = np.linspace(0.0005, 0.002, 12)
    with h5py.File(path, "w") as f:
        f["/screen/parameter_names"] = ["interface.thickness"]
        f["/screen/metric_names"] = ["mass", "frequency_1", "pareto_front"]
        f["/screen/parameters"] = thickness.reshape(-1, 1)
        f["/screen/parameters"].attrs["units"] = ["m"]
        f["/screen/metrics"] = np.stack([mass, f1, front], axis=1)
        f["/screen/metrics"].attrs["units"] = ["kg", "Hz", "flag"]
        f.attrs["config"] = SYNTHETIC_CONFIG.format(thickness=0.001, law="quintic", time_step=1e-4,
                                                    name="screen.h5")
        f.attrs["mastrom_version"] = "0.1.0"
        f.attrs["source"] = "screen"
        f.attrs["wall_time_s"] = 2.0
        f.attrs["pareto_objectives"] = "mass:min,frequency_1:max"


def write_study(path):
    """A study.h5 (rom/studies/study_run.hpp layout) with the four drive laws; peak relative acceleration
    (column 1) cubic > quintic > cycloidal for the full order, and quintic largest for the ROM."""
    laws = ["cubic", "quintic", "cycloidal", "trapezoidal"]
    names = ["peak_abs_end_angular_acceleration_rad_s2", "peak_rel_end_angular_acceleration_rad_s2",
             "settling_time_s", "peak_joint_force_n"]
    full = np.array([[5.0, 3.0, 1.5, 20.0], [4.0, 2.0, 1.4, 19.0], [3.0, 1.0, 1.3, 18.0],
                     [6.0, 9.0, 1.6, 21.0]])
    rom = full.copy()
    rom[1, 1] = 3.5  # quintic above cubic: the finding does not hold for this ROM
    with h5py.File(path, "w") as f:
        f["/study/study_names"] = ["drive_laws"] * 4
        f["/study/case_names"] = laws
        f["/study/metric_names"] = names
        f["/study/configs"] = ['[drive]\nlaw = "%s"\n' % law for law in laws]
        f["/study/full_metrics"] = full
        f["/study/rom_metrics"] = rom
        f["/study/nrmse_relative_acceleration"] = np.array([0.01, 0.02, 0.03, 0.04])
        f["/study/first_bending_frequency"] = np.array([323.0, 323.0, 323.0, 323.0])
        f["/study/first_bending_frequency"].attrs["units"] = "Hz"
        f.attrs["source"] = "study"
        f.attrs["mastrom_version"] = "0.1.0"


def write_uq(path, with_limits=True):
    """A `mastrom uq` file (rom/studies/uncertainty_output.hpp): 2 inputs, 3 metrics (a force, a
    stress and the `settled` flag, which has no distribution to draw), 64 samples, one limit on the
    stress, Sobol indices and three tail runs; the third run lies outside ROM bound + full-order
    estimate on purpose."""
    rng = np.random.default_rng(5)
    rows, q = 64, 3
    inputs = np.column_stack([rng.uniform(1e-3, 2e-3, rows), rng.uniform(0.4, 0.6, rows)])
    force = 4.0 * inputs[:, 1]
    stress = 1.5e7 * inputs[:, 0] + 1e4 * inputs[:, 1]
    metrics = np.column_stack([force, stress, np.ones(rows)])
    with h5py.File(path, "w") as f:
        f["/uq/input_names"] = ["interface.thickness", "module.mass"]
        f["/uq/inputs"] = inputs
        f["/uq/inputs"].attrs["units"] = ["m", "kg"]
        f["/uq/metric_names"] = ["peak_joint_force", "max_peak_von_mises", "settled"]
        f["/uq/metrics"] = metrics
        f["/uq/metrics"].attrs["units"] = ["N", "Pa", "1"]
        f["/uq/rom_error"] = np.full((rows, 2), 1e-3)
        f["/uq/metric_error"] = np.column_stack([1e-3 * force, 1e-3 * stress, np.zeros(rows)])
        f["/uq/statistic_rows"] = np.arange(rows, dtype=float)
        for name, column in (("mean", metrics.mean(axis=0)), ("std", metrics.std(axis=0))):
            f["/uq/summary/" + name] = column
            f["/uq/summary/%s_lower" % name] = 0.99 * column
            f["/uq/summary/%s_upper" % name] = 1.01 * column
        levels = np.array([0.01, 0.05, 0.5, 0.95, 0.99])
        quantiles = np.quantile(metrics, levels, axis=0).T
        f["/uq/summary/quantile_levels"] = levels
        f["/uq/summary/quantiles"] = quantiles
        f["/uq/summary/quantiles_lower"] = 0.99 * quantiles
        f["/uq/summary/quantiles_upper"] = 1.01 * quantiles
        if with_limits:
            f["/uq/limits/text"] = ["max_peak_von_mises > 27000"]
            for name in ("probability", "conservative"):
                f["/uq/limits/" + name] = np.array([0.25])
                f["/uq/limits/%s_lower" % name] = np.array([0.15])
                f["/uq/limits/%s_upper" % name] = np.array([0.37])
            f["/uq/limits/critical_row"] = np.array([float(np.argmax(stress))])
            for name in ("first", "total"):
                value = np.array([[0.0, 1.0], [0.9, 0.1], [-1.0, -1.0]])
                f["/uq/sobol/" + name] = value
                f["/uq/sobol/%s_lower" % name] = np.where(value == -1.0, -1.0, value - 0.05)
                f["/uq/sobol/%s_upper" % name] = np.where(value == -1.0, -1.0, value + 0.05)
            f["/uq/sobol/variance"] = np.array([force.var(), stress.var(), -1.0])
            f["/uq/tails/limit"] = np.zeros(3, dtype=np.int32)
            f["/uq/tails/row"] = np.array([1, 2, 3], dtype=np.int32)
            f["/uq/tails/label"] = ["q01", "q99", "critical"]
            f["/uq/tails/rom_value"] = np.array([20000.0, 30000.0, 31000.0])
            f["/uq/tails/rom_error_bound"] = np.array([20.0, 30.0, 31.0])
            f["/uq/tails/full_value"] = np.array([20010.0, 29980.0, 30500.0])
            f["/uq/tails/full_error_estimate"] = np.array([5.0, 5.0, 50.0])
            f["/uq/tails/full_wall_time"] = np.array([1.0, 1.0, 1.0])
        f.attrs["source"] = "uq"
        f.attrs["mastrom_version"] = "0.1.0"
        f.attrs["wall_time_s"] = 1.5


def write_validation(path):
    with h5py.File(path, "w") as f:
        f["/validation/nrmse"] = np.array([0.01, 0.02])
        f["/validation/nrmse"].attrs["units"] = "1"
        f.attrs["source"] = "validation"
        f.attrs["mastrom_version"] = "0.1.0"


# --- running and reading the report ---------------------------------------------------------------

def run_python(*args, env=None):
    return subprocess.run([PYTHON, SCRIPT, *args], capture_output=True, text=True, env=env)


def run_cli(*args, env=None):
    return subprocess.run([MASTROM_EXE, *args], capture_output=True, text=True, env=env)


class _PageParser(html.parser.HTMLParser):
    """Collects <td> cells (attributes and text) and the embedded images of index.html."""

    def __init__(self):
        super().__init__()
        self.cells = []  # (attrs dict, text)
        self.images = []  # src
        self._cell = None

    def handle_starttag(self, tag, attrs):
        # Table cells, and numbers in running text (figure captions) marked like them.
        if tag == "td" or (tag == "span" and "num" in dict(attrs).get("class", "").split()):
            self._cell = (dict(attrs), [])
        elif tag == "img":
            self.images.append(dict(attrs).get("src", ""))

    def handle_data(self, data):
        if self._cell is not None:
            self._cell[1].append(data)

    def handle_endtag(self, tag):
        if tag in ("td", "span") and self._cell is not None:
            self.cells.append((self._cell[0], "".join(self._cell[1]).strip()))
            self._cell = None


def parse_page(path):
    parser = _PageParser()
    with open(path, encoding="utf-8") as stream:
        parser.feed(stream.read())
    return parser


def hdf5_value(h5, key):
    """The value a table cell's data-key names: "/group@attr", "/@attr", "/dataset[i]", "[i,j]"."""
    match = re.fullmatch(r"(/[^@\[]*)@(.+)", key)
    if match:
        return float(np.asarray(h5[match.group(1)].attrs[match.group(2)]).reshape(-1)[0])
    match = re.fullmatch(r"(/[^\[]+)\[([0-9,]+)\]", key)
    if match:
        index = tuple(int(i) for i in match.group(2).split(","))
        return float(h5[match.group(1)][()][index])
    raise AssertionError("unknown data-key " + key)


def printed_half_ulp(text):
    """Half a unit in the last printed digit of a %g number."""
    match = re.fullmatch(r"-?(\d+)(?:\.(\d*))?(?:e([-+]\d+))?", text)
    assert match, "not a number: %r" % text
    decimals = len(match.group(2) or "")
    exponent = int(match.group(3) or 0)
    return 0.5 * 10.0 ** (exponent - decimals)


class ReportCase(unittest.TestCase):
    """Helpers shared by the test classes."""

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="mastrom_report_test_")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def path(self, name):
        return os.path.join(self.tmp, name)

    def assert_ok(self, result):
        self.assertEqual(result.returncode, 0, "stdout:\n%s\nstderr:\n%s"
                         % (result.stdout, result.stderr))

    def assert_one_line_failure(self, result, pattern, code=2):
        self.assertEqual(result.returncode, code, result.stderr)
        self.assertRegex(result.stderr, r"^[^\n]+\n$", "stderr is not exactly one line")
        self.assertRegex(result.stderr, pattern)

    def check_figures(self, out_dir, expected):
        """Every expected figure is a PNG (signature, > 1 kB) with an SVG twin; returns all PNGs."""
        pngs = sorted(f for f in os.listdir(out_dir) if f.endswith(".png"))
        for name in expected:
            self.assertIn(name + ".png", pngs)
        for png in pngs:
            with open(os.path.join(out_dir, png), "rb") as stream:
                data = stream.read()
            self.assertTrue(data.startswith(PNG_SIGNATURE), png)
            self.assertGreater(len(data), 1024, png)
            svg = os.path.join(out_dir, png[:-4] + ".svg")
            with open(svg, encoding="utf-8") as stream:
                self.assertIn("<svg", stream.read(2000), svg)
        return pngs

    def check_page(self, out_dir, files, pngs):
        """index.html embeds every PNG and every number cell equals its HDF5 value as printed.
        Returns the set of (file index, key) the tables show, and the parsed page."""
        page = parse_page(os.path.join(out_dir, "index.html"))
        embedded = [src for src in page.images if src.startswith("data:image/png;base64,")]
        self.assertEqual(len(embedded), len(page.images), "every image is embedded")
        self.assertEqual(len(embedded), len(pngs))
        for src in embedded:
            self.assertTrue(base64.b64decode(src.split(",", 1)[1]).startswith(PNG_SIGNATURE))
        shown = set()
        handles = [h5py.File(f, "r") for f in files]
        try:
            for attrs, text in page.cells:
                classes = attrs.get("class", "").split()
                if "derived" in classes or not ({"num", "flag"} & set(classes)):
                    continue
                index, key = int(attrs["data-file"]), attrs["data-key"]
                value = hdf5_value(handles[index], key)
                shown.add((index, key))
                self.assertEqual(float(attrs["data-si"]), value, key)  # exact, as stored
                if "flag" in classes:
                    self.assertEqual(text, "yes" if value else "no", key)
                    continue
                unit = attrs["data-unit"]
                if "angular_acceleration" in key or "settling_band" in key:
                    self.assertEqual(unit, "°/s²", key)
                displayed = value * DISPLAY_FACTORS.get(unit, 1.0)
                tolerance = printed_half_ulp(text) * (1 + 1e-9) + 1e-300
                self.assertLessEqual(abs(float(text) - displayed), tolerance,
                                     "%s in file #%d: printed %s, file %r (%s)"
                                     % (key, index, text, value, unit))
                # 7 significant digits, no fewer unless the value is exactly shorter.
                self.assertEqual(text, "%.7g" % displayed, key)
        finally:
            for h in handles:
                h.close()
        return shown, page

    def check_all_metrics_shown(self, shown, files, page_text=None):
        """Every numeric /metrics attribute has a checked cell; a text one (how a metric was
        evaluated) appears verbatim."""
        for index, path in enumerate(files):
            with h5py.File(path, "r") as h5:
                if "metrics" not in h5:
                    continue
                for name, value in h5["/metrics"].attrs.items():
                    if np.asarray(value).dtype.kind in "fiub":
                        self.assertIn((index, "/metrics@" + name), shown, path)
                    else:
                        text = value.decode() if isinstance(value, bytes) else str(value)
                        self.assertIsNotNone(page_text, "%s: text attribute %s" % (path, name))
                        self.assertIn(html.escape(text, quote=True), page_text, name)


class SyntheticTests(ReportCase):
    """(a) Files written by this test: deployment (full-order + rom), modes, screen, validation."""

    def make_inputs(self):
        files = [self.path("thin.h5"), self.path("thick.h5"), self.path("thin_rom.h5"),
                 self.path("modes_a.h5"), self.path("modes_b.h5"), self.path("screen.h5"),
                 self.path("validation.h5")]
        write_deployment(files[0], thickness=0.0005)
        write_deployment(files[1], thickness=0.0015, fixed_strings=False)
        write_deployment(files[2], source="rom", thickness=0.0005, time_step=5e-3, scale=1.03)
        write_modes(files[3], 0.001, with_mac=True)
        write_modes(files[4], 0.002, with_mac=False, order=ORDER_B, unstable=True)
        write_screen(files[5])
        write_validation(files[6])
        return files

    def test_python_report_figures_and_tables(self):
        files = self.make_inputs()
        out = self.path("out")
        result = run_python(*files, "--out", out)
        self.assert_ok(result)
        self.assertIn("wrote " + os.path.join(out, "index.html"), result.stdout)
        pngs = self.check_figures(out, [
            "end_angular_acceleration_absolute", "end_angular_acceleration_relative",
            "joint_force", "joint_force_components", "drive_torque", "rom_vs_full_1",
            "modes_frequencies", "modes_frequency_vs_interface.thickness", "modes_mac_4",
            "modes_effective_mass_4", "modes_effective_mass_5", "mode_shape_4_1",
            "mode_shape_4_6", "mode_shape_5_3", "modes_mac_between_1",
            "screen_6_peak_rel_end_angular_acceleration", "screen_6_peak_joint_force"])
        self.assertNotIn("modes_mac_5.png", pngs)  # modes_b has no MAC matrix
        shown, page = self.check_page(out, files, pngs)
        self.check_all_metrics_shown(shown, files)
        with open(os.path.join(out, "index.html"), encoding="utf-8") as stream:
            text = stream.read()
        for index in (3, 4):
            for i in range(6):
                self.assertIn((index, "/modes/frequency_hz[%d]" % i), shown)
                self.assertIn((index, "/modes/end_rotation[%d,2]" % i), shown)
                # The caption of the mode-shape figure: scale factor and angle from the file.
                self.assertIn((index, "/visualization/shell/mode_%03d@scale" % (i + 1)), shown)
            self.assertIn((index, "/modes/angle_rad[0]"), shown)
        # The unstable file (#5) carries the warning, the stable one (#4) does not.
        warnings = re.findall(r'<h3>#(\d) [^<]*</h3>\n<p class="warning"><b>Unstable equilibrium.'
                              r'</b>[^\n]*shell n=3', text)
        self.assertEqual(warnings, ["5"])
        # Each mode's figure carries its own caption numbers.
        for i in range(6):
            caption = re.search(r'<figure id="mode_shape_4_%d">.*?</figure>' % (i + 1), text,
                                re.S).group(0)
            self.assertIn('data-key="/modes/frequency_hz[%d]"' % i, caption)
            self.assertIn('data-key="/modes/effective_mass_fraction[%d]"' % i, caption)
        # MAC between the two modes files: mode i of A matches the mode of B built from its shape,
        # with MAC 1, and the ratio of the two stored frequencies.
        table = re.search(r'<table class="mac-pairs">.*?</table>', text, re.S).group(0)
        rows = re.findall(r"<tr><td>(\d+)</td><td>[^<]*</td><td [^>]*>[^<]*</td><td>(\d+)</td>"
                          r"<td>[^<]*</td><td [^>]*>[^<]*</td>"
                          r'<td class="num derived" data-si="([^"]+)"[^>]*>[^<]*</td>'
                          r'<td class="num derived" data-si="([^"]+)"', table)
        self.assertEqual(len(rows), 6)
        with h5py.File(files[3], "r") as fa, h5py.File(files[4], "r") as fb:
            fa_hz, fb_hz = fa["/modes/frequency_hz"][()], fb["/modes/frequency_hz"][()]
        for i_text, j_text, mac, ratio in rows:
            i, j = int(i_text) - 1, int(j_text) - 1
            self.assertEqual(ORDER_B[j], i)
            self.assertAlmostEqual(float(mac), 1.0, places=12)
            self.assertAlmostEqual(float(ratio), fb_hz[j] / fa_hz[i], places=12)
        for i in range(12):
            self.assertIn((5, "/screen/metrics[%d,0]" % i), shown)
            self.assertIn((5, "/screen/parameters[%d,1]" % i), shown)
        # Labels: the configuration value that tells the files apart; configs in collapsible blocks.
        self.assertIn("full order, h = 0.5 mm", text)
        self.assertIn("full order, h = 1.5 mm", text)
        self.assertIn("ROM, h = 0.5 mm", text)
        # Never a run setting (the ROM's time step differs) nor an outside document.
        self.assertIn("<td>3</td><td>ROM, h = 0.5 mm</td>", text)
        self.assertNotIn("DESIGN", text)
        self.assertEqual(text.count("<details>"), len(files))
        self.assertIn("/validation/nrmse", text)  # listed generically

        # The ROM vs full NRMSE, recomputed here: ROM is 1.03 × the full-order vibration.
        nrmse_cells = [(a, t) for a, t in page.cells if "derived" in a.get("class", "")]
        self.assertTrue(nrmse_cells)
        with h5py.File(files[0], "r") as full, h5py.File(files[2], "r") as rom:
            reference = full["/end/relative_angular_acceleration"][()]
            model = rom["/end/relative_angular_acceleration"][()]
        expected = 100.0 * math.sqrt(np.mean((model - reference) ** 2)) / math.sqrt(np.mean(reference ** 2))
        attrs, printed = nrmse_cells[0]
        self.assertEqual(attrs["data-unit"], "%")
        self.assertLessEqual(abs(float(printed) - expected), printed_half_ulp(printed) * 1.000001)

    def test_cli_default_out_dir_and_reproducible(self):
        if not MASTROM_EXE:
            self.skipTest("MASTROM_EXE not set")
        files = self.make_inputs()
        result = run_cli("report", *files)
        self.assert_ok(result)
        default_out = os.path.join(self.tmp, "report")
        self.assertIn("wrote " + os.path.join(default_out, "index.html"), result.stdout)
        self.assertEqual(result.stdout.count("index.html"), 1)
        pngs = self.check_figures(default_out, ["rom_vs_full_1", "modes_mac_4"])
        self.check_page(default_out, files, pngs)
        # Same inputs, same bytes (no time stamps, fixed SVG ids).
        again = self.path("again")
        self.assert_ok(run_cli("report", *files, "--out", again))
        for name in sorted(os.listdir(default_out)):
            with open(os.path.join(default_out, name), "rb") as a, \
                    open(os.path.join(again, name), "rb") as b:
                self.assertEqual(a.read(), b.read(), name)
        with open(os.path.join(again, "index.html"), encoding="utf-8") as stream:
            self.assertIn('content="mastrom report (mastrom ', stream.read())

    def test_screen_metric_selects_one_heat_map(self):
        screen = self.path("screen.h5")
        write_screen(screen)
        out = self.path("out")
        self.assert_ok(run_python(screen, "--out", out, "--screen-metric", "peak_joint_force"))
        pngs = self.check_figures(out, ["screen_1_peak_joint_force"])
        self.assertEqual(pngs, ["screen_1_peak_joint_force.png"])
        self.assert_one_line_failure(
            run_python(screen, "--out", out, "--screen-metric", "nope"),
            r"^mastrom report: error: --screen-metric nope: .* peak_joint_force")

    def test_pareto_front_drawn_with_its_designs(self):
        screen = self.path("pareto.h5")
        write_pareto_screen(screen)
        out = self.path("out")
        self.assert_ok(run_python(screen, "--out", out))
        pngs = self.check_figures(out, ["pareto_1_mass_frequency_1", "screen_1_mass",
                                        "screen_1_frequency_1"])
        self.assertNotIn("screen_1_pareto_front.png", pngs)  # the flag is not a heat map
        shown, page = self.check_page(out, [screen], pngs)
        with open(os.path.join(out, "index.html"), encoding="utf-8") as stream:
            text = stream.read()
        table = re.search(r'<table class="pareto">.*?</table>', text, re.S).group(0)
        # The front's designs, numbered by their row, with their parameter and both objectives.
        self.assertEqual(re.findall(r"<tr><td>(\d+)</td>", table), ["1", "4", "7", "10"])
        for row in (0, 3, 6, 9):
            self.assertIn('data-key="/screen/parameters[%d,0]"' % row, table)
            self.assertIn('data-key="/screen/metrics[%d,1]"' % row, table)
        self.assertNotIn('data-key="/screen/metrics[1,0]"', table)
        # A file whose objectives name no metric of it is refused in one line.
        with h5py.File(screen, "a") as f:
            f.attrs["pareto_objectives"] = "weight:min,frequency_1:max"
        self.assert_one_line_failure(run_python(screen, "--out", out),
                                     r"pareto_objectives: 'weight:min' is not METRIC:min\|max")

    def test_study_findings_checked_per_model(self):
        study = self.path("study.h5")
        write_study(study)
        out = self.path("out")
        self.assert_ok(run_python(study, "--study", "drive_laws", "--out", out))
        shown, page = self.check_page(out, [study], [])
        self.assertIn((0, "/study/full_metrics[0,1]"), shown)
        self.assertIn((0, "/study/rom_metrics[3,3]"), shown)
        self.assertIn((0, "/study/nrmse_relative_acceleration[2]"), shown)
        with open(os.path.join(out, "index.html"), encoding="utf-8") as stream:
            text = stream.read()
        # cubic > quintic > cycloidal holds for the full order; the ROM has quintic above cubic.
        self.assertEqual(re.findall(r'data-holds="(\w+)"', text), ["True", "False"])
        # The trapezoidal case is not part of the finding's ordering.
        finding = re.search(r'<table class="findings">.*?</table>', text, re.S).group(0)
        self.assertNotIn("trapezoidal", finding)
        self.assert_one_line_failure(
            run_python(study, "--study", "nope", "--out", out),
            r"^mastrom report: error: --study nope: .* holds the studies drive_laws")

    def test_uq_page_histograms_exceedance_sobol_and_tails(self):
        uq = self.path("uq.h5")
        write_uq(uq)
        out = self.path("out")
        self.assert_ok(run_python(uq, "--out", out))
        pngs = self.check_figures(out, ["uq_1_histograms", "uq_1_exceedance", "uq_1_sobol"])
        self.assertEqual(len(pngs), 3)
        shown, _ = self.check_page(out, [uq], pngs)
        for key in ("/uq/summary/mean[1]", "/uq/summary/quantiles[0,3]",
                    "/uq/limits/probability[0]", "/uq/limits/conservative_upper[0]",
                    "/uq/tails/full_value[2]", "/uq/tails/full_error_estimate[0]"):
            self.assertIn((0, key), shown)
        with open(os.path.join(out, "index.html"), encoding="utf-8") as stream:
            text = stream.read()
        tails = re.search(r'<table class="uq-tails">.*?</table>', text, re.S).group(0)
        # |ROM − full| against bound + estimate: 10 <= 25, 20 <= 35, 500 > 81.
        self.assertEqual(re.findall(r"<td>(yes|<b>no</b>)", tails), ["yes", "yes", "<b>no</b>"])

    def test_uq_page_without_limits(self):
        uq = self.path("uq.h5")
        write_uq(uq, with_limits=False)
        out = self.path("out")
        self.assert_ok(run_python(uq, "--out", out))
        pngs = self.check_figures(out, ["uq_1_histograms"])
        self.assertEqual(pngs, ["uq_1_histograms.png"])
        self.check_page(out, [uq], pngs)
        with open(os.path.join(out, "index.html"), encoding="utf-8") as stream:
            text = stream.read()
        self.assertIn("No limits in this study", text)
        self.assertIn("No full-order tail runs", text)
        # A limit that is not METRIC OP VALUE is refused in one line.
        with h5py.File(uq, "a") as f:
            f["/uq/limits/text"] = ["weight > 3"]
            for name in ("probability", "conservative"):
                for suffix in ("", "_lower", "_upper"):
                    f["/uq/limits/%s%s" % (name, suffix)] = np.array([0.1])
        self.assert_one_line_failure(run_python(uq, "--out", out),
                                     r"/uq/limits/text\[0\] = 'weight > 3' is not METRIC OP VALUE")

    def test_single_deployment_labelled_by_file_name(self):
        path = self.path("scheme_x.h5")
        write_deployment(path)
        out = self.path("out")
        self.assert_ok(run_python(path, "--out", out))
        pngs = self.check_figures(out, ["end_angular_acceleration_absolute", "joint_force"])
        self.assertNotIn("rom_vs_full_1.png", pngs)
        shown, _ = self.check_page(out, [path], pngs)
        self.check_all_metrics_shown(shown, [path])


    def test_item_values_labelled_by_the_item_key(self):
        # Two runs that differ only in one item's values (a camera mast's [interface.1] and
        # [module.2]): the legend names the item keys, in the unit of their kind (mm, kg), and
        # shows no mast-wide name such as "thickness = 0.0031" or "h = 3.1 mm".
        cases = {"item_a.h5": (0.0031, 0.7), "item_b.h5": (0.0021, 0.9)}
        paths = []
        for name, (h, m) in cases.items():
            paths.append(self.path(name))
            write_deployment(paths[-1], items="\n[interface.1]\nthickness = %r\n\n"
                             "[module.2]\nmass = %r\n" % (h, m))
        out = self.path("out")
        self.assert_ok(run_python(*paths, "--out", out))
        self.check_figures(out, ["end_angular_acceleration_relative"])
        with open(os.path.join(out, "end_angular_acceleration_relative.svg"),
                  encoding="utf-8") as stream:
            texts = re.findall(r"<text[^>]*>([^<]*)</text>", stream.read())  # svg.fonttype none
        for h, m in cases.values():
            self.assertIn("full order, interface.1.thickness = %g mm, module.2.mass = %g kg"
                          % (h * 1e3, m), texts)
        for text in texts:
            self.assertNotRegex(text, r"(^|, )(thickness|mass|h|m) = ", texts)


class RealRunTests(ReportCase):
    """(b) A real short Scheme 1 deployment (`mastrom simulate`, 0.05 s), then `mastrom report`."""

    def test_simulate_then_report(self):
        if not MASTROM_EXE:
            self.skipTest("MASTROM_EXE not set")
        h5 = self.path("scheme1_short.h5")
        simulate = subprocess.run(
            [MASTROM_EXE, "simulate", os.path.join(SOURCE_DIR, "configs", "scheme1.toml"),
             "--set", "simulation.end_time=0.05", "--set", "drive.duration=0.04",
             "--set", "drive.ramp=0.01", "--set", "drive.angle_deg=10", "-q", "-o", h5],
            capture_output=True, text=True)
        self.assert_ok(simulate)
        out = self.path("report_out")
        result = run_cli("report", h5, "--out", out)
        self.assert_ok(result)
        self.assertIn("wrote " + os.path.join(out, "index.html"), result.stdout)
        pngs = self.check_figures(out, [
            "end_angular_acceleration_absolute", "end_angular_acceleration_relative",
            "joint_force", "joint_force_components", "drive_torque",
            "end_tangential_acceleration"])
        shown, _ = self.check_page(out, [h5], pngs)
        with open(os.path.join(out, "index.html"), encoding="utf-8") as stream:
            self.check_all_metrics_shown(shown, [h5], stream.read())
        self.assertIn((0, "/@wall_time_s"), shown)


class ModalRunTests(ReportCase):
    """(d) Real modal analyses and a ROM database of Scheme 1 (dense solver, seconds), then
    `mastrom report`: shapes, MAC between two analyses, frequencies over the database's axes."""

    def mastrom(self, *args):
        result = subprocess.run([MASTROM_EXE, *args], capture_output=True, text=True)
        self.assert_ok(result)
        return result

    def setUp(self):
        super().setUp()
        if not MASTROM_EXE:
            self.skipTest("MASTROM_EXE not set")
        self.config = os.path.join(SOURCE_DIR, "configs", "scheme1.toml")

    def test_modes_report_with_shapes_and_mac(self):
        a, b = self.path("a_modes.h5"), self.path("b_modes.h5")
        self.mastrom("modes", self.config, "--backend", "dense", "--set", "modes.count=5",
                     "-q", "-o", a)
        self.mastrom("modes", self.config, "--backend", "dense", "--set", "modes.count=5",
                     "--set", "interface.thickness=0.001", "--set", "modes.angle_deg=40",
                     "-q", "-o", b)
        out = self.path("report")
        self.mastrom("report", a, b, "--out", out)
        expected = ["mode_shape_%d_%d" % (f, k) for f in (1, 2) for k in range(1, 6)]
        pngs = self.check_figures(out, expected + ["modes_effective_mass_1", "modes_mac_between_1"])
        shown, page = self.check_page(out, [a, b], pngs)
        for f in (0, 1):
            for k in range(5):
                self.assertIn((f, "/modes/frequency_hz[%d]" % k), shown)
                self.assertIn((f, "/modes/effective_mass_fraction[%d]" % k), shown)
        # A thinner shell, rotated 40°: the same shapes in the mast's frame (MAC of the matched
        # pairs near 1), and the frequency ratio is the ratio of the two stored frequencies.
        with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
            fa_hz, fb_hz = fa["/modes/frequency_hz"][()], fb["/modes/frequency_hz"][()]
        derived = [(attrs, text) for attrs, text in page.cells
                   if "derived" in attrs.get("class", "")]
        self.assertEqual(len(derived), 10)  # MAC and ratio of 5 pairs
        with open(os.path.join(out, "index.html"), encoding="utf-8") as stream:
            text = stream.read()
        self.assertIn("θ0 = 40°", text)  # the legend of B names its case, not its file
        for i in range(5):
            mac, ratio = float(derived[2 * i][0]["data-si"]), float(derived[2 * i + 1][0]["data-si"])
            self.assertGreater(mac, 0.9, "pair %d" % (i + 1))
            self.assertTrue(any(abs(ratio - fb_hz[j] / fa_hz[i]) <= 1e-12 * ratio
                                for j in range(5)), "pair %d ratio %r" % (i + 1, ratio))

    def test_database_report_curves_through_samples(self):
        db = self.path("db.h5")
        self.mastrom("rom", "build", self.config, "--param", "interface.thickness=0.001:0.002:3",
                     "--param", "module.mass=0.4:0.6:2", "--modes", "6", "--backend", "dense",
                     "-q", "-o", db)
        out = self.path("report")
        self.mastrom("report", db, "--out", out)
        pngs = self.check_figures(out, ["database_1_frequency_vs_interface.thickness",
                                        "database_1_frequency_vs_module.mass",
                                        "database_1_frequency_map"])
        shown, page = self.check_page(out, [db], pngs)
        for s in range(6):
            self.assertIn((0, "/samples/parameters[%d,0]" % s), shown)
        with h5py.File(db, "r") as h5:
            omega = h5["/samples/omega"][()]
            parameters = h5["/samples/parameters"][()]
            gamma = h5["/samples/rotation_participation"][()]
            reference = int(h5.attrs["reference_sample"])
        hz_cells = [(attrs, text) for attrs, text in page.cells if "data-from" in attrs]
        self.assertGreaterEqual(len(hz_cells), 6 * 2)  # at least two drive-excited modes each
        for attrs, text in hz_cells:
            s, k = (int(v) for v in re.fullmatch(r"/samples/omega\[(\d+),(\d+)\]",
                                                 attrs["data-from"]).groups())
            self.assertEqual(float(attrs["data-si"]), omega[s, k] / (2 * math.pi))
            self.assertEqual(text, "%.7g" % (omega[s, k] / (2 * math.pi)))
        # The interpolated curve passes through the samples on its line: the manifold and tracked
        # interpolations reproduce a sample exactly (to the round-off of the small eigenproblem).
        with h5py.File(os.path.join(out, "rom_database_1.h5"), "r") as curves:
            values = curves["/axis_0/values"][()]
            hz = curves["/axis_0/frequency_hz"][()]
            np.testing.assert_array_equal(curves["/axis_0/held"][()], parameters[reference])
        on_line = np.isclose(parameters[:, 1], parameters[reference, 1], rtol=0, atol=0)
        for s in np.flatnonzero(on_line):
            i = int(np.argmin(np.abs(values - parameters[s, 0])))
            self.assertLess(abs(values[i] - parameters[s, 0]), 1e-15)
            np.testing.assert_allclose(np.sort(hz[i]), np.sort(omega[s] / (2 * math.pi)),
                                       rtol=1e-8)


class StudyTests(ReportCase):
    """(e) A tiny study (Scheme 3, three shell thicknesses, 0.3 s): `mastrom study` writes
    <study>/report/index.html with the overlays, the study's numbers as stored in study.h5 and the
    verdict of each finding, recomputed here from study.h5."""

    def test_study_writes_its_report(self):
        if not MASTROM_EXE:
            self.skipTest("MASTROM_EXE not set")
        out = self.path("studies")
        result = subprocess.run(
            [MASTROM_EXE, "study", "shell_thickness", "--set", "simulation.end_time=0.3",
             "--set", "drive.duration=0.2", "--set", "drive.ramp=0.05", "--set",
             "drive.angle_deg=10", "-q", "-o", out], capture_output=True, text=True)
        self.assert_ok(result)
        report = os.path.join(out, "shell_thickness", "report")
        self.assertIn("wrote " + os.path.join(report, "index.html"), result.stdout)
        pngs = self.check_figures(report, ["end_angular_acceleration_absolute",
                                           "end_angular_acceleration_relative", "joint_force",
                                           "rom_vs_full_1", "rom_vs_full_3"])
        table = os.path.join(out, "study.h5")
        cases = ["h0.5mm", "h1.0mm", "h1.5mm"]
        files = [table] + [os.path.join(out, "shell_thickness", "%s_%s.h5" % (c, m))
                           for c in cases for m in ("full", "rom")]
        shown, page = self.check_page(report, files, pngs)
        with h5py.File(table, "r") as h5:
            names = [n.decode() if isinstance(n, bytes) else n for n in h5["/study/metric_names"]]
            full, rom = h5["/study/full_metrics"][()], h5["/study/rom_metrics"][()]
        for i in range(3):
            for j in range(len(names)):
                self.assertIn((0, "/study/full_metrics[%d,%d]" % (i, j)), shown)
                self.assertIn((0, "/study/rom_metrics[%d,%d]" % (i, j)), shown)
        with open(os.path.join(report, "index.html"), encoding="utf-8") as stream:
            text = stream.read()
        self.assertIn("full order, h = 0.5 mm", text)
        self.assertIn("ROM, h = 1.5 mm", text)
        # The first finding: peak relative acceleration decreasing with thickness (cases are in
        # ascending thickness in the study file).
        column = names.index("peak_rel_end_angular_acceleration_rad_s2")
        verdicts = re.findall(r'<td class="verdict" data-holds="(True|False|None)">', text)
        self.assertEqual(len(verdicts), 4)  # two findings × (full order, ROM)
        for model, data in enumerate((full, rom)):
            expected = bool(np.all(np.diff(data[:, column]) < 0))
            self.assertEqual(verdicts[model], str(expected))


class ErrorTests(ReportCase):
    """(c) Every failure: exit code ≠ 0 and exactly one line on stderr, from Python and the CLI."""

    def both(self, args, python_pattern, code=2, env=None):
        self.assert_one_line_failure(run_python(*args, env=env),
                                     r"^mastrom report: error: " + python_pattern, code)
        if MASTROM_EXE:
            self.assert_one_line_failure(run_cli("report", *args, env=env),
                                         r"^mastrom: error: report: " + python_pattern, code)

    def test_missing_file(self):
        self.both([self.path("absent.h5")], r"cannot read '.*absent\.h5': no such file")

    def test_not_hdf5(self):
        path = self.path("notes.h5")
        with open(path, "w") as stream:
            stream.write("not an HDF5 file\n")
        self.both([path], r"'.*notes\.h5' is not an HDF5 file")

    def test_foreign_hdf5(self):
        path = self.path("foreign.h5")
        with h5py.File(path, "w") as f:
            f["data"] = np.arange(3.0)
        self.both([path], r"'.*foreign\.h5' is not a mastrom result file: no root attribute "
                          r"'source'")

    def test_unknown_source(self):
        path = self.path("odd.h5")
        with h5py.File(path, "w") as f:
            f.attrs["source"] = "spreadsheet"
        self.both([path], r".*root attribute source = 'spreadsheet' is not one of full-order, rom")

    def test_missing_dataset(self):
        path = self.path("broken.h5")
        write_deployment(path)
        with h5py.File(path, "r+") as f:
            del f["/joint/force"]
        self.both([path], r"'.*broken\.h5' \(full-order file\): missing dataset /joint/force")

    def test_wrong_shape(self):
        path = self.path("short.h5")
        write_deployment(path)
        with h5py.File(path, "r+") as f:
            del f["/joint/torque"]
            f["/joint/torque"] = np.zeros(7)
        self.both([path], r".*/joint/torque has shape \(7,\), expected \(401,\)")

    def test_modes_missing_dataset(self):
        path = self.path("modes.h5")
        write_modes(path, 0.002, with_mac=False)
        with h5py.File(path, "r+") as f:
            del f["/modes/labels"]
        self.both([path], r".*\(modes file\): missing dataset /modes/labels")

    def test_second_file_bad_after_good_one(self):
        good = self.path("good.h5")
        write_deployment(good)
        self.both([good, self.path("absent.h5")], r"cannot read '.*absent\.h5'")

    def test_unknown_option(self):
        good = self.path("good.h5")
        write_deployment(good)
        self.assert_one_line_failure(run_python(good, "--bogus"),
                                     r"^mastrom report: error: unrecognized arguments: --bogus")

    def test_missing_python_module(self):
        # A stand-in h5py that fails to import, first on the module path.
        fake = self.path("fake_modules")
        os.makedirs(fake)
        with open(os.path.join(fake, "h5py.py"), "w") as stream:
            stream.write("raise ImportError('simulated: h5py is not installed')\n")
        env = dict(os.environ, PYTHONPATH=fake)
        good = self.path("good.h5")
        write_deployment(good)
        self.both([good], r"Python module 'h5py' is missing .*install the Debian package "
                          r"python3-h5py", code=1, env=env)

    def test_cli_script_override(self):
        if not MASTROM_EXE:
            self.skipTest("MASTROM_EXE not set")
        good = self.path("good.h5")
        write_deployment(good)
        env = dict(os.environ, MASTROM_REPORT_SCRIPT=self.path("nowhere.py"))
        self.assert_one_line_failure(run_cli("report", good, env=env),
                                     r"^mastrom: error: report: cannot read the report program "
                                     r"'.*nowhere\.py'", code=1)


def run_shard(argv):
    """`CLASS... --shard K/N`: the K-th of N interleaved parts of the named classes' tests, in their
    sorted order (tests/cli/report_cli.cmake runs the longest class as parts side by side). Every
    test falls in exactly one part, so none is lost when a test is added."""
    at = argv.index("--shard")
    k, n = (int(v) for v in argv[at + 1].split("/"))
    if not 0 <= k < n:
        sys.exit("--shard K/N needs 0 <= K < N, got %s" % argv[at + 1])
    names = [a for a in argv[1:at] + argv[at + 2:] if not a.startswith("-")]
    loader = unittest.TestLoader()
    suite = unittest.TestSuite()
    for name in names:
        suite.addTests(list(loader.loadTestsFromName(name, sys.modules[__name__]))[k::n])
    result = unittest.TextTestRunner(verbosity=2 if "-v" in argv else 1).run(suite)
    sys.exit(0 if result.wasSuccessful() and result.testsRun > 0 else 1)


if __name__ == "__main__":
    if "--shard" in sys.argv:
        run_shard(sys.argv)
    unittest.main()
