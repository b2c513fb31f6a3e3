// ROM screening of an explicit list of designs: design i takes the i-th entry of every column, so
// random samples (Monte Carlo), optimiser iterates or any scattered set can be screened, where
// `mastrom screen` (rom/studies/screening.hpp) enumerates a tensor grid. Each design is reduced to the same
// metrics by the same per-design code (rom/studies/screen_kernel.hpp): a design given here and the same
// design on a grid give the same numbers bit for bit.
//
// A column's key is a database parameter (numbers, inside the sampled box unless extrapolation is
// allowed) or a free key (numbers, or names for drive.law). Keys of neither kind, repeated keys,
// columns of different lengths, non-finite numbers, a point outside the box and an invalid
// combination of free values are InputErrors (one line, naming the key, the design and the value)
// found before the first deployment.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "rom/database/parameter_space.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/studies/design_description.hpp"
#include "rom/studies/screen_kernel.hpp"

namespace mastrom::rom {

/// One key's value for every design: numbers in `values`, or names in `names` (exactly one of the
/// two is non-empty).
struct DesignColumn {
  std::string key;
  std::vector<double> values;
  std::vector<std::string> names;
};

struct DesignScreenOptions {
  std::vector<std::string> overrides;  ///< `--set`-style, on top of the database's base config
  BoxPolicy box = BoxPolicy::Refuse;
  PeakResolution peaks = PeakResolution::Continuous;
  /// The ROM step [s] unless `overrides` set the output interval (screenStep,
  /// screen_kernel.hpp); ≤ 0: the configuration's output interval.
  double step_s = kDefaultScreenStepS;
  /// The natural frequencies of every design (rom/studies/design_description.hpp).
  FrequencyRequest frequencies;
  /// Called after every design with (done, total); may throw to abort the screen.
  std::function<void(long done, long total)> progress;
};

struct DesignScreenTable {
  long designs = 0;
  std::vector<std::string> metric_names;  ///< rom/studies/design_metrics.hpp, in column order
  std::vector<std::string> metric_units;
  MetricColumns columns;
  std::vector<double> metrics;  ///< designs × metrics, row-major
  std::string config_toml;      ///< base configuration with the overrides
  double wall_s = 0.0;
};

/// Screen the designs of `columns` with `interpolator` (made from `db`). At least one column.
DesignScreenTable screenDesigns(const RomDatabase& db, const ModalInterpolator& interpolator,
                                const std::vector<DesignColumn>& columns,
                                const DesignScreenOptions& options);

}  // namespace mastrom::rom
