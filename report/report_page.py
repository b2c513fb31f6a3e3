"""index.html of `mastrom report`: one self-contained page (CSS inline, PNG figures embedded as
base64 data URIs, the SVG and PNG files linked alongside) with the inputs, the figures and the tables.

Every number cell of a table is a <td class="num"> whose text is the value in the displayed unit
with SIGNIFICANT_DIGITS significant digits, and whose attributes say where it comes from, so a test (or a
person) can check it against the file:
    data-file  position of the input file on the command line (0-based; the inputs table lists them)
    data-key   the HDF5 location: "/metrics@name" (attribute of a group), "/@name" (root attribute),
               "/modes/frequency_hz[3]", "/screen/metrics[4,1]" (dataset element, 0-based)
    data-si    the value as stored (SI), shortest round-trip text
    data-unit  the displayed unit ("°/s²" = rad/s² × 180/π)
Cells computed by the report (ROM vs full errors) carry class "derived" and no data-key.
The page holds no time stamp: the same inputs give the same bytes.
"""

import base64
import math
import html
import os

from report_common import (METRIC_TITLES, SIGNIFICANT_DIGITS, display_unit, format_number,
                           format_si, metric_order, metric_unit)

_STYLE = """
body { font-family: sans-serif; margin: 1.5em auto; max-width: 72em; padding: 0 1em; color: #222; }
h1, h2, h3 { font-weight: 600; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; vertical-align: top; }
th { background: #f2f2f2; text-align: left; font-weight: 600; }
td.num, td.flag { text-align: right; font-variant-numeric: tabular-nums; }
figure { margin: 1.2em 0; } figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { font-size: 0.9em; color: #444; max-width: 60em; }
pre { background: #f7f7f7; padding: 0.6em; overflow-x: auto; font-size: 0.85em; }
details { margin: 0.4em 0; } summary { cursor: pointer; }
code { font-size: 0.9em; } .note { color: #555; font-size: 0.9em; }
.warning { background: #fff3cd; border: 1px solid #e0b000; padding: 0.5em 0.8em; }
""".strip()


def escape(text):
    """HTML-escaped text (quotes too)."""
    return html.escape(str(text), quote=True)


def num_cell(value, si_unit, file_index=None, key=None, derived=False):
    """A <td> for one number stored in `si_unit`, shown in its display unit (report_common)."""
    unit, factor = display_unit(si_unit)
    if derived:
        classes, where, origin = "num derived", "", "computed by the report"
    else:
        classes, origin = "num", "as stored"
        where = ' data-file="%d" data-key="%s"' % (file_index, escape(key))
    return ('<td class="%s"%s data-si="%s" data-unit="%s" title="%s %s, %s">%s</td>'
            % (classes, where, format_si(value), escape(unit), format_si(value),
               escape(si_unit if si_unit not in ("", "1") else "(dimensionless)"), origin,
               format_number(value * factor)))


def num_span(value, si_unit, file_index, key):
    """A number inside running text (a figure caption): the same attributes as num_cell."""
    unit, factor = display_unit(si_unit)
    return ('<span class="num" data-file="%d" data-key="%s" data-si="%s" data-unit="%s" '
            'title="%s %s, as stored">%s</span>'
            % (file_index, escape(key), format_si(value), escape(unit), format_si(value),
               escape(si_unit if si_unit not in ("", "1") else "(dimensionless)"),
               format_number(value * factor)))


def flag_cell(value, file_index, key):
    return ('<td class="flag" data-file="%d" data-key="%s" data-si="%s">%s</td>'
            % (file_index, escape(key), format_si(value), "yes" if value else "no"))


def _unit_header(title, si_unit):
    unit = display_unit(si_unit)[0]
    return "%s [%s]" % (escape(title), escape(unit))


class Page:
    """Accumulates sections, then writes index.html atomically."""

    def __init__(self, out_dir):
        self.out_dir = out_dir
        self.parts = []

    def add(self, text):
        self.parts.append(text)

    def heading(self, level, text, anchor=None):
        anchor_text = ' id="%s"' % escape(anchor) if anchor else ""
        self.add("<h%d%s>%s</h%d>" % (level, anchor_text, escape(text), level))

    def paragraph(self, text, css_class=None):
        self.add('<p%s>%s</p>' % (' class="%s"' % css_class if css_class else "", text))

    def figure(self, entry):
        with open(os.path.join(self.out_dir, entry.png), "rb") as stream:
            data = base64.b64encode(stream.read()).decode("ascii")
        caption = getattr(entry, "caption_html", None) or escape(entry.caption)
        self.add('<figure id="%s"><img alt="%s" src="data:image/png;base64,%s">'
                 '<figcaption><b>%s.</b> %s <a href="%s">SVG</a> · <a href="%s">PNG</a>'
                 '</figcaption></figure>'
                 % (escape(entry.name), escape(entry.title), data, escape(entry.title),
                    caption, escape(entry.svg), escape(entry.png)))

    def write(self, title, generator_version):
        version = (" (mastrom %s)" % escape(generator_version)) if generator_version else ""
        body = "\n".join(self.parts)
        text = ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                "<meta name=\"generator\" content=\"mastrom report%s\">\n<title>%s</title>\n"
                "<style>\n%s\n</style>\n</head>\n<body>\n%s\n</body>\n</html>\n"
                % (version, escape(title), _STYLE, body))
        path = os.path.join(self.out_dir, "index.html")
        temporary = path + ".tmp"
        with open(temporary, "w", encoding="utf-8") as stream:
            stream.write(text)
        os.replace(temporary, path)
        return path


PRECISION_NOTE = (
    "Numbers in the tables: %d significant digits of the value in the unit the header shows; "
    "angles are converted from the files' radians to degrees (rad/s² × 180/π = °/s²), everything "
    "else is SI as stored. Hover a number to see the exact SI value in the file." % SIGNIFICANT_DIGITS)


def inputs_table(inputs):
    rows = ["<table class=\"inputs\"><tr><th>#</th><th>label</th><th>file</th><th>source</th>"
            "<th>written by mastrom</th><th>contents</th><th>wall time [s]</th></tr>"]
    for f in inputs:
        wall = (num_cell(f.wall_time_s, "s", f.index, "/@wall_time_s")
                if f.wall_time_s is not None else "<td>–</td>")
        rows.append("<tr><td>%d</td><td>%s</td><td><code>%s</code></td><td>%s</td><td>%s</td>"
                    "<td>%s</td>%s</tr>"
                    % (f.index + 1, escape(f.label), escape(f.path), escape(f.source),
                       escape(f.version or "–"), escape(f.describe()), wall))
    rows.append("</table>")
    return "\n".join(rows)


def config_blocks(inputs):
    blocks = []
    for f in inputs:
        text = f.config_text if f.config_text else "(no root attribute 'config')"
        blocks.append("<details><summary>Resolved configuration of #%d %s (<code>%s</code>)"
                      "</summary><pre>%s</pre></details>"
                      % (f.index + 1, escape(f.label), escape(f.path), escape(text)))
    return "\n".join(blocks)


def metrics_table(deployments):
    """Rows = metrics (name and unit in the row header), columns = deployment files."""
    names = []
    for d in deployments:
        names += [n for n in d.metrics if n not in names]
    rows = ["<table class=\"metrics\"><tr><th>metric [unit]</th>%s</tr>"
            % "".join("<th>#%d %s</th>" % (d.index + 1, escape(d.label)) for d in deployments)]
    for name in metric_order(names):
        unit = metric_unit(name)
        is_flag = unit == "flag"
        header = (escape(METRIC_TITLES.get(name, name)) if is_flag
                  else _unit_header(METRIC_TITLES.get(name, name), unit))
        cells = []
        for d in deployments:
            key = "/metrics@" + name
            if name not in d.metrics:
                cells.append("<td>–</td>")
            elif is_flag:
                cells.append(flag_cell(d.metrics[name], d.index, key))
            else:
                cells.append(num_cell(d.metrics[name], unit, d.index, key))
        rows.append("<tr><th>%s<br><code>%s</code></th>%s</tr>"
                    % (header, escape(name), "".join(cells)))
    notes = []
    for d in deployments:
        notes += [n for n in getattr(d, "metric_notes", {}) if n not in notes]
    for name in sorted(notes):  # how the metrics were evaluated (text attributes)
        cells = ["<td>%s</td>" % escape(d.metric_notes[name]) if name in d.metric_notes
                 else "<td>–</td>" for d in deployments]
        rows.append("<tr><th><code>%s</code></th>%s</tr>" % (escape(name), "".join(cells)))
    rows.append("</table>")
    return "\n".join(rows)


def comparison_table(comparison):
    rows = ["<table class=\"comparison\"><tr><th>quantity</th><th>NRMSE [%]</th>"
            "<th>max |ROM − full|</th><th>unit</th></tr>"]
    for name, unit, nrmse, max_error in comparison.rows:
        rows.append("<tr><th>%s</th>%s%s<td>%s</td></tr>"
                    % (escape(name), num_cell(100.0 * nrmse, "%", derived=True),
                       num_cell(max_error, unit, derived=True), escape(display_unit(unit)[0])))
    rows.append("</table>")
    return "\n".join(rows)


def modes_table(m):
    headers = ["mode", "label"]
    titles = {"frequency_hz": "frequency", "damping_ratio": "damping ratio ζ",
              "participation": "participation Γ (rotation about Z)",
              "effective_mass_fraction": "effective mass fraction"}
    headers += [_unit_header(titles.get(name, name), units) for name, _, units in m.columns]
    headers += [_unit_header("end rotation " + axis, m.end_rotation_units) for axis in "xyz"]
    rows = ["<table class=\"modes\"><tr>%s</tr>" % "".join("<th>%s</th>" % h for h in headers)]
    for i in range(m.frequency_hz.size):
        cells = ["<td>%d</td>" % (i + 1), "<td>%s</td>" % escape(m.labels[i])]
        for name, values, units in m.columns:
            cells.append(num_cell(values[i], units, m.index, "/modes/%s[%d]" % (name, i)))
        for axis in range(3):
            cells.append(num_cell(m.end_rotation[i, axis], m.end_rotation_units, m.index,
                                  "/modes/end_rotation[%d,%d]" % (i, axis)))
        rows.append("<tr>%s</tr>" % "".join(cells))
    rows.append("</table>")
    return "\n".join(rows)


def screen_table(s, limit):
    headers = ["point"]
    headers += [_unit_header(n, u) for n, u in zip(s.parameter_names, s.parameter_units)]
    headers += [_unit_header(METRIC_TITLES.get(n, n), u)
                for n, u in zip(s.metric_names, s.metric_units)]
    rows = ["<table class=\"screen\"><tr>%s</tr>" % "".join("<th>%s</th>" % h for h in headers)]
    count = s.parameters.shape[0]
    for i in range(min(count, limit)):
        cells = ["<td>%d</td>" % (i + 1)]
        for j, unit in enumerate(s.parameter_units):
            cells.append(num_cell(s.parameters[i, j], unit, s.index,
                                  "/screen/parameters[%d,%d]" % (i, j)))
        for j, unit in enumerate(s.metric_units):
            cells.append(num_cell(s.metrics[i, j], unit, s.index,
                                  "/screen/metrics[%d,%d]" % (i, j)))
        rows.append("<tr>%s</tr>" % "".join(cells))
    rows.append("</table>")
    if count > limit:
        rows.append('<p class="note">First %d of %d points; the file holds them all.</p>'
                    % (limit, count))
    return "\n".join(rows)


def generic_listing(f):
    rows = ["<table class=\"contents\"><tr><th>dataset</th><th>shape</th><th>units</th></tr>"]
    for name, shape, units in f.datasets:
        rows.append("<tr><td><code>%s</code></td><td>%s</td><td>%s</td></tr>"
                    % (escape(name), escape(" × ".join(str(s) for s in shape) or "scalar"),
                       escape(units)))
    rows.append("</table>")
    if f.attributes:
        rows.append("<table class=\"attributes\"><tr><th>object</th><th>attribute</th>"
                    "<th>value</th></tr>")
        for obj, name, text in f.attributes:
            rows.append("<tr><td><code>%s</code></td><td>%s</td><td>%s</td></tr>"
                        % (escape(obj), escape(name), escape(text)))
        rows.append("</table>")
    return "\n".join(rows)


def mode_caption(m, mode):
    """Caption of a mode-shape figure: what the mode is (label, frequency, damping, participation,
    effective mass, each a number the page can be checked against) and how it is drawn."""
    i = m.index
    values = {name: (values, units) for name, values, units in m.columns}

    def number(name):
        data, units = values[name]
        return num_span(data[mode], units, i, "/modes/%s[%d]" % (name, mode))

    _, _, _, scales = m.views["shell"]
    scale_key = "/visualization/shell/mode_%03d@scale" % (mode + 1)
    amplitude = m.views["relative_amplitude"]
    angle = ("joint locked at θ0 = %s" % num_span(m.angle_rad, "rad", i, "/modes/angle_rad[0]")
             if m.angle_rad is not None else "at the linearisation point")
    return ("<b>%s</b>: f = %s Hz, damping ratio ζ = %s, participation Γ = %s kg^0.5·m, "
            "effective-mass fraction %s. Displacement drawn × %s per unit modal coordinate "
            "(so that the largest is %s of the mast's bounding-box diagonal; the shape is "
            "mass-normalised, its size has no physical meaning). Grey: the undeformed mast, %s; "
            "blue: shell interfaces (corner nodes of each element), red: rigid modules. Views in "
            "the mast's frame: a along the axis, n across it in the deployment plane, z along the "
            "joint axis."
            % (escape(m.labels[mode]), number("frequency_hz"), number("damping_ratio"),
               number("participation"), number("effective_mass_fraction"),
               num_span(scales[mode], "", i, scale_key),
               ("%g %%" % (100.0 * amplitude)) if amplitude == amplitude else "a fixed share",
               angle))


def stability_note(m):
    """A warning paragraph for modes of an unstable equilibrium (None when stable or unknown)."""
    if m.stable is None or m.stable:
        return None
    return ('<p class="warning"><b>Unstable equilibrium.</b> This modal analysis was written with '
            '<code>--allow-unstable</code>: the linearisation point is not a stable equilibrium '
            '(%s), so these modes do not describe small vibrations about it. See '
            'docs/user_guide.md, "Stability of the linearisation point".</p>'
            % escape(m.instability or "negative stiffness in the constrained tangent"))


def modal_comparison_table(comparison):
    """The matched pairs of a ModalComparison: mode and frequency of A and of its best match in B
    (numbers from the files), the pair's MAC and frequency ratio (computed, class "derived")."""
    a, b = comparison.a, comparison.b
    rows = ["<table class=\"mac-pairs\"><tr><th>mode of A</th><th>label (A)</th>"
            "<th>f_A [Hz]</th><th>best match in B</th><th>label (B)</th><th>f_B [Hz]</th>"
            "<th>MAC [–]</th><th>f_B / f_A [–]</th></tr>"]
    for i, j, mac, ratio in comparison.pairs:
        rows.append("<tr><td>%d</td><td>%s</td>%s<td>%d</td><td>%s</td>%s%s%s</tr>"
                    % (i + 1, escape(a.labels[i]),
                       num_cell(a.frequency_hz[i], "Hz", a.index, "/modes/frequency_hz[%d]" % i),
                       j + 1, escape(b.labels[j]),
                       num_cell(b.frequency_hz[j], "Hz", b.index, "/modes/frequency_hz[%d]" % j),
                       num_cell(mac, "1", derived=True), num_cell(ratio, "1", derived=True)))
    rows.append("</table>")
    return "\n".join(rows)


def database_samples_table(db, shown):
    """Per sample: the parameters (as stored) and the lowest drive-excited frequencies, each
    f = ω/2π of /samples/omega[s, k] (computed: class "derived", the data-key names the ω)."""
    from report_inputs import drive_excited

    headers = ["sample"] + [_unit_header(key, units) for key, _, units in db.axes]
    headers += ["drive-excited mode %d [Hz]" % (j + 1) for j in range(shown)]
    rows = ['<table class="database"><tr>%s</tr>' % "".join("<th>%s</th>" % h for h in headers)]
    for s in range(db.parameters.shape[0]):
        cells = ["<td>%d%s</td>" % (s + 1, " (reference)" if s == db.reference_sample else "")]
        for a, (_, _, units) in enumerate(db.axes):
            cells.append(num_cell(db.parameters[s, a], units, db.index,
                                  "/samples/parameters[%d,%d]" % (s, a)))
        hz = db.omega[s] / (2.0 * math.pi)
        chosen = drive_excited(hz, db.participation[s], shown)
        for j in range(shown):
            if j >= len(chosen):
                cells.append("<td>–</td>")
                continue
            k = chosen[j]
            cells.append('<td class="num derived" data-file="%d" data-from="/samples/omega[%d,%d]" '
                         'data-si="%s" data-unit="Hz" title="ω/2π of /samples/omega[%d,%d] = %s '
                         'rad/s, mode %d of the sample">%s</td>'
                         % (db.index, s, k, format_si(hz[k]), s, k, format_si(db.omega[s, k]),
                            k + 1, format_number(hz[k])))
        rows.append("<tr>%s</tr>" % "".join(cells))
    rows.append("</table>")
    return "\n".join(rows)
