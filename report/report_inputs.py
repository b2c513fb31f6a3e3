"""Reading the HDF5 files `mastrom report` is given, and recognising each by its root attribute
`source` (the layouts of README.md "Outputs and units" and docs/report.md):

* "full-order", "rom"  deployment files (fullorder/results_io.hpp): time series and the /metrics
                       attributes;
* "modes"              /modes/frequency_hz [k], /modes/damping_ratio [k], /modes/participation [k],
                       /modes/effective_mass_fraction [k], /modes/end_rotation [k,3], /modes/labels
                       (strings) [k], optional /modes/mac [k,k];
* "screen"             /screen/parameter_names (strings) [p], /screen/parameters [N,p],
                       /screen/metric_names (strings) [q], /screen/metrics [N,q]; the `units`
                       attribute of the two numeric datasets is one string per column (or one string
                       for all columns; without it, units come from the key and metric names);
* "uq"                 `mastrom uq` (report/report_uq.py reads it: rom/studies/uncertainty_output.hpp);
* "validation"         not laid out yet: listed generically (root attributes, datasets, attributes).

Every failure is a ReportError with one line naming the file and what is wrong.
"""

import math
import os

import h5py
import numpy as np

from report_common import CONFIG_UNITS, ReportError, metric_order, metric_unit

try:  # Python >= 3.11 (Debian 12); without it labels fall back to file names.
    import tomllib
except ImportError:  # pragma: no cover
    tomllib = None

DEPLOYMENT_SOURCES = ("full-order", "rom")
KNOWN_SOURCES = ("full-order", "rom", "modes", "screen", "rom-database", "study", "uq",
                 "validation", "optimize")

#: A mode is drive-excited when its rotation participation |Γ_k| is at least this share of the
#: largest one (the rule of rom/offline/direct_modal_model.cpp firstExcitedMode).
DRIVE_EXCITED_SHARE = 1e-3

#: Configuration sections (and single keys) that define the physical case: two deployment files with
#: equal values here are "the same case", whatever their time step, end time or output settings.
CASE_SECTIONS = ("mast", "module", "interface", "material", "drive")
CASE_KEYS = ("simulation.gravity",)


def as_text(value):
    """A string attribute or element as str, whether h5py gives bytes, numpy bytes or str."""
    if isinstance(value, np.ndarray) and value.shape == ():
        value = value[()]
    if isinstance(value, (bytes, np.bytes_)):
        return bytes(value).decode("utf-8", errors="replace")
    return str(value)


def flatten_config(text):
    """{"section.key": value} of a resolved TOML config, or {} when it cannot be parsed."""
    if tomllib is None or not text:
        return {}
    try:
        tree = tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        return {}
    flat = {}

    def walk(prefix, node):
        for key, value in node.items():
            name = prefix + key
            if isinstance(value, dict):
                walk(name + ".", value)
            else:
                flat[name] = value

    walk("", tree)
    return flat


class InputFile:
    """What every mastrom file has: path (as given), position on the command line, root
    attributes."""

    kind = "generic"

    def __init__(self, index, path, h5):
        self.index = index
        self.path = path
        self.source = as_text(h5.attrs["source"])
        self.version = as_text(h5.attrs["mastrom_version"]) if "mastrom_version" in h5.attrs else ""
        self.config_text = as_text(h5.attrs["config"]) if "config" in h5.attrs else ""
        self.config = flatten_config(self.config_text)
        self.wall_time_s = float(h5.attrs["wall_time_s"]) if "wall_time_s" in h5.attrs else None
        self.label = os.path.splitext(os.path.basename(path))[0]
        self.case_label = self.label  # the label without the source suffix
        self.output_step_rule = (as_text(h5.attrs["output_step_rule"])
                                 if "output_step_rule" in h5.attrs else "")

    def describe(self):
        """Short size text for the inputs table."""
        return ""

    # --- helpers for the subclasses -------------------------------------------------------------
    def _fail(self, what):
        raise ReportError("'%s' (%s file): %s" % (self.path, self.source, what))

    def _dataset(self, h5, name):
        if name not in h5 or not isinstance(h5[name], h5py.Dataset):
            self._fail("missing dataset " + name)
        return h5[name]

    def _numbers(self, h5, name, shape):
        """Dataset `name` as float64, shape checked against `shape` (None = any length); units."""
        dataset = self._dataset(h5, name)
        if dataset.dtype.kind not in "fiub":
            self._fail("%s is not numeric (type %s)" % (name, dataset.dtype))
        values = np.asarray(dataset[()], dtype=np.float64)
        if values.ndim != len(shape) or any(
            want is not None and have != want for have, want in zip(values.shape, shape)
        ):
            expected = "(%s%s)" % (", ".join("n" if s is None else str(s) for s in shape),
                                   "," if len(shape) == 1 else "")
            self._fail("%s has shape %s, expected %s" % (name, tuple(values.shape), expected))
        return values, as_text(dataset.attrs.get("units", ""))

    def _strings(self, h5, name, length):
        dataset = self._dataset(h5, name)
        values = [as_text(v) for v in np.asarray(dataset[()]).reshape(-1)]
        if length is not None and len(values) != length:
            self._fail("%s has %d entries, expected %d" % (name, len(values), length))
        return values


def tangential_acceleration(position, acceleration):
    """a·t̂ with t̂ = Z × p / |Z × p| per row (fullorder/deployment_result.hpp); 0 on the axis."""
    radius = np.hypot(position[:, 0], position[:, 1])
    along = -position[:, 1] * acceleration[:, 0] + position[:, 0] * acceleration[:, 1]
    return np.divide(along, radius, out=np.zeros_like(along), where=radius > 0.0)


class Deployment(InputFile):
    """A full-order or ROM deployment (fullorder/results_io.hpp)."""

    kind = "deployment"

    def __init__(self, index, path, h5):
        super().__init__(index, path, h5)
        for name in ("config", "mastrom_version", "wall_time_s"):
            if name not in h5.attrs:
                self._fail("missing root attribute " + name)
        self.time, self.time_units = self._numbers(h5, "/time", (None,))
        n = self.time.shape[0]
        if n < 1:
            self._fail("/time is empty")
        self.drive_acceleration, _ = self._numbers(h5, "/drive/acceleration", (n,))
        self.angular_acceleration, self.angular_units = self._numbers(
            h5, "/end/angular_acceleration", (n, 3))
        self.relative_angular_acceleration, self.relative_units = self._numbers(
            h5, "/end/relative_angular_acceleration", (n,))
        self.joint_force, self.force_units = self._numbers(h5, "/joint/force", (n, 3))
        self.joint_torque, self.torque_units = self._numbers(h5, "/joint/torque", (n,))
        #: The accelerometer's signal (docs/theory.md (1.11)); None when the file has neither it nor
        #: the end point's position and acceleration to derive it from (files of older versions).
        self.tangential_acceleration, self.tangential_units = None, ""
        if "/end/tangential_acceleration" in h5:
            self.tangential_acceleration, self.tangential_units = self._numbers(
                h5, "/end/tangential_acceleration", (n,))
        elif "/end/position" in h5 and "/end/acceleration" in h5:
            position, _ = self._numbers(h5, "/end/position", (n, 3))
            acceleration, self.tangential_units = self._numbers(h5, "/end/acceleration", (n, 3))
            self.tangential_acceleration = tangential_acceleration(position, acceleration)
        if "/metrics" not in h5 or not isinstance(h5["/metrics"], h5py.Group):
            self._fail("missing group /metrics")
        attributes = h5["/metrics"].attrs
        if len(attributes) == 0:
            self._fail("/metrics has no attributes")
        #: name -> float value (SI) in display order; `settled` is an int 0/1. Text attributes
        #: (how a metric was evaluated, e.g. the peak's source) are kept apart as notes.
        numeric = [name for name in attributes.keys()
                   if np.asarray(attributes[name]).dtype.kind in "fiub"]
        self.metrics = {name: float(np.asarray(attributes[name]).reshape(-1)[0])
                        for name in metric_order(numeric)}
        self.metric_notes = {name: as_text(attributes[name]) for name in attributes.keys()
                             if name not in numeric}
        self.interfaces = self._interfaces(h5, n)

    def _interfaces(self, h5, n):
        """The interface stresses (/interfaces/K, fullorder/interface_stress_io.hpp), [] if absent:
        per interface a dict with the max von Mises history [Pa] (None when absent), the recovery points' unrolled
        coordinates (axial m, angle rad), the von Mises field at the peak [Pa, per point and
        station] and the peak's attributes."""
        if "/interfaces" not in h5:
            return []
        out = []
        k = 1
        while "/interfaces/%d" % k in h5:
            g = "/interfaces/%d" % k
            # A ROM result carries the history only when asked (rom eval --stress-history).
            history = (self._numbers(h5, g + "/max_von_mises", (n,))[0]
                       if g + "/max_von_mises" in h5 else None)
            points, _ = self._numbers(h5, g + "/points", (None, 2))
            field, _ = self._numbers(h5, g + "/peak/von_mises_field", (points.shape[0], 3))
            peak = {name: float(np.asarray(value).reshape(-1)[0])
                    for name, value in h5[g + "/peak"].attrs.items()}
            out.append({"max_von_mises": history, "points": points, "field": field, "peak": peak})
            k += 1
        return out

    @property
    def drive_end_time(self):
        return self.metrics.get("drive_end_time")

    def describe(self):
        text = "%d samples, t = %.6g … %.6g s" % (self.time.shape[0], self.time[0], self.time[-1])
        # What the output step resolves (docs/theory.md §5.4a); files of earlier versions lack it.
        if self.output_step_rule:
            text += "; " + self.output_step_rule
        return text


class Modes(InputFile):
    """A modal analysis (modes/modes_file.hpp, /modes/*; /visualization of modes/xdmf_writer.hpp)."""

    kind = "modes"

    def __init__(self, index, path, h5):
        super().__init__(index, path, h5)
        self.frequency_hz, self.frequency_units = self._numbers(h5, "/modes/frequency_hz", (None,))
        k = self.frequency_hz.shape[0]
        self.columns = [("frequency_hz", self.frequency_hz, self.frequency_units)]
        for name in ("damping_ratio", "participation", "effective_mass_fraction"):
            values, units = self._numbers(h5, "/modes/" + name, (k,))
            self.columns.append((name, values, units))
        self.end_rotation, self.end_rotation_units = self._numbers(
            h5, "/modes/end_rotation", (k, 3))
        self.labels = self._strings(h5, "/modes/labels", k)
        self.mac = None
        if "/modes/mac" in h5:
            self.mac, _ = self._numbers(h5, "/modes/mac", (k, None))
        self.angle_rad = None
        if "/modes/angle_rad" in h5:
            self.angle_rad = float(self._numbers(h5, "/modes/angle_rad", (1,))[0][0])
        #: Mass-normalised shapes [k, ndof] when stored (for MAC between files), else None.
        self.shapes = None
        if "/modes/shapes" in h5:
            self.shapes, _ = self._numbers(h5, "/modes/shapes", (k, None))
        self.views = self._views(h5, k) if "/visualization" in h5 else None
        group = h5["/modes"]
        #: Stability of the linearisation point (written by `modes --allow-unstable`); None = not
        #: recorded (files of older versions), True = stable.
        self.stable = None
        self.instability = ""
        if "stable" in group.attrs and int(np.asarray(group.attrs["stable"]).reshape(-1)[0]) >= 0:
            self.stable = bool(int(np.asarray(group.attrs["stable"]).reshape(-1)[0]))
            if "instability" in group.attrs:
                self.instability = as_text(group.attrs["instability"])

    def _views(self, h5, k):
        """The drawable mesh of modes/xdmf_writer.hpp: per part (shell, modules) the points at the
        linearisation point, the cells (quads, hexahedra) and the scaled displacement of every
        mode with its scale factor (displayed = scale × mass-normalised shape)."""
        views = {}
        for part, corners in (("shell", 4), ("modules", 8)):
            base = "/visualization/%s/" % part
            points, _ = self._numbers(h5, base + "points", (None, 3))
            cells, _ = self._numbers(h5, base + "connectivity", (None, corners))
            cells = cells.astype(np.int64)
            if cells.size and (cells.min() < 0 or cells.max() >= points.shape[0]):
                self._fail("%sconnectivity refers to points outside 0 … %d"
                           % (base, points.shape[0] - 1))
            displacements, scales = [], []
            for mode in range(k):
                name = base + "mode_%03d" % (mode + 1)
                values, _ = self._numbers(h5, name, (points.shape[0], 3))
                displacements.append(values)
                scales.append(float(np.asarray(h5[name].attrs.get("scale", 1.0)).reshape(-1)[0]))
            views[part] = (points, cells, displacements, scales)
        views["relative_amplitude"] = float(np.asarray(
            h5["/visualization"].attrs.get("relative_amplitude", math.nan)).reshape(-1)[0])
        return views

    def describe(self):
        return "%d modes" % self.frequency_hz.shape[0]


class Screen(InputFile):
    """A screening table: N parameter points, p parameters, q metrics."""

    kind = "screen"

    def __init__(self, index, path, h5):
        super().__init__(index, path, h5)
        self.parameter_names = self._strings(h5, "/screen/parameter_names", None)
        self.metric_names = self._strings(h5, "/screen/metric_names", None)
        p, q = len(self.parameter_names), len(self.metric_names)
        self.parameters, _ = self._numbers(h5, "/screen/parameters", (None, p))
        n = self.parameters.shape[0]
        self.metrics, _ = self._numbers(h5, "/screen/metrics", (n, q))
        self.parameter_units = self._column_units(h5, "/screen/parameters", self.parameter_names,
                                                  lambda name: CONFIG_UNITS.get(name, ""))
        self.metric_units = self._column_units(h5, "/screen/metrics", self.metric_names,
                                               metric_unit)
        #: [(metric, maximise)] of `mastrom screen --pareto` (root attribute pareto_objectives);
        #: the front is the column pareto_front.
        self.pareto_objectives = []
        if "pareto_objectives" in h5.attrs:
            for item in as_text(h5.attrs["pareto_objectives"]).split(","):
                name, _, sense = item.partition(":")
                if name not in self.metric_names or sense not in ("min", "max"):
                    self._fail("pareto_objectives: '%s' is not METRIC:min|max of a metric here"
                               % item)
                self.pareto_objectives.append((name, sense == "max"))
            if len(self.pareto_objectives) < 2 or "pareto_front" not in self.metric_names:
                self._fail("pareto_objectives without two objectives and the pareto_front column")

    def _column_units(self, h5, name, columns, fallback):
        units = h5[name].attrs.get("units")
        if units is None:
            return [fallback(c) for c in columns]
        units = np.asarray(units)
        if units.ndim == 0:
            return [as_text(units)] * len(columns)
        units = [as_text(u) for u in units.reshape(-1)]
        if len(units) != len(columns):
            self._fail("%s: the units attribute has %d entries for %d columns"
                       % (name, len(units), len(columns)))
        return units

    def describe(self):
        return "%d points × %d parameters, %d metrics" % (
            self.parameters.shape[0], len(self.parameter_names), len(self.metric_names))


class Generic(InputFile):
    """A mastrom file whose layout the report does not know yet: listed, not plotted."""

    def __init__(self, index, path, h5):
        super().__init__(index, path, h5)
        self.datasets = []  # (name, shape, units)
        self.attributes = []  # (object, name, text)

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                self.datasets.append(("/" + name, tuple(obj.shape),
                                      as_text(obj.attrs.get("units", ""))))
            for key in sorted(obj.attrs.keys()):
                if key != "units":
                    self.attributes.append(("/" + name, key, _attribute_text(obj.attrs[key])))

        h5.visititems(visit)

    def describe(self):
        return "%d datasets (layout not known to this report)" % len(self.datasets)


def _attribute_text(value):
    array = np.asarray(value)
    if array.dtype.kind in "SUO":
        return ", ".join(as_text(v) for v in array.reshape(-1))
    return ", ".join(repr(float(v)) if array.dtype.kind == "f" else str(v)
                     for v in array.reshape(-1))


def drive_excited(frequency_hz, participation, count):
    """Column indices of the `count` lowest drive-excited modes of one model (fewer if it has
    fewer), in ascending frequency."""
    magnitude = np.abs(participation)
    largest = float(magnitude.max()) if magnitude.size else 0.0
    if not largest > 0:
        return []
    candidates = [k for k in np.argsort(frequency_hz, kind="stable")
                  if magnitude[k] >= DRIVE_EXCITED_SHARE * largest]
    return [int(k) for k in candidates[:count]]


class RomDatabaseInput(InputFile):
    """A ROM database (rom/database/database_io.hpp): the axes of its parameter box and, per sample, the
    parameters, angular frequencies ω and rotation participations Γ. The interpolation between
    the samples is evaluated by `mastrom report` in C++ (cli/report_database.hpp) and attached
    with attach_curves."""

    kind = "database"

    def __init__(self, index, path, h5):
        super().__init__(index, path, h5)
        if "/axes" not in h5 or not isinstance(h5["/axes"], h5py.Group):
            self._fail("missing group /axes")
        self.axes = []  # (key, values, units)
        for a in range(len(h5["/axes"])):
            name = "/axes/%d" % a
            if name not in h5 or "key" not in h5[name].attrs:
                self._fail("missing %s or its attribute key" % name)
            values, units = self._numbers(h5, name + "/values", (None,))
            self.axes.append((as_text(h5[name].attrs["key"]), values, units))
        p = len(self.axes)
        self.parameters, _ = self._numbers(h5, "/samples/parameters", (None, p))
        s = self.parameters.shape[0]
        self.omega, self.omega_units = self._numbers(h5, "/samples/omega", (s, None))
        k = self.omega.shape[1]
        self.participation, _ = self._numbers(h5, "/samples/rotation_participation", (s, k))
        self.reference_sample = int(np.asarray(h5.attrs.get("reference_sample", 0)).reshape(-1)[0])
        self.method = as_text(h5.attrs.get("method", ""))
        self.gravity_on = False
        if "/samples/gravity" in h5:
            gravity, _ = self._numbers(h5, "/samples/gravity", (s, 3))
            self.gravity_on = bool(np.any(gravity != 0.0))
        self.curves = None  # set by attach_curves

    def attach_curves(self, path):
        """Read the interpolated curves `mastrom report` wrote for this database."""
        try:
            with h5py.File(path, "r") as h5:
                curves = {"axes": [], "plane": None}
                for a in range(len(self.axes)):
                    base = "/axis_%d/" % a
                    curves["axes"].append((h5[base + "values"][()], h5[base + "frequency_hz"][()],
                                           h5[base + "participation"][()], h5[base + "held"][()]))
                if "/plane" in h5:
                    curves["plane"] = (h5["/plane/values_0"][()], h5["/plane/values_1"][()],
                                       h5["/plane/frequency_hz"][()],
                                       h5["/plane/participation"][()])
                curves["method"] = as_text(h5.attrs.get("method", ""))
        except (OSError, KeyError) as error:
            raise ReportError("cannot read the interpolated curves '%s' of '%s': %s"
                              % (path, self.path, error)) from None
        self.curves = curves

    def describe(self):
        return "%d samples × %d modes over %s" % (self.parameters.shape[0], self.omega.shape[1],
                                                 " × ".join(a[0] for a in self.axes))


_CLASSES = {"full-order": Deployment, "rom": Deployment, "modes": Modes, "screen": Screen,
            "rom-database": RomDatabaseInput,
            "validation": Generic}


def read_input(index, path):
    """Read and recognise one file; ReportError (one line) when it cannot be used."""
    if not os.path.exists(path):
        raise ReportError("cannot read '%s': no such file" % path)
    if os.path.isdir(path):
        raise ReportError("'%s' is a directory, not a result file" % path)
    try:
        if not h5py.is_hdf5(path):
            raise ReportError("'%s' is not an HDF5 file" % path)
        with h5py.File(path, "r") as h5:
            if "source" not in h5.attrs:
                raise ReportError("'%s' is not a mastrom result file: no root attribute 'source'"
                                  % path)
            source = as_text(h5.attrs["source"])
            if source == "study":  # its module builds on this one
                from report_study import StudyTable
                return StudyTable(index, path, h5)
            if source == "uq":  # so is the uncertainty page's
                from report_uq import UqFile
                return UqFile(index, path, h5)
            if source == "optimize":  # its module builds on this one too
                from report_optimize import OptimizeRecord
                return OptimizeRecord(index, path, h5)
            if source not in _CLASSES:
                raise ReportError("'%s': root attribute source = '%s' is not one of %s"
                                  % (path, source, ", ".join(KNOWN_SOURCES)))
            return _CLASSES[source](index, path, h5)
    except OSError as error:
        raise ReportError("cannot read '%s': %s" % (path, error)) from None
