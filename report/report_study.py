"""The study part of `mastrom report` (`mastrom study NAME -o DIR` writes DIR/NAME/report/): the
comparison table `mastrom study` stores in study.h5 (rom/studies/study_run.hpp), the finding of the paper
that each of the repository's studies (configs/studies/*.toml) tests, and whether the runs
reproduce it — separately for the full order and the ROM.

A finding is a statement about how one metric orders the cases: e.g. for shell_thickness, "the
thinner the shell, the larger the peak relative end angular acceleration" holds when the metric
decreases strictly as interface.thickness increases. The check uses the numbers in the table and
nothing else.
"""

import math

import numpy as np

from report_common import display_unit, format_number, format_si
from report_inputs import InputFile, as_text, flatten_config
from report_page import escape, num_cell

#: Metric name suffix in study.h5 -> SI unit (rom/studies/study_run.cpp studyMetricNames).
_SUFFIX_UNITS = (("_rad_s2", "rad/s^2"), ("_nm", "N*m"), ("_n", "N"), ("_s", "s"))

_TITLES = {
    "peak_abs_end_angular_acceleration": "peak |absolute| end angular acceleration",
    "peak_rel_end_angular_acceleration": "peak |relative| end angular acceleration",
    "rms_rel_end_angular_acceleration": "RMS relative end angular acceleration",
    "residual_rel_end_angular_acceleration": "residual |relative| after the drive stops",
    "settling_time": "settling time",
    "peak_joint_force": "peak joint force ‖F‖",
    "peak_drive_torque": "peak |drive torque|",
}


def split_metric(name):
    """'peak_joint_force_n' -> ('peak_joint_force', 'N')."""
    for suffix, unit in _SUFFIX_UNITS:
        if name.endswith(suffix):
            return name[:-len(suffix)], unit
    return name, ""


class StudyTable(InputFile):
    """study.h5: one row per case of every study run together."""

    kind = "study"

    def __init__(self, index, path, h5):
        super().__init__(index, path, h5)
        self.study_names = self._strings(h5, "/study/study_names", None)
        n = len(self.study_names)
        self.case_names = self._strings(h5, "/study/case_names", n)
        self.metric_names = self._strings(h5, "/study/metric_names", None)
        m = len(self.metric_names)
        self.configs = [flatten_config(text) for text in self._strings(h5, "/study/configs", n)]
        self.full, _ = self._numbers(h5, "/study/full_metrics", (n, m))
        self.rom, _ = self._numbers(h5, "/study/rom_metrics", (n, m))
        self.nrmse, _ = self._numbers(h5, "/study/nrmse_relative_acceleration", (n,))
        self.first_hz, _ = self._numbers(h5, "/study/first_bending_frequency", (n,))

    def rows_of(self, study):
        return [i for i, s in enumerate(self.study_names) if s == study]

    def describe(self):
        return "%d cases of %s" % (len(self.case_names), ", ".join(sorted(set(self.study_names))))


class Finding:
    """A paper finding: `metric` ordered over the cases by `order(config, case_name)`; `trend` is
    "decreasing" / "increasing" (strictly, in the order) or "extremes" (the first case of the
    order has the largest value, the last the smallest)."""

    def __init__(self, text, metric, order_text, order, trend, source):
        self.text, self.metric, self.order_text = text, metric, order_text
        self.order, self.trend, self.source = order, trend, source

    def holds(self, values):
        """True / False for values listed in the finding's order; None when a value is missing."""
        values = np.asarray(values, dtype=float)
        if values.size < 2 or not np.all(np.isfinite(values)) or np.all(values == values[0]):
            return None  # nothing to order (e.g. no case settled within a short record)
        if self.trend == "increasing":
            return bool(np.all(np.diff(values) > 0))
        if self.trend == "decreasing":
            return bool(np.all(np.diff(values) < 0))
        return bool(values[0] == values.max() and values[-1] == values.min())


_LAW_ORDER = {"cubic": 0, "quintic": 1, "cycloidal": 2}

#: The findings of Liu & Wen (2024) that the repository's studies test (configs/studies/*.toml).
FINDINGS = {
    "schemes": [
        Finding("The more modules, the larger the peak joint force (Scheme 3 > 2 > 1).",
                "peak_joint_force", "mast.modules", lambda c, n: c.get("mast.modules"),
                "increasing", "paper §3.1, Fig 8"),
        Finding("The more modules, the larger the peak end angular acceleration.",
                "peak_abs_end_angular_acceleration", "mast.modules",
                lambda c, n: c.get("mast.modules"), "increasing", "paper §3.1, Fig 7"),
    ],
    "shell_thickness": [
        Finding("The thinner the shell, the larger the relative end vibration.",
                "peak_rel_end_angular_acceleration", "interface.thickness",
                lambda c, n: c.get("interface.thickness"), "decreasing", "paper §3.2, Figs 9, 14"),
        Finding("The thinner the shell, the slower the vibration decays (longer settling).",
                "settling_time", "interface.thickness",
                lambda c, n: c.get("interface.thickness"), "decreasing", "paper §3.2, Fig 14"),
    ],
    "inner_diameter": [
        Finding("The larger the inner diameter, the smaller the end vibration.",
                "peak_rel_end_angular_acceleration", "interface.inner_diameter",
                lambda c, n: c.get("interface.inner_diameter"), "decreasing",
                "paper §3.2, Figs 11, 12"),
    ],
    "drive_laws": [
        Finding("Of the cubic, quintic and cycloidal laws the cubic excites the largest end "
                "vibration and the cycloidal the smallest.",
                "peak_rel_end_angular_acceleration", "drive.law (cubic, quintic, cycloidal)",
                lambda c, n: _LAW_ORDER.get(c.get("drive.law")), "extremes",
                "paper §3.3, Figs 13, 14"),
    ],
}


def _metric_column(table, metric):
    for j, name in enumerate(table.metric_names):
        if split_metric(name)[0] == metric:
            return j
    return None


def _yes_no(value):
    return "undecided" if value is None else ("holds" if value else "does not hold")


def findings_table(table, study):
    """HTML: every finding of `study`, the metric per case in the finding's order (full order and
    ROM, numbers from study.h5) and whether it holds for each model."""
    findings = FINDINGS.get(study)
    if not findings:
        return ('<p class="note">No finding of the paper is recorded for the study "%s" (the '
                'studies with findings: %s); the tables below show its numbers.</p>'
                % (escape(study), ", ".join(sorted(FINDINGS))))
    rows = ['<table class="findings"><tr><th>finding</th><th>metric</th><th>cases, in the order '
            'of the finding</th><th>full order</th><th>ROM</th></tr>']
    for finding in findings:
        column = _metric_column(table, finding.metric)
        members = [(finding.order(table.configs[i], table.case_names[i]), i)
                   for i in table.rows_of(study)]
        members = sorted((key, i) for key, i in members if key is not None)
        if column is None or len(members) < 2:
            rows.append("<tr><td>%s</td><td colspan=\"4\">not testable with these cases</td></tr>"
                        % escape(finding.text))
            continue
        _, unit = split_metric(table.metric_names[column])
        cases = []
        for _, i in members:
            cases.append("%s: full %s, ROM %s" % (
                escape(table.case_names[i]),
                _num_span(table.full[i, column], unit, table.index,
                          "/study/full_metrics[%d,%d]" % (i, column)),
                _num_span(table.rom[i, column], unit, table.index,
                          "/study/rom_metrics[%d,%d]" % (i, column))))
        full = finding.holds([table.full[i, column] for _, i in members])
        rom = finding.holds([table.rom[i, column] for _, i in members])
        rows.append('<tr><td>%s <span class="note">(%s)</span></td><td>%s [%s], ordered by %s'
                    '</td><td>%s</td><td class="verdict" data-holds="%s">%s</td>'
                    '<td class="verdict" data-holds="%s">%s</td></tr>'
                    % (escape(finding.text), escape(finding.source),
                       escape(_TITLES.get(finding.metric, finding.metric)),
                       escape(display_unit(unit)[0]), escape(finding.order_text),
                       "<br>".join(cases), full, _yes_no(full), rom, _yes_no(rom)))
    rows.append("</table>")
    return "\n".join(rows)


def _num_span(value, si_unit, file_index, key):
    unit, factor = display_unit(si_unit)
    return ('<span class="num" data-file="%d" data-key="%s" data-si="%s" data-unit="%s" '
            'title="%s %s, as stored">%s</span>'
            % (file_index, escape(key), format_si(value), escape(unit), format_si(value),
               escape(si_unit), format_number(value * factor)))


def metrics_table(table, study):
    """Every metric of every case of `study`, full order and ROM rows, plus the NRMSE of the
    relative end angular acceleration and the ROM's first drive-excited frequency."""
    headers = ["case", "model"]
    for name in table.metric_names:
        metric, unit = split_metric(name)
        headers.append("%s [%s]" % (escape(_TITLES.get(metric, metric)),
                                    escape(display_unit(unit)[0])))
    headers += ["NRMSE of the relative end angular acceleration [–]",
                "first drive-excited frequency (ROM) [Hz]"]
    rows = ['<table class="study"><tr>%s</tr>' % "".join("<th>%s</th>" % h for h in headers)]
    for i in table.rows_of(study):
        for model, data, dataset in (("full order", table.full, "full_metrics"),
                                     ("ROM", table.rom, "rom_metrics")):
            cells = ["<td>%s</td>" % escape(table.case_names[i]), "<td>%s</td>" % model]
            for j, name in enumerate(table.metric_names):
                value = data[i, j]
                cells.append(num_cell(value, split_metric(name)[1], table.index,
                                      "/study/%s[%d,%d]" % (dataset, i, j))
                             if math.isfinite(value) else "<td>–</td>")
            if model == "full order":
                for value, key, unit in ((table.nrmse[i], "nrmse_relative_acceleration", "1"),
                                         (table.first_hz[i], "first_bending_frequency", "Hz")):
                    cells.append(num_cell(value, unit, table.index, "/study/%s[%d]" % (key, i))
                                 if math.isfinite(value) else "<td>–</td>")
            else:
                cells.append('<td colspan="2"></td>')
            rows.append("<tr>%s</tr>" % "".join(cells))
    rows.append("</table>")
    return "\n".join(rows)


__all__ = ["StudyTable", "FINDINGS", "findings_table", "metrics_table", "as_text"]
