// The ROM's answer for one design of an optimisation (docs/theory.md §4.5): the metrics of a
// screen (rom/studies/screen_kernel.hpp, the same per-design code, so a design optimised gives the
// numbers `mastrom screen` gives it) and the database's upper estimate of its error there
// (rom/interpolation/point_error_estimate.hpp). Everything that does not depend on the design —
// the configuration with --set, the free case, the interpolator — is set up once.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/config.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/studies/design_description.hpp"
#include "rom/studies/screen_kernel.hpp"

namespace mastrom::rom {

class RomDesignEvaluator {
public:
  /// The database's default method with `overrides` (--set: free keys, or database parameters
  /// held fixed) on its base configuration. InputError as evaluationConfig and freeCaseOf.
  RomDesignEvaluator(const RomDatabase& db, const std::vector<std::string>& overrides);

  const Config& config() const { return config_; }
  /// The screen's metric names and SI units at every design.
  const std::vector<std::string>& names() const { return names_; }
  const std::vector<std::string>& units() const { return units_; }
  /// The columns behind names(): what metricIndex checks a requested metric against.
  const MetricColumns& columns() const { return columns_; }
  /// The point of the configuration (with --set): where the fixed parameters are held.
  const std::vector<double>& basePoint() const { return base_point_; }

  /// The metrics at a point of the database's box (one value per axis), in names() order.
  std::vector<double> metrics(const std::vector<double>& point) const;

  /// (e_ω, e_r): the upper estimate at `point`, or where the database has no point estimate its
  /// own box-wide estimate; {−1, −1} when it has neither.
  std::pair<double, double> upperErrorEstimate(const std::vector<double>& point) const;
  /// Whether the errors come from the point estimate (probes) or the box-wide one.
  bool pointwiseEstimate() const { return pointwise_; }

private:
  const RomDatabase& db_;
  Config config_;
  std::unique_ptr<ModalInterpolator> interpolator_;
  std::vector<FreeCase> cases_;
  ScreenStressColumns stress_;
  std::unique_ptr<DesignDescriber> describer_;
  MetricColumns columns_;
  std::vector<std::string> names_, units_;
  std::vector<double> base_point_;
  bool pointwise_ = false;
  std::pair<double, double> box_estimate_{-1.0, -1.0};
};

}  // namespace mastrom::rom
