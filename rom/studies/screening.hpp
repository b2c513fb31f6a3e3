// Design-space screening with the ROM (docs/theory.md §4, §5.2 `mastrom screen`): the scalar
// metrics of docs/theory.md §1 for every point of a grid of designs (database parameters) and drive
// laws (free keys), each point one interpolated modal model and one ROM deployment.
//
// Grid axes: `KEY=LO:HI:N` (N evenly spaced values, ends included) or `KEY=v1,v2,…` (a list:
// numbers, or names such as drive.law=trapezoidal,cubic). A key is either a parameter of the
// database (its values must lie in the sampled box unless extrapolation is allowed) or a free key
// (drive.*, simulation.end_time / time_step, output.every, …). Designs are enumerated first axis
// fastest.
//
// Table: one row per design, columns = the grid keys (a list of names is stored as the index of the
// name in the list), then the metrics. Written as CSV (the names themselves, numbers in shortest
// round-trip form) or as HDF5:
//   /screen/parameter_names [p] (strings)   /screen/parameters [N, p] (units: one per column;
//                                            attribute `levels`: per column, the comma-separated
//                                            names of a list axis, "" for a numeric one)
//   /screen/metric_names [q] (strings)      /screen/metrics [N, q] (units: one per column)
//   / attributes source = "screen", mastrom_version, config (the database's base configuration
//                with --set applied), database_checksum, method, designs, wall_time_s, and
//                pareto_objectives ("mass:min,frequency_1:max") when --pareto marked a front
//
// Each design's metrics come from rom/model/deployment_metrics.hpp (the ROM deployment reduced
// while stepping, no series stored: the same numbers as `rom eval` to round-off, several times
// faster). Their peaks are those of the continuous ROM response (PeakResolution::Continuous), so a
// coarse output step (simulation.time_step × output.every = 1 ms) no longer under-reads them; RMS
// and settling remain sample metrics of that step.
//
// Distribution: contiguous blocks of designs over the ranks, gathered to rank 0 in design order;
// every design is computed by the same code from the same inputs, so the table is identical for
// any number of ranks.
#pragma once

#include <mpi.h>

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "rom/database/parameter_space.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/studies/design_description.hpp"
#include "rom/studies/screen_kernel.hpp"

namespace mastrom::rom {

struct ScreenAxis {
  std::string key;
  std::vector<double> values;       ///< numbers (a list of names: 0, 1, 2, …)
  std::vector<std::string> labels;  ///< text of each value (names, or numbers in shortest form)
  bool named = false;               ///< the values are names (e.g. drive laws)
};

/// Parse one `--grid` argument against the database. InputError (one line) when malformed, when
/// the key is neither a database parameter nor a free key, or when a value is invalid for its key.
/// Each value is checked on the database's base configuration with `overrides` (the screen's
/// --set) applied first, as the screen itself applies them: a value that needs another key
/// (drive.law=table needs drive.table) is valid when --set gives that key.
ScreenAxis parseScreenAxis(const std::string& text, const RomDatabase& db,
                           const std::vector<std::string>& overrides = {});

struct ScreenOptions {
  std::vector<ScreenAxis> axes;        ///< at least one
  std::vector<std::string> overrides;  ///< --set on top of the database's base configuration
  InterpolationMethod method = InterpolationMethod::Tracked;
  BoxPolicy box = BoxPolicy::Refuse;
  /// Peaks over the samples (the behaviour before continuous peaks, kept for comparisons) or
  /// continuous.
  PeakResolution peaks = PeakResolution::Continuous;
  /// The ROM step [s] unless `overrides` set the output interval (screenStep,
  /// screen_kernel.hpp); ≤ 0: the configuration's output interval.
  double step_s = kDefaultScreenStepS;
  /// The strength columns (rom/studies/screen_kernel.hpp ScreenStressColumns) when the database
  /// carries stress modes; false leaves them out (and their cost).
  bool stresses = true;
  /// The natural frequencies of every design (rom/studies/design_description.hpp): by default the
  /// lowest 3 where the database can give them at the deployed angle.
  FrequencyRequest frequencies;
  /// Ranks the designs are distributed over; MPI_COMM_NULL = this process only, no MPI call.
  MPI_Comm communicator = MPI_COMM_NULL;
  /// Called on every rank as its designs complete: (done, total) of its own block.
  std::function<void(long done, long total)> progress;
};

struct ScreenTable {
  std::vector<ScreenAxis> axes;
  std::vector<std::string> metric_names;  ///< rom/studies/design_metrics.hpp, in column order
  std::vector<std::string> metric_units;
  MetricColumns columns;  ///< what the metric columns are (and why a family is absent)
  long designs = 0;
  std::vector<double> parameters;  ///< designs × axes, row-major
  std::vector<double> metrics;     ///< designs × metrics, row-major
  std::string config_toml;         ///< base configuration with the --set overrides
  std::string database_checksum;
  InterpolationMethod method = InterpolationMethod::Tracked;
  int ranks = 1;
  double wall_s = 0.0;  ///< rank 0
  double step_s = 0.0;  ///< the ROM step of every deployment [s]
  /// "OBJ:min|max,…" when the table carries the front's column (rom/studies/pareto_front.hpp).
  std::string pareto_objectives;
};

/// The metric columns runScreen(db, options) gives, and why a family is absent: every input error
/// of the options (InputError, one line), without a deployment — for checking the names of
/// --where, --sort-by and --pareto before any work.
MetricColumns screenTableColumns(const RomDatabase& db, const ScreenOptions& options);

/// Run the screen. Collective over options.communicator; the table is complete on rank 0 (the other
/// ranks get the header fields only). Every input error (keys, ranges, box, drive laws) is found
/// before the first deployment.
ScreenTable runScreen(const RomDatabase& db, const ScreenOptions& options);

/// The table as CSV: a header line (grid keys, then metric names), one line per design; names as
/// given, numbers in shortest round-trip form. The file version is written atomically.
void writeScreenCsv(std::ostream& out, const ScreenTable& table);
void writeScreenCsv(const std::string& path, const ScreenTable& table);
void writeScreenH5(const std::string& path, const ScreenTable& table);

}  // namespace mastrom::rom
