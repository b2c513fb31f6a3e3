"""The figures of `mastrom report`, drawn with matplotlib (Agg backend, no display) and saved as PNG
(embedded in index.html) and SVG (alongside, for print). Output is deterministic: fixed backend,
fixed SVG id salt, no dates in the metadata.

Deployment figures overlay every deployment file on the same axes, one line per file (ROM dashed),
with a dotted vertical line where the drive stops; they correspond to the paper's Figures 7, 9, 11,
13 (absolute end angular acceleration), 14 (relative) and 8, 10, 12 (joint force).
"""

import math
import os
import re

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams.update({
    "svg.hashsalt": "mastrom-report",  # reproducible element ids in the SVG files
    "svg.fonttype": "none",  # text stays text in the SVG (smaller, searchable)
    "axes.grid": True,
    "grid.alpha": 0.3,
    "font.size": 9,
    "axes.titlesize": 10,
    "legend.fontsize": 8,
    "lines.linewidth": 1.0,
})
from matplotlib import transforms  # noqa: E402  (after the backend is fixed)
from matplotlib.figure import Figure  # noqa: E402
import numpy as np  # noqa: E402

from report_common import (CONFIG_UNITS, METRIC_TITLES, MILLIMETRE_KEYS,  # noqa: E402
                           display_unit, generic_key)

DPI = 120
#: A signal whose largest magnitude is below this fraction of its neighbours' (e.g. the out-of-plane
#: joint force of a planar deployment) is round-off: drawn at the neighbours' scale and said so.
ROUND_OFF = 1e-6
WIDE = (8.0, 4.2)


class FigureFile:
    """One saved figure: file names relative to the output directory, and what it shows."""

    def __init__(self, name, title, caption):
        self.name = name
        self.title = title
        self.caption = caption
        self.png = name + ".png"
        self.svg = name + ".svg"


def safe_name(text):
    """A file-name-safe version of `text`."""
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text).strip("_") or "figure"


def save(figure, out_dir, name, title, caption):
    """Write `figure` as out_dir/name.png and .svg; returns the FigureFile."""
    entry = FigureFile(name, title, caption)
    figure.savefig(os.path.join(out_dir, entry.png), dpi=DPI, format="png")
    figure.savefig(os.path.join(out_dir, entry.svg), format="svg", metadata={"Date": None})
    return entry


def _new_figure(size=WIDE, rows=1, height_ratios=None):
    figure = Figure(figsize=size, layout="constrained")
    axes = figure.subplots(rows, 1, sharex=True, squeeze=False,
                           gridspec_kw={"height_ratios": height_ratios} if height_ratios else None)
    return figure, [row[0] for row in axes]


def _legend_below(axis, entries):
    """Legend under the axis, clear of the tick labels and the x label whatever the axis height
    (constrained layout makes room for it)."""
    if entries > 1:
        anchor = transforms.offset_copy(axis.transAxes, fig=axis.figure, y=-0.5, units="inches")
        axis.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), bbox_transform=anchor,
                    ncol=min(entries, 3), frameon=False)


def _mark_drive_end(axis, deployments):
    """Dotted vertical line at each distinct drive end time inside the record; 1 if drawn."""
    ends = sorted({d.drive_end_time for d in deployments if d.drive_end_time is not None})
    t_max = max(float(d.time[-1]) for d in deployments)
    drawn = 0
    for end in ends:
        if 0.0 < end <= t_max:
            axis.axvline(end, color="0.4", linestyle=":", linewidth=1.0,
                         label="drive stops" if not drawn else None)
            drawn = 1
    return drawn


def _line_style(deployment):
    return "--" if deployment.source == "rom" else "-"


def _time_series(deployments, get, si_unit_of, symbol, title):
    """One axis, one line per deployment: get(d) in the display unit of si_unit_of(d)."""
    figure, (axis,) = _new_figure()
    unit = display_unit(si_unit_of(deployments[0]))[0]
    for d in deployments:
        factor = display_unit(si_unit_of(d))[1]
        axis.plot(d.time, get(d) * factor, _line_style(d), color=d.colour, label=d.label)
    extra = _mark_drive_end(axis, deployments)
    axis.set_xlabel("time [s]")
    axis.set_ylabel("%s [%s]" % (symbol, unit))
    axis.set_title(title)
    _legend_below(axis, len(deployments) + extra)
    return figure


def deployment_figures(deployments, out_dir):
    """The time-series figures of all deployment files, overlaid."""
    figures = []
    figure = _time_series(
        deployments, lambda d: d.angular_acceleration[:, 2], lambda d: d.angular_units,
        r"$\alpha_z$", "Absolute end angular acceleration (Z component)")
    figures.append(save(figure, out_dir, "end_angular_acceleration_absolute",
                        "Absolute end angular acceleration",
                        "Z component of the last module's angular acceleration in the global frame "
                        "(as the paper's Figures 7, 9, 11 and 13)."))
    figure = _time_series(
        deployments, lambda d: d.relative_angular_acceleration, lambda d: d.relative_units,
        r"$\alpha_z - \ddot\theta$",
        r"Relative end angular acceleration (absolute − drive $\ddot\theta$)")
    figures.append(save(figure, out_dir, "end_angular_acceleration_relative",
                        "Relative end angular acceleration",
                        "Absolute Z angular acceleration of the last module minus the drive's "
                        "prescribed θ̈(t): the vibration (as the paper's Figure 14)."))
    figure = _time_series(
        deployments, lambda d: np.linalg.norm(d.joint_force, axis=1), lambda d: d.force_units,
        r"$\|F\|$", "Joint force magnitude")
    figures.append(save(figure, out_dir, "joint_force",
                        "Joint force magnitude",
                        "Euclidean norm of the base joint's reaction force on module 1 "
                        "(as the paper's Figures 8, 10 and 12)."))

    figure, axes = _new_figure(size=(8.0, 6.0), rows=3)
    unit = display_unit(deployments[0].force_units)[0]
    peaks = [max(float(np.max(np.abs(d.joint_force[:, c]))) for d in deployments)
             for c in range(3)]
    largest = max(peaks)
    for component, axis in enumerate(axes):
        for d in deployments:
            axis.plot(d.time, d.joint_force[:, component], _line_style(d), color=d.colour,
                      label=d.label)
        axis.set_ylabel("$F_%s$ [%s]" % ("xyz"[component], unit))
        if largest > 0.0 and peaks[component] <= ROUND_OFF * largest:
            # Zero up to round-off: on its own autoscaled axis the noise would look like a signal.
            axis.set_ylim(-largest, largest)
            axis.text(0.5, 0.75, "zero to round-off (|F_%s| ≤ %.1e %s)"
                      % ("xyz"[component], peaks[component], unit),
                      transform=axis.transAxes, ha="center", va="center", color="0.3",
                      bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8})
    extra = _mark_drive_end(axes[-1], deployments)
    for axis in axes[:-1]:
        _mark_drive_end(axis, deployments)
    axes[0].set_title("Joint force components (global frame)")
    axes[-1].set_xlabel("time [s]")
    _legend_below(axes[-1], len(deployments) + extra)
    figures.append(save(figure, out_dir, "joint_force_components", "Joint force components",
                        "X, Y and Z components of the base joint's reaction force on module 1, "
                        "global frame (X = stowed mast axis, Y = deployed, Z = joint axis). A "
                        "component below %g of the largest is round-off: drawn on the largest "
                        "one's scale and marked so." % ROUND_OFF))

    figure = _time_series(deployments, lambda d: d.joint_torque, lambda d: d.torque_units,
                          r"$\tau_z$", "Drive torque about the joint axis Z")
    figures.append(save(figure, out_dir, "drive_torque", "Drive torque",
                        "Torque the drive applies about the joint axis Z."))
    with_tangential = [d for d in deployments if d.tangential_acceleration is not None]
    if with_tangential:
        figure = _time_series(
            with_tangential, lambda d: d.tangential_acceleration, lambda d: d.tangential_units,
            r"$a_t$", "Tangential acceleration of the end point")
        figures.append(save(figure, out_dir, "end_tangential_acceleration",
                            "Tangential end acceleration",
                            "Linear acceleration of the last module's centroid along its direction "
                            "of motion about the joint axis, what an accelerometer on the tip "
                            "measures (as in the experiment of [LW24], docs/theory.md (1.11))."))
    return figures


def comparison_figure(number, comparison, out_dir):
    """ROM over full order: relative end angular acceleration, and ROM − full below."""
    name = "relative end angular acceleration"
    reference, model = comparison.series[name]
    unit, factor = display_unit("rad/s^2")
    nrmse = comparison.nrmse_relative
    figure, (top, bottom) = _new_figure(size=(8.0, 5.5), rows=2, height_ratios=(2, 1))
    top.plot(comparison.time, reference * factor, "-", color="C0",
             label="full order: #%d %s" % (comparison.full.index + 1, comparison.full.case_label))
    top.plot(comparison.time, model * factor, "--", color="C1",
             label="ROM: #%d %s" % (comparison.rom.index + 1, comparison.rom.case_label))
    top.set_ylabel(r"$\alpha_z - \ddot\theta$ [%s]" % unit)
    top.set_title("ROM vs full order — relative end angular acceleration; NRMSE = %s"
                  % ("n/a" if math.isnan(nrmse) else "%.3g %%" % (100.0 * nrmse)))
    top.legend(loc="upper right")
    bottom.plot(comparison.time, (model - reference) * factor, "-", color="C3")
    bottom.axhline(0.0, color="0.5", linewidth=0.8)
    bottom.set_ylabel("ROM − full [%s]" % unit)
    bottom.set_xlabel("time [s]")
    for axis in (top, bottom):
        _mark_drive_end(axis, [comparison.full])
    return save(figure, out_dir, "rom_vs_full_%d" % number,
                "ROM vs full order %d" % number,
                "Top: relative end angular acceleration of the full-order run (solid) and of the "
                "ROM (dashed, interpolated linearly onto the full-order instants). Bottom: ROM − "
                "full. NRMSE = RMS(ROM − full) / RMS(full) over the common time span.")


def _parameter_axis(key):
    """(label, factor) for a configuration key on an axis: lengths of the interface in mm."""
    if generic_key(key) in MILLIMETRE_KEYS:
        return "%s [mm]" % key, 1e3
    unit = CONFIG_UNITS.get(generic_key(key), "")
    return ("%s [%s]" % (key, unit) if unit else key), 1.0


def modes_figures(modes, out_dir, differing):
    """Frequencies by mode number (all files), frequency vs a parameter when the files differ in a
    numeric configuration key, and the MAC matrix of every file that stores one."""
    figures = []
    figure, (axis,) = _new_figure()
    frequencies = np.concatenate([m.frequency_hz for m in modes])
    positive = frequencies[frequencies > 0]
    spread = float(positive.max() / positive.min()) if positive.size else 1.0
    for m in modes:
        axis.plot(np.arange(1, m.frequency_hz.size + 1), m.frequency_hz, "o-", label=m.label)
    if spread > 100.0:
        axis.set_yscale("log")
    axis.set_xlabel("mode number")
    axis.set_ylabel("frequency [Hz]")
    axis.set_title("Natural frequencies")
    axis.xaxis.get_major_locator().set_params(integer=True)
    _legend_below(axis, len(modes))
    figures.append(save(figure, out_dir, "modes_frequencies", "Natural frequencies",
                        "Frequency of every mode, by mode number, one line per modal analysis."))

    numeric = [k for k in differing
               if all(isinstance(m.config.get(k), (int, float))
                      and not isinstance(m.config.get(k), bool) for m in modes)]
    if len(modes) > 1 and numeric:
        key = numeric[0]
        label, factor = _parameter_axis(key)
        ordered = sorted(modes, key=lambda m: m.config[key])
        x = np.array([m.config[key] for m in ordered], dtype=float) * factor
        count = min(m.frequency_hz.size for m in ordered)
        figure, (axis,) = _new_figure()
        for j in range(count):
            axis.plot(x, [m.frequency_hz[j] for m in ordered], "o-", label="mode %d" % (j + 1))
        if spread > 100.0:
            axis.set_yscale("log")
        axis.set_xlabel(label)
        axis.set_ylabel("frequency [Hz]")
        axis.set_title("Frequency vs %s" % key)
        if count <= 12:
            _legend_below(axis, count)
        figures.append(save(figure, out_dir, "modes_frequency_vs_" + safe_name(key),
                            "Frequency vs %s" % key,
                            "Frequency of mode j (by mode number, not tracked by MAC) against "
                            "%s, one point per modal-analysis file." % key))

    for m in modes:
        if m.mac is None:
            continue
        rows, cols = m.mac.shape
        figure = Figure(figsize=(5.2, 4.4), layout="constrained")
        axis = figure.subplots()
        image = axis.imshow(m.mac, vmin=0.0, vmax=1.0, cmap="viridis", origin="upper",
                            interpolation="nearest")
        figure.colorbar(image, ax=axis, label="MAC [–]")
        axis.set_xticks(range(cols), [str(j + 1) for j in range(cols)])
        axis.set_yticks(range(rows), [str(i + 1) for i in range(rows)])
        axis.grid(False)
        axis.set_xlabel("mode j")
        axis.set_ylabel("mode i")
        axis.set_title("MAC matrix — " + m.label)
        if rows <= 12 and cols <= 12:
            for i in range(rows):
                for j in range(cols):
                    axis.text(j, i, "%.2f" % m.mac[i, j], ha="center", va="center", fontsize=7,
                              color="black" if m.mac[i, j] > 0.6 else "white")
        figures.append(save(figure, out_dir, "modes_mac_%d" % (m.index + 1),
                            "MAC matrix of %s" % m.label,
                            "Modal assurance criterion MAC_ij = (φ_iᵀMψ_j)² / "
                            "((φ_iᵀMφ_i)(ψ_jᵀMψ_j)) as stored in /modes/mac: 1 = same shape, "
                            "0 = M-orthogonal."))
    return figures


def screen_figure(screen, column, out_dir):
    """Heat map of metric `column` over the first two parameters (a line for one parameter)."""
    name = screen.metric_names[column]
    unit, factor = display_unit(screen.metric_units[column])
    values = screen.metrics[:, column] * factor
    title = METRIC_TITLES.get(name, name)
    colour_label = "%s [%s]" % (title, unit)
    x_name = screen.parameter_names[0]
    x_label, x_factor = _axis_for(screen, 0)
    figure = Figure(figsize=(6.4, 4.8), layout="constrained")
    axis = figure.subplots()
    note = ""
    if len(screen.parameter_names) == 1:
        order = np.argsort(screen.parameters[:, 0], kind="stable")
        axis.plot(screen.parameters[order, 0] * x_factor, values[order], "o-")
        axis.set_xlabel(x_label)
        axis.set_ylabel(colour_label)
        axis.set_title("%s vs %s" % (title, x_name))
    else:
        y_name = screen.parameter_names[1]
        y_label, y_factor = _axis_for(screen, 1)
        xs, x_index = np.unique(screen.parameters[:, 0], return_inverse=True)
        ys, y_index = np.unique(screen.parameters[:, 1], return_inverse=True)
        filled = len(set(zip(x_index.tolist(), y_index.tolist())))
        if xs.size * ys.size <= 2 * filled:
            # A (nearly) full grid: one cell per (x, y); several points in a cell (other parameters
            # vary) show the largest value.
            grid = np.full((ys.size, xs.size), np.nan)
            for i, j, v in zip(y_index, x_index, values):
                grid[i, j] = v if np.isnan(grid[i, j]) else max(grid[i, j], v)
            if filled < screen.parameters.shape[0]:
                note = " (largest over the other parameters)"
            mesh = axis.pcolormesh(np.arange(xs.size + 1) - 0.5, np.arange(ys.size + 1) - 0.5,
                                   np.ma.masked_invalid(grid), cmap="viridis", shading="flat")
            figure.colorbar(mesh, ax=axis, label=colour_label)
            axis.set_xticks(range(xs.size), ["%g" % (v * x_factor) for v in xs])
            axis.set_yticks(range(ys.size), ["%g" % (v * y_factor) for v in ys])
            axis.grid(False)
            if xs.size * ys.size <= 100:
                finite = grid[np.isfinite(grid)]
                middle = 0.5 * (finite.min() + finite.max()) if finite.size else 0.0
                for i in range(ys.size):
                    for j in range(xs.size):
                        if np.isfinite(grid[i, j]):
                            axis.text(j, i, "%.4g" % grid[i, j], ha="center", va="center",
                                      fontsize=7, color="black" if grid[i, j] > middle else "white")
        else:  # scattered design (space-filling): coloured points
            points = axis.scatter(screen.parameters[:, 0] * x_factor,
                                  screen.parameters[:, 1] * y_factor, c=values, cmap="viridis",
                                  s=36, edgecolors="0.3", linewidths=0.4)
            figure.colorbar(points, ax=axis, label=colour_label)
        axis.set_xlabel(x_label)
        axis.set_ylabel(y_label)
        axis.set_title("%s\nover %s × %s%s" % (title, x_name, y_name, note))
    return save(figure, out_dir, "screen_%d_%s" % (screen.index + 1, safe_name(name)),
                "Screening: %s (%s)" % (title, screen.label),
                "%s over the first two screening parameters%s." % (colour_label, note))


def _axis_for(screen, column):
    key = screen.parameter_names[column]
    unit = screen.parameter_units[column]
    if unit == "m" and generic_key(key) in MILLIMETRE_KEYS:
        return "%s [mm]" % key, 1e3
    shown, factor = display_unit(unit)
    return ("%s [%s]" % (key, shown) if unit else key), factor


# --- mode shapes ----------------------------------------------------------------------------------

#: Edges of a quad (shell element, its four corner nodes) and of a hexahedron in VTK corner order
#: (rigid module), the lines a wireframe draws.
_QUAD_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0))
_HEX_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
              (0, 4), (1, 5), (2, 6), (3, 7))

#: The three orthogonal views of a mode shape, in the mast's own frame at the locked angle θ0:
#: a = along the mast axis, n = in the deployment plane across the axis, z = the joint axis.
_VIEWS = (("side (deployment plane)", 0, 1, "a [m]", "n [m]"),
          ("top (out of plane)", 0, 2, "a [m]", "z [m]"),
          ("end (along the axis)", 1, 2, "n [m]", "z [m]"))


def _mast_frame(points, angle_rad):
    """Global points → (a, n, z): rotated by −θ0 about Z so the mast axis is horizontal."""
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    a = c * points[:, 0] + s * points[:, 1]
    n = -s * points[:, 0] + c * points[:, 1]
    return np.stack([a, n, points[:, 2]], axis=1)


def _segments(points, cells, edges, i, j):
    """Line segments [(x0, y0), (x1, y1)] of every cell edge in view coordinates (i, j)."""
    if cells.size == 0:
        return np.zeros((0, 2, 2))
    starts = np.concatenate([cells[:, e0] for e0, _ in edges])
    ends = np.concatenate([cells[:, e1] for _, e1 in edges])
    return np.stack([points[starts][:, [i, j]], points[ends][:, [i, j]]], axis=1)


def mode_shape_figure(m, mode, out_dir):
    """Mode `mode` (0-based) of modes file `m` in three orthogonal projections: the undeformed mast
    in grey, the displaced one in colour (shell blue, modules red), displacement scaled as stored
    in /visualization (the figure's caption says by how much)."""
    from matplotlib.collections import LineCollection

    angle = m.angle_rad or 0.0
    figure = Figure(figsize=(10.0, 2.9), layout="constrained")
    axes = figure.subplots(1, 3, gridspec_kw={"width_ratios": (2.6, 2.6, 1.3)})
    parts = []
    for part, edges, colour in (("shell", _QUAD_EDGES, "C0"), ("modules", _HEX_EDGES, "C3")):
        points, cells, displacements, _ = m.views[part]
        parts.append((edges, colour, _mast_frame(points, angle),
                      _mast_frame(points + displacements[mode], angle), cells))
    everything = np.concatenate([p[2] for p in parts] + [p[3] for p in parts])
    for axis, (title, i, j, x_label, y_label) in zip(axes, _VIEWS):
        for edges, colour, undeformed, deformed, cells in parts:
            axis.add_collection(LineCollection(_segments(undeformed, cells, edges, i, j),
                                               colors="0.75", linewidths=0.6))
            axis.add_collection(LineCollection(_segments(deformed, cells, edges, i, j),
                                               colors=colour, linewidths=0.8))
        lo, hi = everything[:, [i, j]].min(axis=0), everything[:, [i, j]].max(axis=0)
        pad = 0.05 * float(max(hi - lo)) + 1e-12
        axis.set_xlim(lo[0] - pad, hi[0] + pad)
        axis.set_ylim(lo[1] - pad, hi[1] + pad)
        axis.set_aspect("equal", adjustable="box")
        axis.set_title(title)
        axis.set_xlabel(x_label)
        axis.set_ylabel(y_label)
    figure.suptitle("Mode %d — %s, %.6g Hz" % (mode + 1, m.labels[mode], m.frequency_hz[mode]))
    return save(figure, out_dir, "mode_shape_%d_%d" % (m.index + 1, mode + 1),
                "Mode %d of #%d %s" % (mode + 1, m.index + 1, m.label), "")


def effective_mass_figure(m, out_dir):
    """Bar chart of the effective-mass fractions of file `m`'s modes, and their running sum."""
    fractions = m.columns[3][1]
    count = fractions.size
    figure, (axis,) = _new_figure(size=(8.0, 3.6))
    modes = np.arange(1, count + 1)
    axis.bar(modes, fractions, color="C0", label="effective-mass fraction of the mode")
    axis.step(modes, np.cumsum(fractions), where="mid", color="C1",
              label="sum over modes 1 … j")
    axis.set_xlabel("mode number j")
    axis.set_ylabel("effective-mass fraction [–]")
    axis.set_ylim(0.0, max(1.0, float(np.sum(fractions))) * 1.05)
    axis.xaxis.get_major_locator().set_params(integer=True)
    axis.set_title("Effective mass of the rotation about the joint axis — #%d %s"
                   % (m.index + 1, m.label))
    _legend_below(axis, 2)
    return save(figure, out_dir, "modes_effective_mass_%d" % (m.index + 1),
                "Effective-mass fractions of #%d %s" % (m.index + 1, m.label),
                "Share of the mast's moment of inertia about the joint axis that each mode "
                "carries, Γ_j² / J (bars, /modes/effective_mass_fraction), and the running sum "
                "(line): a sum near 1 means the modes shown capture the response to the drive.")


def modal_comparison_figure(number, comparison, out_dir):
    """MAC matrix between two modal analyses (heat map) and the frequency ratio of the matched
    pairs (B over A, by mode of A)."""
    a, b, mac = comparison.a, comparison.b, comparison.mac
    rows, cols = mac.shape
    figure = Figure(figsize=(10.0, 4.6), layout="constrained")
    left, right = figure.subplots(1, 2, gridspec_kw={"width_ratios": (1.15, 1.0)})
    image = left.imshow(mac, vmin=0.0, vmax=1.0, cmap="viridis", origin="upper",
                        interpolation="nearest")
    figure.colorbar(image, ax=left, label="MAC [–]")
    left.set_xticks(range(cols), [str(j + 1) for j in range(cols)])
    left.set_yticks(range(rows), [str(i + 1) for i in range(rows)])
    left.grid(False)
    left.set_xlabel("mode j of B")
    left.set_ylabel("mode i of A")
    left.set_title("MAC between the two mode sets")
    figure.suptitle("A = #%d %s;  B = #%d %s" % (a.index + 1, a.label, b.index + 1, b.label))
    if rows <= 12 and cols <= 12:
        for i in range(rows):
            for j in range(cols):
                left.text(j, i, "%.2f" % mac[i, j], ha="center", va="center", fontsize=7,
                          color="black" if mac[i, j] > 0.6 else "white")
    modes = np.arange(1, rows + 1)
    ratios = np.array([p[3] for p in comparison.pairs])
    quality = np.array([p[2] for p in comparison.pairs])
    right.axhline(1.0, color="0.5", linewidth=0.8)
    points = right.scatter(modes, ratios, c=quality, vmin=0.0, vmax=1.0, cmap="viridis",
                           edgecolors="0.3", linewidths=0.5, s=40, zorder=3)
    figure.colorbar(points, ax=right, label="MAC of the pair [–]")
    for i, j, _, ratio in comparison.pairs:
        right.annotate("→%d" % (j + 1), (i + 1, ratio), textcoords="offset points", xytext=(4, 4),
                       fontsize=7)
    right.set_xlabel("mode i of A")
    right.set_ylabel("frequency ratio f_B,j / f_A,i [–]")
    right.set_title("Matched pairs (j = the mode of B with the largest MAC)")
    right.xaxis.get_major_locator().set_params(integer=True)
    return save(figure, out_dir, "modes_mac_between_%d" % number,
                "MAC between #%d and #%d" % (a.index + 1, b.index + 1),
                "Left: modal assurance criterion MAC_ij = (a_iᵀb_j)² / ((a_iᵀa_i)(b_jᵀb_j)) "
                "between mode i of A and mode j of B, over the displacements of the shell nodes "
                "and module corners in the mast's frame (1 = same shape, 0 = orthogonal). Right: "
                "for each mode of A, the frequency ratio to its best match in B (label → j, "
                "colour = the pair's MAC).")


# --- ROM databases --------------------------------------------------------------------------------

#: How many of the lowest drive-excited frequencies the database figures follow.
DRIVE_EXCITED_SHOWN = 3


def _excited_rows(frequency_hz, participation):
    """[rows, DRIVE_EXCITED_SHOWN] lowest drive-excited frequencies per row (NaN where fewer)."""
    from report_inputs import drive_excited

    out = np.full((frequency_hz.shape[0], DRIVE_EXCITED_SHOWN), np.nan)
    for r in range(frequency_hz.shape[0]):
        chosen = drive_excited(frequency_hz[r], participation[r], DRIVE_EXCITED_SHOWN)
        out[r, :len(chosen)] = frequency_hz[r, chosen]
    return out


def _database_axis(key, units):
    if key == "modes.angle_deg":
        return "locked joint angle θ0 [°]", 1.0
    if units == "m" and generic_key(key) in MILLIMETRE_KEYS:
        return "%s [mm]" % key, 1e3
    return ("%s [%s]" % (key, units) if units else key), 1.0


def database_figures(db, out_dir):
    """Lowest drive-excited frequencies of a ROM database over each parameter axis (interpolation
    as lines, samples as markers) and, for two or more axes, the lowest one as a map."""
    figures = []
    sample_hz = db.omega / (2.0 * math.pi)
    samples = _excited_rows(sample_hz, db.participation)
    reference = db.parameters[db.reference_sample]
    for a, (key, _, units) in enumerate(db.axes):
        label, factor = _database_axis(key, units)
        figure, (axis,) = _new_figure()
        others = [b for b in range(len(db.axes)) if b != a]
        on_line = np.all(np.isclose(db.parameters[:, others], reference[others], rtol=1e-12,
                                    atol=0.0), axis=1) if others else np.ones(len(samples), bool)
        drawn = 0
        for j in range(DRIVE_EXCITED_SHOWN):
            if not np.any(np.isfinite(samples[:, j])):
                continue  # the models have fewer drive-excited modes
            drawn += 1
            colour = "C%d" % j
            if db.curves is not None:
                values, hz, participation, _ = db.curves["axes"][a]
                curve = _excited_rows(hz, participation)[:, j]
                axis.plot(values * factor, curve, "-", color=colour,
                          label="mode %d: interpolated" % (j + 1))
            axis.plot(db.parameters[on_line, a] * factor, samples[on_line, j], "o", color=colour,
                      markersize=6, label="mode %d: samples on the line" % (j + 1))
            if not np.all(on_line):
                axis.plot(db.parameters[~on_line, a] * factor, samples[~on_line, j], ".",
                          color=colour, alpha=0.35, markersize=5,
                          label="mode %d: other samples" % (j + 1))
        axis.set_xlabel(label)
        axis.set_ylabel("frequency [Hz]")
        axis.ticklabel_format(axis="y", useOffset=False)
        held = ", ".join("%s = %g" % (db.axes[b][0], reference[b]) for b in others)
        axis.set_title("Lowest drive-excited frequencies vs %s%s"
                       % ("the locked angle θ0" if key == "modes.angle_deg" else key,
                          "\n(other parameters at the reference sample: %s)" % held if held
                          else ""))
        _legend_below(axis, (3 if not np.all(on_line) else 2) * drawn)
        figures.append(save(
            figure, out_dir, "database_%d_frequency_vs_%s" % (db.index + 1, safe_name(key)),
            "Frequency vs %s (#%d)" % (key, db.index + 1),
            "The %d lowest drive-excited frequencies (modes whose rotation participation is at "
            "least 1e-3 of the largest) against %s: lines = the database's own interpolation "
            "evaluated by mastrom at %s points, other parameters held at the reference sample; "
            "filled markers = the stored samples on that line (exact modal solves), faint dots = "
            "the other samples projected onto the axis." % (DRIVE_EXCITED_SHOWN, key,
                                                            "41" if db.curves else "no")))
    if len(db.axes) >= 2:
        (x_key, _, x_units), (y_key, _, y_units) = db.axes[0], db.axes[1]
        x_label, x_factor = _database_axis(x_key, x_units)
        y_label, y_factor = _database_axis(y_key, y_units)
        figure = Figure(figsize=(6.4, 4.8), layout="constrained")
        axis = figure.subplots()
        if db.curves is not None and db.curves["plane"] is not None:
            x, y, hz, participation = db.curves["plane"]
            lowest = _excited_rows(hz, participation)[:, 0].reshape(x.size, y.size)
            mesh = axis.pcolormesh(x * x_factor, y * y_factor, lowest.T, shading="gouraud",
                                   cmap="viridis")
            figure.colorbar(mesh, ax=axis, label="lowest drive-excited frequency [Hz]")
            contours = axis.contour(x * x_factor, y * y_factor, lowest.T, colors="white",
                                    linewidths=0.6)
            axis.clabel(contours, fontsize=7, fmt="%.4g")
        points = axis.scatter(db.parameters[:, 0] * x_factor, db.parameters[:, 1] * y_factor,
                              c=samples[:, 0], cmap="viridis", edgecolors="black", s=50,
                              marker="o", zorder=3, clip_on=False)
        axis.margins(0.04)
        if db.curves is None:
            figure.colorbar(points, ax=axis, label="lowest drive-excited frequency [Hz]")
        axis.set_xlabel(x_label)
        axis.set_ylabel(y_label)
        axis.grid(False)
        axis.set_title("Lowest drive-excited frequency over %s × %s" % (x_key, y_key))
        figures.append(save(
            figure, out_dir, "database_%d_frequency_map" % (db.index + 1),
            "Frequency map (#%d)" % (db.index + 1),
            "The lowest drive-excited frequency over the first two parameters: colour field and "
            "contours = the database's interpolation, circles = the stored samples (coloured by "
            "their own exact value, so a mismatch between a circle and the field around it is "
            "an interpolation error)."))
    return figures
