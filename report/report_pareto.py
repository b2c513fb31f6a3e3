"""The Pareto front of a screen (`mastrom screen --pareto OBJ[:min|max],...`, docs/user_guide.md §3):
a scatter of the first two objectives, every design grey and the front's designs highlighted and
numbered, and beside it the table of the front's designs (number, parameters, objectives), so that
each highlighted point's design can be read off.

The front is the file's own column `pareto_front` (1 = no design is better in every objective of
the root attribute `pareto_objectives`); the report draws it, it does not recompute it.
"""

from matplotlib.figure import Figure
import numpy as np

from report_common import METRIC_TITLES, display_unit
from report_figures import safe_name, save
from report_page import _unit_header, escape, num_cell

PARETO_COLUMN = "pareto_front"
#: Front designs numbered in the figure and listed in the table (the file holds them all).
PARETO_TABLE_ROWS = 60


def has_front(screen):
    return bool(screen.pareto_objectives) and PARETO_COLUMN in screen.metric_names


def _front_rows(screen):
    flag = screen.metrics[:, screen.metric_names.index(PARETO_COLUMN)]
    return np.flatnonzero(flag == 1.0)


def pareto_figure(screen, out_dir):
    """Scatter of the first two objectives; the front highlighted, its designs numbered as in the
    table beside it (their row in the file, from 1)."""
    (x_name, x_max), (y_name, y_max) = screen.pareto_objectives[:2]
    x_col, y_col = screen.metric_names.index(x_name), screen.metric_names.index(y_name)
    x_unit, x_factor = display_unit(screen.metric_units[x_col])
    y_unit, y_factor = display_unit(screen.metric_units[y_col])
    x = screen.metrics[:, x_col] * x_factor
    y = screen.metrics[:, y_col] * y_factor
    front = _front_rows(screen)
    figure = Figure(figsize=(6.4, 4.8), layout="constrained")
    axis = figure.subplots()
    axis.scatter(x, y, s=14, color="0.7", label="designs (%d)" % x.size)
    order = front[np.argsort(x[front], kind="stable")]
    if len(screen.pareto_objectives) == 2:
        # The boundary of what the screen attains: between two front designs the better value of
        # the second objective is the one of the design the first objective still allows.
        axis.plot(x[order], y[order], "-", color="tab:red", linewidth=0.8,
                  drawstyle="steps-pre" if x_max else "steps-post")
    axis.scatter(x[order], y[order], s=30, color="tab:red", edgecolors="black", linewidths=0.4,
                 label="Pareto front (%d)" % front.size, zorder=3)
    for row in order[:PARETO_TABLE_ROWS]:
        axis.annotate("%d" % (row + 1), (x[row], y[row]), textcoords="offset points",
                      xytext=(4, 4), fontsize=7)
    axis.set_xlabel("%s [%s] (%s)" % (METRIC_TITLES.get(x_name, x_name), x_unit,
                                      "max" if x_max else "min"))
    axis.set_ylabel("%s [%s] (%s)" % (METRIC_TITLES.get(y_name, y_name), y_unit,
                                      "max" if y_max else "min"))
    objectives = ", ".join("%s:%s" % (n, "max" if m else "min") for n, m in screen.pareto_objectives)
    axis.set_title("Pareto front of %s" % objectives, fontsize=9)
    axis.legend(loc="best", fontsize=8)
    caption = ("Every design of the screen (grey) and the designs no other design beats in every "
               "objective (%s; red, numbered by their row in the file, listed in the table "
               "below)." % objectives)
    if len(screen.pareto_objectives) > 2:
        caption += (" With more than two objectives a front design may lie inside the cloud of "
                    "these two: another objective puts it on the front.")
    return save(figure, out_dir, "pareto_%d_%s_%s" % (screen.index + 1, safe_name(x_name),
                                                     safe_name(y_name)),
                "Pareto front (%s)" % screen.label, caption)


def pareto_table(screen, limit=PARETO_TABLE_ROWS):
    """The front's designs: their number (row in the file), parameters and objectives."""
    objective_columns = [screen.metric_names.index(n) for n, _ in screen.pareto_objectives]
    headers = ["design"]
    headers += [_unit_header(n, u) for n, u in zip(screen.parameter_names, screen.parameter_units)]
    headers += [_unit_header(METRIC_TITLES.get(screen.metric_names[j], screen.metric_names[j]),
                             screen.metric_units[j]) for j in objective_columns]
    rows = ['<table class="pareto"><tr>%s</tr>' % "".join("<th>%s</th>" % h for h in headers)]
    front = _front_rows(screen)
    for i in front[:limit]:
        cells = ["<td>%d</td>" % (i + 1)]
        for j, unit in enumerate(screen.parameter_units):
            cells.append(num_cell(screen.parameters[i, j], unit, screen.index,
                                  "/screen/parameters[%d,%d]" % (i, j)))
        for j in objective_columns:
            cells.append(num_cell(screen.metrics[i, j], screen.metric_units[j], screen.index,
                                  "/screen/metrics[%d,%d]" % (i, j)))
        rows.append("<tr>%s</tr>" % "".join(cells))
    rows.append("</table>")
    if front.size > limit:
        rows.append('<p class="note">First %d of the %d designs on the front; the file holds them '
                    'all.</p>' % (limit, front.size))
    return "\n".join(rows) if front.size else '<p class="note">%s</p>' % escape(
        "No design on the front (every objective value is NaN).")
