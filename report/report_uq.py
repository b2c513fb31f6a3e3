"""The uncertainty page of `mastrom report` for a `mastrom uq` file (root attribute source "uq";
layout in rom/studies/uncertainty_output.hpp, docs/theory.md §7): a histogram per metric with the
limits marked, the exceedance curve of every limited metric (plain and with each sample's ROM error
bound taken against the limit, the conservative value), the first-order and total Sobol indices
with their bootstrap intervals, and the full-order runs at the tails beside the ROM.

Every number comes from the file: the report draws the samples and the stored summaries, it
recomputes no estimate. Values the file marks as missing (−1) are left out.
"""

import numpy as np
from matplotlib.figure import Figure

from report_common import METRIC_TITLES, display_unit
from report_figures import save
from report_inputs import InputFile, as_text
from report_page import _unit_header, escape, num_cell

#: Metrics that are flags or constants of the configuration: no distribution to draw.
_NOT_DRAWN = ("settled", "drive_end_time", "settling_band")
_UPWARD = (">", ">=")


def _columns(count):
    return min(3, max(1, count))


def _grid(count, height_per_row=2.4):
    """A figure with `count` axes in rows of up to three; the spare axes hidden."""
    columns = _columns(count)
    rows = (count + columns - 1) // columns
    figure = Figure(figsize=(3.3 * columns, height_per_row * rows), layout="constrained")
    axes = np.atleast_1d(figure.subplots(rows, columns, squeeze=False).ravel())
    for axis in axes[count:]:
        axis.set_visible(False)
    return figure, axes


class UqFile(InputFile):
    """A `mastrom uq` result: samples, metrics, summaries, limits, Sobol indices, tails."""

    kind = "uq"

    def __init__(self, index, path, h5):
        super().__init__(index, path, h5)
        self.input_names = self._strings(h5, "/uq/input_names", None)
        k = len(self.input_names)
        self.metric_names = self._strings(h5, "/uq/metric_names", None)
        q = len(self.metric_names)
        self.inputs, _ = self._numbers(h5, "/uq/inputs", (None, k))
        rows = self.inputs.shape[0]
        self.metrics, _ = self._numbers(h5, "/uq/metrics", (rows, q))
        self.metric_units = [as_text(u) for u in np.asarray(
            h5["/uq/metrics"].attrs.get("units", [""] * q)).reshape(-1)]
        if len(self.metric_units) != q:
            self._fail("/uq/metrics has %d units for %d metrics" % (len(self.metric_units), q))
        self.metric_error, _ = self._numbers(h5, "/uq/metric_error", (rows, q))
        statistic_rows, _ = self._numbers(h5, "/uq/statistic_rows", (None,))
        self.statistic_rows = statistic_rows.astype(int)
        if self.statistic_rows.size and (self.statistic_rows.min() < 0
                                         or self.statistic_rows.max() >= rows):
            self._fail("/uq/statistic_rows names rows outside the %d samples" % rows)
        self.summary = {}
        for name in ("mean", "std"):
            for suffix in ("", "_lower", "_upper"):
                self.summary[name + suffix], _ = self._numbers(
                    h5, "/uq/summary/%s%s" % (name, suffix), (q,))
        self.quantile_levels, _ = self._numbers(h5, "/uq/summary/quantile_levels", (None,))
        levels = self.quantile_levels.size
        for suffix in ("", "_lower", "_upper"):
            self.summary["quantiles" + suffix], _ = self._numbers(
                h5, "/uq/summary/quantiles" + suffix, (q, levels))
        self.limits = []
        if "/uq/limits" in h5:
            texts = self._strings(h5, "/uq/limits/text", None)
            n = len(texts)
            values = {}
            for name in ("probability", "conservative"):
                for suffix in ("", "_lower", "_upper"):
                    values[name + suffix], _ = self._numbers(
                        h5, "/uq/limits/%s%s" % (name, suffix), (n,))
            for i, text in enumerate(texts):
                parts = text.split()
                if len(parts) != 3 or parts[0] not in self.metric_names or parts[1] not in (
                        "<", "<=", ">", ">="):
                    self._fail("/uq/limits/text[%d] = '%s' is not METRIC OP VALUE" % (i, text))
                try:
                    value = float(parts[2])
                except ValueError:
                    self._fail("/uq/limits/text[%d] = '%s' is not METRIC OP VALUE" % (i, text))
                self.limits.append({"text": text, "metric": parts[0], "op": parts[1],
                                    "value": value, "index": i,
                                    **{key: v[i] for key, v in values.items()}})
        self.sobol = None
        if "/uq/sobol" in h5:
            self.sobol = {}
            for name in ("first", "total"):
                for suffix in ("", "_lower", "_upper"):
                    self.sobol[name + suffix], _ = self._numbers(
                        h5, "/uq/sobol/%s%s" % (name, suffix), (q, k))
            self.sobol["variance"], _ = self._numbers(h5, "/uq/sobol/variance", (q,))
        self.tails = None
        if "/uq/tails" in h5:
            labels = self._strings(h5, "/uq/tails/label", None)
            t = len(labels)
            self.tails = {"label": labels}
            for name in ("limit", "row", "rom_value", "rom_error_bound", "full_value",
                         "full_error_estimate"):
                self.tails[name], _ = self._numbers(h5, "/uq/tails/" + name, (t,))

    def describe(self):
        return "%d ROM evaluations of %d inputs × %d metrics" % (
            self.inputs.shape[0], len(self.input_names), len(self.metric_names))

    def drawn_metrics(self):
        """Columns with a distribution to draw: finite samples that are not all equal."""
        columns = []
        for j, name in enumerate(self.metric_names):
            if name in _NOT_DRAWN:
                continue
            v = self.metrics[self.statistic_rows, j]
            v = v[np.isfinite(v)]
            if v.size >= 2 and np.ptp(v) > 0.0:
                columns.append(j)
        return columns

    def title(self, j):
        name = self.metric_names[j]
        return METRIC_TITLES.get(name, name)


def histogram_figure(uq, out_dir):
    """A histogram of every drawn metric over the statistics' samples; limits in red, the mean
    dashed."""
    columns = uq.drawn_metrics()
    figure, axes = _grid(max(1, len(columns)))
    for axis, j in zip(axes, columns):
        unit, factor = display_unit(uq.metric_units[j])
        v = uq.metrics[uq.statistic_rows, j]
        v = v[np.isfinite(v)] * factor
        axis.hist(v, bins=min(50, max(10, int(np.sqrt(v.size)))), color="tab:blue", alpha=0.75)
        axis.axvline(uq.summary["mean"][j] * factor, color="black", linestyle="--",
                     linewidth=0.8)
        for limit in uq.limits:
            if limit["metric"] == uq.metric_names[j]:
                axis.axvline(limit["value"] * factor, color="tab:red", linewidth=1.2)
        axis.set_xlabel("%s [%s]" % (uq.title(j), unit), fontsize=7)
        axis.tick_params(labelsize=6)
    caption = ("Distribution of every metric over the %d samples of the inputs' laws (%s); "
               "black dashed: the mean; red: the limits given with --limit."
               % (uq.statistic_rows.size, ", ".join(uq.input_names)))
    return save(figure, out_dir, "uq_%d_histograms" % (uq.index + 1),
                "Metric distributions (%s)" % uq.label, caption)


def exceedance_figure(uq, out_dir):
    """For every limit: the probability of the event as a function of the threshold, plain and
    conservative, with the stored probability and its interval at the limit."""
    figure, axes = _grid(len(uq.limits), 2.8)
    for axis, limit in zip(axes, uq.limits):
        j = uq.metric_names.index(limit["metric"])
        unit, factor = display_unit(uq.metric_units[j])
        rows = uq.statistic_rows
        v = uq.metrics[rows, j]
        bound = uq.metric_error[rows, j]
        keep = np.isfinite(v)
        v, bound = v[keep], bound[keep]
        upward = limit["op"] in _UPWARD
        shifted = v + bound if upward else v - bound
        n = v.size
        for values, style, label in ((v, "-", "ROM"), (shifted, "--", "ROM ± its error bound")):
            x = np.sort(values) * factor
            # P(X > x) just below each sorted value (upward), P(X < x) just above (downward).
            p = 1.0 - np.arange(n) / n if upward else np.arange(1, n + 1) / n
            axis.step(x, p, style, where="post" if not upward else "pre", linewidth=1.0,
                      label=label)
        axis.axvline(limit["value"] * factor, color="tab:red", linewidth=1.0)
        axis.errorbar([limit["value"] * factor], [limit["probability"]],
                      yerr=[[limit["probability"] - limit["probability_lower"]],
                            [limit["probability_upper"] - limit["probability"]]],
                      fmt="o", color="tab:red", markersize=3, capsize=3)
        axis.set_yscale("log")
        axis.set_ylim(max(0.5 / n, 1e-6), 1.05)
        axis.set_xlabel("%s [%s]" % (uq.title(j), unit), fontsize=7)
        axis.set_ylabel("P(%s %s x)" % (limit["metric"][:18], limit["op"]), fontsize=7)
        axis.set_title(limit["text"], fontsize=7)
        axis.tick_params(labelsize=6)
        axis.legend(fontsize=6, loc="best")
    caption = ("Exceedance: the share of the samples in the event as a function of the threshold "
               "x, for each limit; dashed with every sample's ROM error bound taken against the "
               "limit (the conservative probability). Red: the limit and the stored probability "
               "with its interval.")
    return save(figure, out_dir, "uq_%d_exceedance" % (uq.index + 1),
                "Exceedance curves (%s)" % uq.label, caption)


def sobol_metrics(uq):
    """Metrics whose indices exist (variance > 0 and not marked −1)."""
    if uq.sobol is None:
        return []
    return [j for j in range(len(uq.metric_names))
            if uq.sobol["variance"][j] > 0.0 and np.all(uq.sobol["first_lower"][j] != -1.0)
            and uq.metric_names[j] not in _NOT_DRAWN]


def sobol_figure(uq, out_dir):
    """Grouped bars per input: first-order S and total ST, bootstrap intervals as error bars."""
    columns = sobol_metrics(uq)
    figure, axes = _grid(len(columns), 2.6)
    k = len(uq.input_names)
    x = np.arange(k)
    for axis, j in zip(axes, columns):
        for offset, name, color, label in ((-0.18, "first", "tab:blue", "S (first order)"),
                                           (0.18, "total", "tab:orange", "ST (total)")):
            value = uq.sobol[name][j]
            error = [np.maximum(0.0, value - uq.sobol[name + "_lower"][j]),
                     np.maximum(0.0, uq.sobol[name + "_upper"][j] - value)]
            axis.bar(x + offset, value, 0.36, yerr=error, capsize=3, color=color, label=label)
        axis.set_xticks(x)
        axis.set_xticklabels([n.split(".")[-1] for n in uq.input_names], fontsize=6)
        axis.set_ylim(min(-0.05, axis.get_ylim()[0]), max(1.05, axis.get_ylim()[1]))
        axis.axhline(0.0, color="black", linewidth=0.5)
        axis.set_title(uq.title(j), fontsize=7)
        axis.tick_params(labelsize=6)
    if columns:
        axes[0].legend(fontsize=6, loc="best")
    caption = ("Sobol indices of every metric for each uncertain input (%s): first order S (the "
               "share of the variance the input explains alone) and total ST (with all its "
               "interactions), Jansen's estimators, error bars the bootstrap intervals."
               % ", ".join(uq.input_names))
    return save(figure, out_dir, "uq_%d_sobol" % (uq.index + 1),
                "Sobol indices (%s)" % uq.label, caption)


def summary_table(uq):
    """Mean, standard deviation and quantiles of every metric, each with its interval."""
    levels = ["q%02d" % round(100 * level) for level in uq.quantile_levels]
    headers = ["metric", "mean", "[lower", "upper]", "std"] + levels
    rows = ['<table class="uq-summary"><tr>%s</tr>' % "".join("<th>%s</th>" % h for h in headers)]
    for j, name in enumerate(uq.metric_names):
        if uq.summary["mean_lower"][j] == -1.0 and uq.summary["mean"][j] == -1.0:
            continue
        unit = uq.metric_units[j]
        cells = ["<td>%s</td>" % _unit_header(uq.title(j), unit)]
        cells += [num_cell(uq.summary[key][j], unit, uq.index, "/uq/summary/%s[%d]" % (key, j))
                  for key in ("mean", "mean_lower", "mean_upper", "std")]
        cells += [num_cell(uq.summary["quantiles"][j, i], unit, uq.index,
                           "/uq/summary/quantiles[%d,%d]" % (j, i)) for i in range(len(levels))]
        rows.append("<tr>%s</tr>" % "".join(cells))
    rows.append("</table>")
    return "\n".join(rows)


def limits_table(uq):
    """Each limit's probability and conservative probability with their intervals."""
    rows = ['<table class="uq-limits"><tr><th>limit</th><th>P</th><th>[lower</th><th>upper]</th>'
            '<th>conservative</th><th>[lower</th><th>upper]</th></tr>']
    for limit in uq.limits:
        i = limit["index"]
        cells = ["<td><code>%s</code></td>" % escape(limit["text"])]
        for name in ("probability", "conservative"):
            cells += [num_cell(limit[name + suffix], "1", uq.index,
                               "/uq/limits/%s%s[%d]" % (name, suffix, i))
                      for suffix in ("", "_lower", "_upper")]
        rows.append("<tr>%s</tr>" % "".join(cells))
    rows.append("</table>")
    return "\n".join(rows)


def tail_table(uq):
    """The full order at the tails: ROM ± its bound beside full order ± its own estimate, and
    whether the two intervals meet."""
    t = uq.tails
    headers = ["limit", "sample at", "row", "ROM", "± bound", "full order", "± estimate",
               "ROM − full", "consistent"]
    rows = ['<table class="uq-tails"><tr>%s</tr>' % "".join("<th>%s</th>" % h for h in headers)]
    for i, label in enumerate(t["label"]):
        limit = uq.limits[int(t["limit"][i])]
        unit = uq.metric_units[uq.metric_names.index(limit["metric"])]
        full, estimate = t["full_value"][i], t["full_error_estimate"][i]
        rom, bound = t["rom_value"][i], t["rom_error_bound"][i]
        cells = ["<td><code>%s</code></td><td>%s</td><td>%d</td>"
                 % (escape(limit["text"]), escape(label), int(t["row"][i]))]
        cells += [num_cell(rom, unit, uq.index, "/uq/tails/rom_value[%d]" % i),
                  num_cell(bound, unit, uq.index, "/uq/tails/rom_error_bound[%d]" % i),
                  num_cell(full, unit, uq.index, "/uq/tails/full_value[%d]" % i),
                  num_cell(estimate, unit, uq.index, "/uq/tails/full_error_estimate[%d]" % i)]
        if full == -1.0:  # no full-order value for this metric (the file's −1)
            cells.append("<td>–</td><td>–</td>")
        else:
            difference = rom - full
            margin = bound + max(estimate, 0.0)
            cells.append(num_cell(difference, unit, derived=True))
            cells.append("<td>%s</td>" % ("yes" if abs(difference) <= margin else
                                          "<b>no</b> (|ROM − full| > bound + estimate)"))
        rows.append("<tr>%s</tr>" % "".join(cells))
    rows.append("</table>")
    return "\n".join(rows)


def uq_section(uq, page, out_dir):
    """Figures and tables of one uq file onto the page; returns the number of figures."""
    figures = 0
    page.paragraph("%d ROM evaluations; the statistics use %d samples of the inputs' laws "
                   "(%s). Intervals at the file's confidence level."
                   % (uq.inputs.shape[0], uq.statistic_rows.size,
                      ", ".join(uq.input_names)), "note")
    page.figure(histogram_figure(uq, out_dir))
    figures += 1
    page.add(summary_table(uq))
    if uq.limits:
        page.figure(exceedance_figure(uq, out_dir))
        figures += 1
        page.add(limits_table(uq))
    else:
        page.paragraph("No limits in this study (mastrom uq --limit): no exceedance curves.",
                       "note")
    if sobol_metrics(uq):
        page.figure(sobol_figure(uq, out_dir))
        figures += 1
    else:
        page.paragraph("No Sobol indices in this file (--no-sensitivity, or no metric varies).",
                       "note")
    if uq.tails is not None and len(uq.tails["label"]):
        page.paragraph("The nonlinear full order at the samples nearest each limited metric's 1 % "
                       "and 99 % quantiles and at the most critical sample (docs/theory.md §7.5). "
                       "Consistent: |ROM − full| within the ROM's bound plus the full order's own "
                       "error estimate.", "note")
        page.add(tail_table(uq))
    else:
        page.paragraph("No full-order tail runs in this file (no limit, or --no-tail-runs).",
                       "note")
    return figures
