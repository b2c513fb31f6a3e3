"""Figures of the interface stresses of full-order deployments (docs/theory.md §6): the history of
each interface's largest von Mises stress, and the field at its peak on the cylinder unrolled
(axial position across, angle about the axis up, colour = von Mises, the larger of the two walls).
"""

import math

from matplotlib.figure import Figure
import numpy as np

from report_figures import WIDE, safe_name, save


def stress_figures(deployments, out_dir):
    """The stress figures of every deployment that carries /interfaces; [] when none does."""
    figures = []
    with_stress = [d for d in deployments if d.interfaces]
    if not with_stress:
        return figures
    with_history = [d for d in with_stress
                    if all(itf["max_von_mises"] is not None for itf in d.interfaces)]
    if with_history:
        figure = Figure(figsize=WIDE, layout="constrained")
        axis = figure.subplots()
        for d in with_history:
            for k, itf in enumerate(d.interfaces, start=1):
                axis.plot(d.time, itf["max_von_mises"] * 1e-6,
                          label="%s, interface %d" % (d.label, k))
        axis.set_xlabel("time [s]")
        axis.set_ylabel("max von Mises [MPa]")
        axis.set_title("Largest von Mises stress of each interface")
        axis.legend(loc="upper right")
        figures.append(save(figure, out_dir, "interface_stress_history",
                            "Interface stress histories",
                            "Largest von Mises stress of each interface over its elements, "
                            "recovery points and both walls, at every output instant (a ROM "
                            "result has it with rom eval --stress-history)."))
    for d in with_stress:
        count = len(d.interfaces)
        figure = Figure(figsize=(WIDE[0], 2.2 * count + 0.6), layout="constrained")
        axes = figure.subplots(count, 1, squeeze=False)
        for k, itf in enumerate(d.interfaces):
            axis = axes[k][0]
            points = itf["points"]
            walls = np.maximum(itf["field"][:, 0], itf["field"][:, 2]) * 1e-6
            cells = axis.scatter(points[:, 0] * 1e3, np.degrees(points[:, 1]), c=walls, s=36,
                                 marker="s", cmap="viridis")
            peak = itf["peak"]
            axis.plot([peak["axial_position_m"] * 1e3], [math.degrees(peak["angle_rad"])], "rx",
                      markersize=9)
            axis.set_ylabel("angle [deg]")
            axis.set_title("interface %d at t = %.4f s: peak %.4g MPa (red cross)"
                           % (k + 1, peak["time_s"], peak["von_mises_pa"] * 1e-6))
            figure.colorbar(cells, ax=axis, label="von Mises [MPa]")
        axes[-1][0].set_xlabel("axial position from the base edge [mm]")
        figures.append(save(figure, out_dir, "interface_stress_field_" + safe_name(d.label),
                            "Stress field at the peak (%s)" % d.label,
                            "Von Mises stress at the recovery points (3 x 3 per element, the larger "
                            "of the inner and outer wall) at the instant of each interface's peak, "
                            "on the cylinder unrolled."))
    return figures
