"""The optimisation part of `mastrom report`: the record `mastrom optimize` writes (source
"optimize", rom/studies/optimization.hpp, docs/theory.md §4.5). One figure per file — for the
objective and every constraint, the ROM's value with its margin and the full order's with its own
error estimate, round by round, against the bound each round used — and a table of the rounds.
"""

from matplotlib.figure import Figure
import numpy as np

from report_common import display_unit
from report_figures import save, safe_name
from report_inputs import InputFile, as_text
from report_page import escape, num_cell


class OptimizeRecord(InputFile):
    """The rounds of one optimisation: R rounds, p parameters, q metrics (objective first)."""

    kind = "optimize"

    def __init__(self, index, path, h5):
        super().__init__(index, path, h5)
        self.parameter_names = self._strings(h5, "/optimize/parameter_names", None)
        self.metric_names = self._strings(h5, "/optimize/metric_names", None)
        self.metric_units = self._strings(h5, "/optimize/metric_units", len(self.metric_names))
        p, q = len(self.parameter_names), len(self.metric_names)
        self.points, _ = self._numbers(h5, "/optimize/points", (None, p))
        r = self.points.shape[0]
        self.bounds, _ = self._numbers(h5, "/optimize/bounds", (r, q - 1))
        self.rom, _ = self._numbers(h5, "/optimize/rom", (r, q))
        self.margin, _ = self._numbers(h5, "/optimize/margin", (r, q))
        self.full, _ = self._numbers(h5, "/optimize/full_order", (r, q))
        self.full_error, _ = self._numbers(h5, "/optimize/full_order_error", (r, q))
        self.met, _ = self._numbers(h5, "/optimize/met", (r, q - 1))
        self.objective = as_text(h5.attrs.get("objective", ""))
        self.sense = as_text(h5.attrs.get("sense", ""))
        self.constraints = [c for c in as_text(h5.attrs.get("constraints", "")).split("; ") if c]
        self.confirmed = bool(h5.attrs.get("confirmed", 0))
        self.stop_reason = as_text(h5.attrs.get("stop_reason", ""))
        self.margin_factor = float(h5.attrs.get("margin_factor", 0.0))
        self.parameter_units = []
        units = h5["/optimize/parameter_names"].attrs.get("units")
        if units is not None:
            self.parameter_units = [as_text(u) for u in np.asarray(units).reshape(-1)]
        if len(self.parameter_units) != p:
            self.parameter_units = [""] * p

    def describe(self):
        return "%d round%s, %s" % (self.points.shape[0], "" if self.points.shape[0] == 1 else "s",
                                   "confirmed" if self.confirmed else "not confirmed")


def optimize_figure(record, out_dir):
    """ROM (with margin) and full order (with its estimated error) per round, one panel a metric."""
    q = len(record.metric_names)
    rounds = np.arange(1, record.points.shape[0] + 1)
    figure = Figure(figsize=(8.0, 2.0 * q + 0.6), layout="constrained")
    axes = figure.subplots(q, 1, sharex=True, squeeze=False)
    for m in range(q):
        axis = axes[m][0]
        unit, factor = display_unit(record.metric_units[m])
        full_error = np.where(record.full_error[:, m] >= 0, record.full_error[:, m], 0.0)
        axis.errorbar(rounds - 0.05, record.rom[:, m] * factor, yerr=record.margin[:, m] * factor,
                      fmt="o", capsize=4, label="ROM ± margin")
        axis.errorbar(rounds + 0.05, record.full[:, m] * factor, yerr=full_error * factor, fmt="s",
                      capsize=4, label="full order ± its estimate")
        if m > 0:
            axis.step(rounds, record.bounds[:, m - 1] * factor, where="mid", color="grey",
                      linestyle="--", label="bound used")
            axis.set_title(record.constraints[m - 1] if m - 1 < len(record.constraints)
                           else record.metric_names[m], fontsize=9)
        else:
            axis.set_title("objective: %s %s" % (record.sense, record.metric_names[0]), fontsize=9)
        axis.set_ylabel("[%s]" % unit)
        axis.legend(loc="best", fontsize=7)
    axes[-1][0].set_xlabel("round")
    axes[-1][0].set_xticks(rounds)
    return save(figure, out_dir, "optimize_rounds_" + safe_name(record.label),
                "Optimisation rounds (%s)" % record.label,
                "Per round: the ROM's value at its optimum with the margin the constraint was "
                "taken with (%g × the ROM's estimated error), and the full order's value there "
                "with its own error estimate (a second run at 8 × its tolerance); dashed: the "
                "bound that round used (tightened after a violation, docs/theory.md (4.16))."
                % record.margin_factor)


def rounds_table(record):
    """One row per round: the design, then per metric ROM and full order (and met)."""
    headers = ["round"]
    headers += ["%s [%s]" % (escape(n), escape(display_unit(u)[0]))
                for n, u in zip(record.parameter_names, record.parameter_units)]
    for m, name in enumerate(record.metric_names):
        unit = escape(display_unit(record.metric_units[m])[0])
        headers += ["%s ROM [%s]" % (escape(name), unit), "full order [%s]" % unit]
        if m > 0:
            headers.append("met")
    rows = ['<table class="screen"><tr>%s</tr>' % "".join("<th>%s</th>" % h for h in headers)]
    for r in range(record.points.shape[0]):
        cells = ["<td>%d</td>" % (r + 1)]
        for j, unit in enumerate(record.parameter_units):
            cells.append(num_cell(record.points[r, j], unit, record.index,
                                  "/optimize/points[%d,%d]" % (r, j)))
        for m, unit in enumerate(record.metric_units):
            cells.append(num_cell(record.rom[r, m], unit, record.index,
                                  "/optimize/rom[%d,%d]" % (r, m)))
            cells.append(num_cell(record.full[r, m], unit, record.index,
                                  "/optimize/full_order[%d,%d]" % (r, m)))
            if m > 0:
                cells.append("<td>%s</td>" % ("yes" if record.met[r, m - 1] else "NO"))
        rows.append("<tr>%s</tr>" % "".join(cells))
    rows.append("</table>")
    rows.append('<p class="note">%s: %s</p>' % ("Confirmed" if record.confirmed else
                                                "Not confirmed", escape(record.stop_reason)))
    return "\n".join(rows)


def summary_text(record):
    """One sentence: the objective, the constraints and the outcome."""
    return ("%s %s subject to %s; %d round%s, %s." % (
        record.sense, escape(record.objective),
        ", ".join(escape(c) for c in record.constraints) or "no constraint",
        record.points.shape[0], "" if record.points.shape[0] == 1 else "s",
        "confirmed by the full order" if record.confirmed else "NOT confirmed"))

