// Uncertainty and sensitivity through the ROM (`mastrom uq`, docs/theory.md §7): the uncertain
// inputs of a configuration ([uncertainty], common/config.hpp) are sampled (randomised Sobol points
// or plain Monte Carlo, common/statistics/unit_sampler.hpp), every sample is reduced to every
// metric of the screen by the screen's own per-design code (rom/studies/screen_kernel.hpp, so a
// metric added there appears here), and rank 0 summarises: mean, standard deviation and quantiles
// with confidence intervals, the exceedance probability of each limit, the same probability with
// each sample's ROM error estimate taken against the limit (the conservative value, §7.3), and,
// on Saltelli's design, first-order and total Sobol indices with bootstrap intervals (§7.4).
//
// The configuration is a run configuration of the database's mast: every key the database holds
// fixed must have the database's value (InputError naming the first that differs), database
// parameters give the nominal point, free keys (drive, timing) the deployment, and each uncertain
// key must be a parameter of the database. Samples are distributed over the ranks in contiguous
// blocks; every sample is computed by the same code from the same inputs whatever the rank count,
// so the results do not depend on it.
#pragma once

#include <mpi.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/statistics/sample_statistics.hpp"
#include "common/statistics/sobol_indices.hpp"
#include "common/statistics/unit_sampler.hpp"
#include "rom/database/interpolation_method.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/studies/screen_filter.hpp"
#include "rom/studies/screen_kernel.hpp"

namespace mastrom::rom {

struct UqOptions {
  stats::SamplingKind sampling = stats::SamplingKind::Sobol;
  /// Base samples N: N ROM evaluations, or N (k + 2) with sensitivity (k uncertain inputs).
  long samples = 4096;
  unsigned long seed = 1;
  /// Saltelli's design and Sobol indices; false: the N samples only (moments, probabilities).
  bool sensitivity = true;
  /// With sensitivity: double N until the widest index interval of any metric is at most this
  /// (0: no adaptive growth) or the next doubling would exceed max_evaluations.
  double target_width = 0.0;
  long max_evaluations = 1000000;
  double confidence = 0.95;
  int bootstrap_resamples = 200;
  /// "METRIC OP VALUE" with OP one of < <= > >=: the event whose probability is wanted.
  std::vector<ColumnCondition> limits;
  /// The interpolation; none: the database's default, the only one whose error it estimates (a
  /// fixed default here once made a study that forgot to set it run another method than
  /// `mastrom uq`, with no error estimate).
  std::optional<InterpolationMethod> method;
  BoxPolicy box = BoxPolicy::Refuse;
  double step_s = kDefaultScreenStepS;  ///< the ROM step (screen_kernel.hpp screenStep)
  bool stresses = true;
  MPI_Comm communicator = MPI_COMM_NULL;
  /// Called on every rank: (phase, done, total) of its own block of the current phase.
  std::function<void(const std::string& phase, long done, long total)> progress;
};

/// The probability of one limit's event.
struct LimitProbability {
  ColumnCondition limit;
  stats::Interval probability;  ///< of the ROM's values
  /// With every sample's ROM error estimate taken against the limit (the sample counts when the
  /// event holds anywhere in value ± error): an upper value of the probability (§7.3).
  stats::Interval conservative;
  bool has_error_estimate = false;  ///< false: the metric has no ROM error estimate (= probability)
  long critical_row = -1;           ///< the sample farthest into the event (or nearest to it)
};

struct UqResult {
  std::vector<std::string> input_names;  ///< the uncertain keys (database axes), in config order
  std::vector<std::string> metric_names, metric_units;
  long base_samples = 0;
  long rows = 0;  ///< ROM evaluations
  int inputs = 0;
  /// Row r's role in Saltelli's design: r % (k + 2) = 0 A, 1 B, 2 + i AB_i; without sensitivity
  /// every row is a plain sample.
  std::vector<double> input_values;  ///< rows × inputs (the sampled keys' values, SI)
  std::vector<double> metrics;       ///< rows × metrics
  /// Per row: the ROM's estimated relative error (ω₁, response NRMSE upper value, (4.13)/(4.14));
  /// −1 where the database has no estimate.
  std::vector<double> rom_error;  ///< rows × 2
  /// Per row and metric: the absolute error bound taken against the limits (§7.3); 0 where the
  /// metric has none.
  std::vector<double> metric_error;  ///< rows × metrics
  std::vector<bool> metric_has_error;
  std::vector<long> statistic_rows;             ///< the rows of the statistics: A and B, or all
  std::vector<stats::SampleSummary> summaries;  ///< per metric (count 0: not enough finite values)
  std::vector<LimitProbability> limits;
  bool has_sensitivity = false;
  std::vector<stats::SobolIndices> sobol;  ///< per metric (empty indices for a constant metric)
  std::string config_toml;                 ///< the study's configuration (with [uncertainty])
  std::string database_checksum;
  stats::SamplingKind sampling = stats::SamplingKind::Sobol;
  unsigned long seed = 1;
  double confidence = 0.95;
  double step_s = 0.0;
  int ranks = 1;
  double wall_s = 0.0;
  /// The parameter point of row r (every database axis).
  std::vector<double> point(long row) const;
  std::vector<double> nominal_point;
  std::vector<int> input_axis;  ///< axis index of each input
  double metric(long row, std::size_t m) const {
    return metrics[static_cast<std::size_t>(row) * metric_names.size() + m];
  }
};

/// The study's configuration checked against the database (see the header): InputError naming the
/// first fixed key that differs, an uncertain key that is not a database parameter, or a study
/// without uncertain inputs.
void checkUqConfig(const RomDatabase& db, const Config& config);

/// Run the study. Collective over options.communicator; the result is complete on rank 0 (the
/// other ranks get the names only). Every input error is found before the first deployment.
UqResult runUncertaintyStudy(const RomDatabase& db, const Config& config, const UqOptions& options);

}  // namespace mastrom::rom
