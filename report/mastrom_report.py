#!/usr/bin/python3
"""`mastrom report FILE.h5 … [--out DIR]`: the plots and tables people would otherwise make by hand
from mastrom's HDF5 result files (README.md "Command line" and "Outputs and units"), written as PNG + SVG figures and one
self-contained index.html into DIR (default: report/ next to the first input).

Run by the `mastrom report` subcommand (cli/cmd_report.cpp) or directly:
    /usr/bin/python3 report/mastrom_report.py out.h5 rom.h5 --out my_report
Needs Debian's python3-h5py, python3-numpy and python3-matplotlib (visible to /usr/bin/python3).

Each input is recognised by its root attribute `source` (report_inputs.py). Failures print one line,
`mastrom report: error: <what>`, and exit with 2 (bad input or file) or 1 (anything else, e.g. a
missing Python package) — the codes of the `mastrom` executable, which forwards them.
docs/report.md says what every figure and table shows.
"""

import argparse
import os
import sys

# No __pycache__ in the source tree (it may be read-only, and it is not the user's output).
sys.dont_write_bytecode = True
_HERE = os.path.dirname(os.path.abspath(__file__))
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)

from report_common import EXIT_FAILURE, EXIT_INPUT, EXIT_OK, ReportError  # noqa: E402

#: Python module -> the Debian package that provides it for /usr/bin/python3.
_DEBIAN_PACKAGES = (("numpy", "python3-numpy"), ("h5py", "python3-h5py"),
                    ("matplotlib", "python3-matplotlib"))

#: Rows of a screening table shown in the page (the figures use every point).
SCREEN_TABLE_ROWS = 1000
#: Mode-shape figures per modes file (a finer analysis can hold hundreds of modes).
SHAPE_FIGURES_PER_FILE = 24


class _Parser(argparse.ArgumentParser):
    """argparse that raises ReportError (one line) instead of printing usage and exiting."""

    def error(self, message):
        raise ReportError("%s (run with --help)" % message)


def parse_arguments(argv):
    parser = _Parser(prog="mastrom report",
                     description="Plots (PNG + SVG) and one self-contained HTML page from mastrom "
                                 "result files (deployment, modes, screen).")
    parser.add_argument("files", nargs="+", metavar="FILE.h5", help="mastrom HDF5 result files")
    parser.add_argument("--out", metavar="DIR",
                        help="output directory (default: report/ next to the first FILE)")
    parser.add_argument("--screen-metric", metavar="NAME",
                        help="screening heat map of this metric only (default: every metric)")
    parser.add_argument("--mastrom-version", default="", help=argparse.SUPPRESS)
    parser.add_argument("--no-index-line", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--study", metavar="NAME",
                        help="with a study.h5 among the files: the report of this study only")
    # INDEX:PATH — the interpolated frequency curves `mastrom report` computed for the ROM
    # database at position INDEX (0-based) of FILE (cli/report_database.hpp).
    parser.add_argument("--database-curves", action="append", default=[], help=argparse.SUPPRESS)
    return parser.parse_args(argv)


def check_dependencies():
    """ReportError naming the Debian package of the first Python module that is missing."""
    for module, package in _DEBIAN_PACKAGES:
        try:
            __import__(module)
        except ImportError:
            raise ReportError("Python module '%s' is missing for %s: install the Debian package %s "
                              "(apt-get install %s)" % (module, sys.executable, package, package),
                              EXIT_FAILURE) from None


def default_out_dir(first_input):
    return os.path.join(os.path.dirname(first_input), "report")


def run(options):
    # Imported here: they need numpy, h5py and matplotlib, which check_dependencies() has checked.
    import report_figures as figures
    import report_inputs as inputs_module
    import report_pairing as pairing
    import report_page as page_module
    import report_stress
    import report_pareto

    inputs = [inputs_module.read_input(i, path) for i, path in enumerate(options.files)]
    deployments = [f for f in inputs if f.kind == "deployment"]
    modes = [f for f in inputs if f.kind == "modes"]
    screens = [f for f in inputs if f.kind == "screen"]
    databases = [f for f in inputs if f.kind == "database"]
    uq_files = [f for f in inputs if f.kind == "uq"]
    study_tables = [f for f in inputs if f.kind == "study"]
    optimizations = [f for f in inputs if f.kind == "optimize"]
    if options.study is not None:
        if not study_tables:
            raise ReportError("--study %s: no study.h5 (source 'study') among the inputs"
                              % options.study)
        for table in study_tables:
            if options.study not in table.study_names:
                raise ReportError("--study %s: '%s' holds the studies %s" % (
                    options.study, table.path, ", ".join(sorted(set(table.study_names)))))
    for spec in options.database_curves:
        index, _, path = spec.partition(":")
        if not index.isdigit() or int(index) >= len(inputs) or inputs[int(index)].kind != "database":
            raise ReportError("--database-curves %s: no ROM database at that position" % spec)
        inputs[int(index)].attach_curves(path)
    others = [f for f in inputs if f.kind == "generic"]
    for group in (deployments, modes):
        pairing.assign_labels(group)

    if options.screen_metric is not None:
        if not screens:
            raise ReportError("--screen-metric %s: no screen file among the inputs"
                              % options.screen_metric)
        for s in screens:
            if options.screen_metric not in s.metric_names:
                raise ReportError("--screen-metric %s: '%s' has the metrics %s"
                                  % (options.screen_metric, s.path, ", ".join(s.metric_names)))

    out_dir = options.out if options.out else default_out_dir(options.files[0])
    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as error:
        raise ReportError("cannot create the output directory '%s': %s"
                          % (out_dir, error.strerror or error)) from None
    if not os.access(out_dir, os.W_OK):
        raise ReportError("the output directory '%s' is not writable" % out_dir)

    page = page_module.Page(out_dir)
    page.heading(1, "mastrom report")
    page.paragraph("%d input file%s. %s" % (len(inputs), "" if len(inputs) == 1 else "s",
                                            page_module.PRECISION_NOTE), "note")
    sections = [("inputs", "Inputs")]
    if study_tables:
        sections.append(("study", "Study"))
    if deployments:
        sections.append(("deployments", "Deployments"))
    if modes:
        sections.append(("modes", "Modal analyses"))
    if screens:
        sections.append(("screening", "Screening"))
    if uq_files:
        sections.append(("uq", "Uncertainty"))
    if optimizations:
        sections.append(("optimization", "Optimisation"))
    if databases:
        sections.append(("databases", "ROM databases"))
    if others:
        sections.append(("other", "Other files"))
    page.add("<p>%s</p>" % " · ".join('<a href="#%s">%s</a>' % s for s in sections))

    page.heading(2, "Inputs", "inputs")
    page.add(page_module.inputs_table(inputs))
    page.add(page_module.config_blocks(inputs))

    if study_tables:
        import report_study

        page.heading(2, "Study", "study")
        page.paragraph("Each case run with the nonlinear full order and with the modal ROM solved "
                       "at the case's own parameters (<code>mastrom study</code>, "
                       "docs/user_guide.md \"Studies\"). The findings are those of Liu &amp; Wen "
                       "(2024) that the study tests; a finding holds for a model when its metric "
                       "orders the cases as the finding says. The overlays below are the paper's "
                       "figures: one colour per case, full order solid, ROM dashed.", "note")
        for table in study_tables:
            names = ([options.study] if options.study is not None
                     else sorted(set(table.study_names), key=table.study_names.index))
            for name in names:
                page.heading(3, "%s (#%d %s)" % (name, table.index + 1,
                                                 os.path.basename(table.path)))
                page.add(report_study.findings_table(table, name))
                page.add(report_study.metrics_table(table, name))

    figure_count = 0
    if deployments:
        page.heading(2, "Deployments", "deployments")
        page.paragraph("One line per file (ROM dashed); the dotted vertical line marks where the "
                       "drive stops. Angular accelerations in °/s², forces in N, torques in N·m.",
                       "note")
        for entry in figures.deployment_figures(deployments, out_dir):
            page.figure(entry)
            figure_count += 1
        for entry in report_stress.stress_figures(deployments, out_dir):
            page.figure(entry)
            figure_count += 1
        page.heading(3, "Metrics")
        page.add(page_module.metrics_table(deployments))
        roms = [d for d in deployments if d.source == "rom"]
        if roms:
            page.heading(3, "ROM vs full order", "rom-vs-full")
            pairs = pairing.rom_full_pairs(deployments)
            for number, (rom, full) in enumerate(pairs, start=1):
                comparison = pairing.Comparison(rom, full)
                page.paragraph("#%d %s (ROM) against #%d %s (full order), %d common instants. "
                               "NRMSE = RMS(ROM − full) / RMS(full); the ROM is interpolated "
                               "linearly onto the full-order instants."
                               % (rom.index + 1, page_module.escape(rom.case_label),
                                  full.index + 1, page_module.escape(full.case_label),
                                  comparison.time.size))
                page.add(page_module.comparison_table(comparison))
                page.figure(figures.comparison_figure(number, comparison, out_dir))
                figure_count += 1
            unmatched = [r for r in roms if all(r is not p[0] for p in pairs)]
            for rom in unmatched:
                page.paragraph("#%d %s: no full-order file of the same case (same mast, module, "
                               "interface, material, drive and gravity) among the inputs."
                               % (rom.index + 1, page_module.escape(rom.label)), "note")

    if modes:
        page.heading(2, "Modal analyses", "modes")
        for m in modes:
            page.heading(3, "#%d %s" % (m.index + 1, m.label))
            warning = page_module.stability_note(m)
            if warning:
                page.add(warning)
            elif m.stable:
                page.paragraph("Linearisation point checked: a stable equilibrium (no negative "
                               "eigenvalue of the constrained tangent stiffness).", "note")
            page.add(page_module.modes_table(m))
            page.figure(figures.effective_mass_figure(m, out_dir))
            figure_count += 1
            if m.views is None:
                page.paragraph("No /visualization group in this file: mode shapes not drawn.",
                               "note")
                continue
            shown = min(m.frequency_hz.size, SHAPE_FIGURES_PER_FILE)
            page.paragraph("Mode shapes of #%d: %s" % (
                m.index + 1, "every mode" if shown == m.frequency_hz.size else
                "the first %d of %d modes (the file holds them all; ParaView shows them with "
                "the .xdmf written next to it)" % (shown, m.frequency_hz.size)), "note")
            for mode in range(shown):
                entry = figures.mode_shape_figure(m, mode, out_dir)
                entry.caption_html = page_module.mode_caption(m, mode)
                page.figure(entry)
                figure_count += 1
        differing = pairing.differing_keys(modes)
        for entry in figures.modes_figures(modes, out_dir, differing):
            page.figure(entry)
            figure_count += 1
        if len(modes) > 1:
            page.heading(3, "Mode sets compared (MAC)", "modes-mac")
            for number, other in enumerate(modes[1:], start=1):
                comparison = pairing.ModalComparison(modes[0], other)
                title = ("A = #%d %s, B = #%d %s" % (modes[0].index + 1, modes[0].label,
                                                     other.index + 1, other.label))
                if comparison.mac is None:
                    page.paragraph("%s: no MAC, %s." % (page_module.escape(title),
                                                         comparison.reason), "note")
                    continue
                page.paragraph(page_module.escape(title) + ". The MAC uses the displacements of "
                               "the drawn points (shell nodes, module corners) in the mast's "
                               "frame; each mode of A is matched to the mode of B it resembles "
                               "most.", "note")
                page.figure(figures.modal_comparison_figure(number, comparison, out_dir))
                figure_count += 1
                page.add(page_module.modal_comparison_table(comparison))

    if screens:
        page.heading(2, "Screening", "screening")
        for s in screens:
            page.heading(3, "#%d %s" % (s.index + 1, s.label))
            columns = ([s.metric_names.index(options.screen_metric)] if options.screen_metric
                       else [j for j, name in enumerate(s.metric_names)
                             if name != report_pareto.PARETO_COLUMN])
            for column in columns:
                page.figure(figures.screen_figure(s, column, out_dir))
                figure_count += 1
            if report_pareto.has_front(s):
                page.figure(report_pareto.pareto_figure(s, out_dir))
                figure_count += 1
                page.add(report_pareto.pareto_table(s))
            page.add(page_module.screen_table(s, SCREEN_TABLE_ROWS))

    if uq_files:
        import report_uq

        page.heading(2, "Uncertainty", "uq")
        for uq in uq_files:
            page.heading(3, "#%d %s" % (uq.index + 1, uq.label))
            figure_count += report_uq.uq_section(uq, page, out_dir)
    if optimizations:
        import report_optimize

        page.heading(2, "Optimisation", "optimization")
        page.paragraph("<code>mastrom optimize</code> (docs/theory.md §4.5): each round the ROM's "
                       "constrained optimum, every constraint taken with a margin of the ROM's "
                       "estimated error, then the nonlinear full order at that design; a "
                       "constraint the full order violates is tightened by the measured "
                       "difference for the next round.", "note")
        for record in optimizations:
            page.heading(3, "#%d %s" % (record.index + 1, record.label))
            page.paragraph(report_optimize.summary_text(record))
            page.figure(report_optimize.optimize_figure(record, out_dir))
            figure_count += 1
            page.add(report_optimize.rounds_table(record))

    if databases:
        page.heading(2, "ROM databases", "databases")
        for db in databases:
            page.heading(3, "#%d %s" % (db.index + 1, db.label))
            if db.curves is None:
                page.paragraph("Samples only: the interpolation between them is evaluated by "
                               "<code>mastrom report</code> (the Python program run alone cannot "
                               "call it).", "note")
            else:
                page.paragraph("Interpolation: method %s (the database's default), evaluated "
                               "along each axis; the curves are stored in <code>%s</code>."
                               % (page_module.escape(db.curves["method"]),
                                  page_module.escape("rom_database_%d.h5" % (db.index + 1))),
                               "note")
            for entry in figures.database_figures(db, out_dir):
                page.figure(entry)
                figure_count += 1
            page.add(page_module.database_samples_table(db, figures.DRIVE_EXCITED_SHOWN))

    if others:
        page.heading(2, "Other files", "other")
        for f in others:
            page.heading(3, "#%d %s (source %s)" % (f.index + 1, f.label, f.source))
            page.paragraph("This report does not plot '%s' files yet; their contents:"
                           % page_module.escape(f.source), "note")
            page.add(page_module.generic_listing(f))

    index = page.write("mastrom report: " + ", ".join(os.path.basename(f.path) for f in inputs),
                       options.mastrom_version)
    print("mastrom report: %d input file%s, %d figures (PNG + SVG) in %s"
          % (len(inputs), "" if len(inputs) == 1 else "s", figure_count, out_dir))
    if not options.no_index_line:
        print("wrote " + index)
    return EXIT_OK


def main(argv=None):
    """Entry point; returns the exit code (0, 1 or 2) instead of exiting."""
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        options = parse_arguments(argv)
        check_dependencies()
        return run(options)
    except SystemExit as done:  # --help
        return done.code if isinstance(done.code, int) else EXIT_OK
    except ReportError as error:
        return _fail(str(error), error.exit_code)
    except OSError as error:  # writing the figures or the page
        return _fail("cannot write %s: %s"
                     % (error.filename or "the report", error.strerror or error), EXIT_INPUT)


def _fail(message, code):
    sys.stdout.flush()
    print("mastrom report: error: " + " ".join(message.split()), file=sys.stderr)
    return code


if __name__ == "__main__":
    sys.exit(main())
