"""Labels of the inputs `mastrom report` is given, and the pairs it compares: which keys differ
between files, a short label per file, which ROM and full-order deployments are the same case
(report_inputs.CASE_SECTIONS), and the ROM-vs-full and mode-vs-mode comparisons of such pairs
(docs/report.md).
"""

import math
import os

import numpy as np

from report_common import CONFIG_UNITS, generic_key
from report_inputs import CASE_KEYS, CASE_SECTIONS

# --- labels and cases -----------------------------------------------------------------------------

#: Legend symbols of configuration keys whose values are lengths shown in mm.
_MILLIMETRE_SYMBOLS = {"interface.thickness": "h", "interface.inner_diameter": "D_in",
                       "interface.radius": "R", "interface.length": "L", "module.side": "d"}
#: Legend symbols (and display unit) of other physical keys.
_SYMBOLS = {"module.mass": ("m", "kg"), "material.youngs_modulus": ("E", "GPa"),
            "material.poisson_ratio": ("ν", ""), "material.density": ("ρ", "kg/m³"),
            "material.damping": ("μ", "s"), "drive.angle_deg": ("Θ", "°"),
            "drive.duration": ("T", "s"), "drive.ramp": ("t_r", "s"),
            "modes.angle_deg": ("θ0", "°"), "simulation.gravity": ("g", "m/s²")}


def _hint(key, value):
    """Short text for one configuration value, as a legend shows it: a symbol and the value in
    the unit people use (mm for the interface's lengths, GPa for E, degrees for angles). A value
    of one item (interface.1.thickness) is named by its own key: a symbol or a bare name would
    read as the whole mast's value."""
    generic = generic_key(key)

    def name(short):
        return short if generic == key else key

    if isinstance(value, (int, float)) and not isinstance(value, bool):
        if key == "mast.modules":
            return "%d modules" % value
        if generic in _MILLIMETRE_SYMBOLS:
            return "%s = %g mm" % (name(_MILLIMETRE_SYMBOLS[generic]), value * 1e3)
        if generic in _SYMBOLS:
            symbol, unit = _SYMBOLS[generic]
            shown = value * 1e-9 if unit == "GPa" else value
            return "%s = %g%s" % (name(symbol), shown,
                                  (" " + unit) if unit and unit != "°" else unit)
        unit = CONFIG_UNITS.get(generic, "")
        return "%s = %g%s" % (name(key.split(".")[-1]), value, " " + unit if unit else "")
    if key == "drive.law":
        return "%s law" % value
    if key == "simulation.gravity" and isinstance(value, list):
        return "g = (%s) m/s²" % ", ".join("%g" % v for v in value)
    return "%s = %s" % (name(key.split(".")[-1]), value)


def _key_rank(key):
    order = ("mast.", "interface.", "drive.law", "material.", "module.", "drive.")
    for rank, prefix in enumerate(order):
        if key.startswith(prefix):
            return (rank, key)
    return (len(order), key)


def differing_keys(files):
    """Configuration keys (not output.*) whose values differ between the files, most telling
    first."""
    keys = set()
    for f in files:
        keys.update(f.config)
    keys = [k for k in keys if not k.startswith("output.")]
    differing = [k for k in keys if len({repr(f.config.get(k)) for f in files}) > 1]
    return sorted(differing, key=_key_rank)


def is_case_key(key, modal=False):
    """True for a key that defines the physical case (for modal analyses also the locked angle);
    run settings — time step, end time, mode count, backend, output — are not."""
    return (key.split(".")[0] in CASE_SECTIONS or key in CASE_KEYS
            or (modal and key == "modes.angle_deg"))


#: What each kind of file is, as a legend names it.
MODEL_NAMES = {"full-order": "full order", "rom": "ROM", "modes": "modes"}


def assign_labels(files):
    """Legend labels of a group of files shown on the same axes. A label says what the curve is:
    the model (full order / ROM) and the case — the physical values that tell the files apart (at
    most three, e.g. "h = 0.5 mm", "cubic law") — never a run setting such as the time step or the
    mode count. When nothing physical differs the model alone names the curve, with the file name
    added only where two curves would otherwise share a label."""
    if not files:
        return
    modal = files[0].kind == "modes"
    keys = differing_keys(files) if len(files) > 1 else []
    keys = [k for k in keys if is_case_key(k, modal)][:3]
    for f in files:
        hints = [_hint(k, f.config[k]) for k in keys if k in f.config]
        f.case_label = ", ".join(hints)
        model = MODEL_NAMES.get(f.source, f.source)
        if modal:
            f.label = f.case_label or os.path.splitext(os.path.basename(f.path))[0]
        else:
            f.label = "%s, %s" % (model, f.case_label) if f.case_label else model
        if not f.case_label:
            f.case_label = os.path.splitext(os.path.basename(f.path))[0]
    seen = {}
    for f in files:
        seen.setdefault(f.label, []).append(f)
    for group in seen.values():
        if len(group) > 1:
            for f in group:
                f.label += " [%s]" % os.path.basename(f.path)
    if len({f.label for f in files}) < len(files):
        for f in files:
            f.label += " #%d" % (f.index + 1)
    # One colour per case, shared by its full-order and ROM curves (told apart by the line style);
    # a second file of the same model and case gets a colour of its own.
    colours, occurrences = {}, {}
    for f in files:
        occurrence = occurrences.get((f.case_label, f.source), 0)
        occurrences[(f.case_label, f.source)] = occurrence + 1
        f.colour = "C%d" % (colours.setdefault((f.case_label, occurrence), len(colours)) % 10)


def case_key(f):
    """What makes two deployments the same case: the physical configuration (CASE_SECTIONS)."""
    if not f.config:
        return ("text", f.config_text)
    return tuple(sorted((k, repr(v)) for k, v in f.config.items() if is_case_key(k)))


def rom_full_pairs(deployments):
    """(rom, full-order) pairs of the same case; each ROM file is paired with the first match."""
    fulls = [d for d in deployments if d.source == "full-order"]
    pairs = []
    for rom in (d for d in deployments if d.source == "rom"):
        match = next((f for f in fulls if case_key(f) == case_key(rom)), None)
        if match is not None:
            pairs.append((rom, match))
    return pairs


class Comparison:
    """ROM against full order on the full-order output instants inside the common time span, the
    ROM interpolated linearly: per quantity NRMSE = ‖ROM − full‖₂ / ‖full‖₂ (RMS-normalised, the
    definition of rom/model/comparison.hpp used by `mastrom validate`) and the
    largest |ROM − full| (SI)."""

    QUANTITIES = (
        ("relative end angular acceleration", "rad/s^2",
         lambda d: d.relative_angular_acceleration),
        ("absolute end angular acceleration (Z)", "rad/s^2",
         lambda d: d.angular_acceleration[:, 2]),
        ("joint force ‖F‖", "N", lambda d: np.linalg.norm(d.joint_force, axis=1)),
        ("drive torque", "N*m", lambda d: d.joint_torque),
    )

    def __init__(self, rom, full):
        self.rom, self.full = rom, full
        lo, hi = max(rom.time[0], full.time[0]), min(rom.time[-1], full.time[-1])
        tolerance = 1e-12 * max(1.0, abs(hi))
        mask = (full.time >= lo - tolerance) & (full.time <= hi + tolerance)
        self.time = full.time[mask]
        self.rows = []  # (name, si unit, nrmse, max abs error)
        self.series = {}  # name -> (full values, rom values) on self.time
        for name, unit, get in self.QUANTITIES:
            reference = get(full)[mask]
            model = np.interp(self.time, rom.time, get(rom)) if self.time.size else reference
            self.series[name] = (reference, model)
            if self.time.size == 0:
                self.rows.append((name, unit, math.nan, math.nan))
                continue
            error = model - reference
            scale = float(np.sqrt(np.mean(reference * reference)))
            rms = float(np.sqrt(np.mean(error * error)))
            self.rows.append((name, unit, rms / scale if scale > 0 else math.nan,
                              float(np.max(np.abs(error)))))

    @property
    def nrmse_relative(self):
        return self.rows[0][2]


# --- comparing two modal analyses ----------------------------------------------------------------

def _displacement_vectors(m):
    """[k, 3P] physical displacements of every drawn point (shell nodes, module corners), in the
    mast's own frame at the locked angle, so analyses at different angles compare like for like."""
    angle = m.angle_rad or 0.0
    c, s = math.cos(angle), math.sin(angle)
    rotation = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])  # global -> mast frame
    rows = []
    for mode in range(m.frequency_hz.size):
        parts = [m.views[part][2][mode] @ rotation.T for part in ("shell", "modules")]
        rows.append(np.concatenate([p.reshape(-1) for p in parts]))
    return np.array(rows)


class ModalComparison:
    """MAC between the modes of two analyses of the same mesh, and the matched pairs.

    MAC_ij = (a_iᵀ b_j)² / ((a_iᵀ a_i)(b_jᵀ b_j)) (Allemang & Brown 1982, the unweighted modal
    assurance criterion) over the displacements of the drawn points — shell nodes and module
    corners, all in metres, in the mast's frame — so it needs no mass matrix and is blind to the
    per-mode display scale. Mode i of A is matched to the mode j of B with the largest MAC_ij; the
    frequency ratio of the pair is f_B,j / f_A,i."""

    def __init__(self, a, b):
        self.a, self.b = a, b
        self.reason = None
        self.mac = None
        if a.views is None or b.views is None:
            self.reason = "a file has no /visualization group"
            return
        for part in ("shell", "modules"):
            if a.views[part][0].shape != b.views[part][0].shape or not np.array_equal(
                    a.views[part][1], b.views[part][1]):
                self.reason = ("the meshes differ (%s: %d and %d points)"
                               % (part, a.views[part][0].shape[0], b.views[part][0].shape[0]))
                return
        u, v = _displacement_vectors(a), _displacement_vectors(b)
        cross = u @ v.T
        norms = np.outer(np.einsum("ij,ij->i", u, u), np.einsum("ij,ij->i", v, v))
        with np.errstate(invalid="ignore", divide="ignore"):
            self.mac = np.where(norms > 0, cross * cross / norms, 0.0)
        #: (i, j, MAC_ij, f_B,j / f_A,i) for every mode i of A.
        self.pairs = []
        for i in range(self.mac.shape[0]):
            j = int(np.argmax(self.mac[i]))
            ratio = (b.frequency_hz[j] / a.frequency_hz[i] if a.frequency_hz[i] != 0
                     else math.nan)
            self.pairs.append((i, j, float(self.mac[i, j]), float(ratio)))
