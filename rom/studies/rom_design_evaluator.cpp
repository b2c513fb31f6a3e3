// One design's ROM metrics and error estimate (see rom_design_evaluator.hpp).
#include "rom/studies/rom_design_evaluator.hpp"

#include "rom/database/database_io.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/point_error_estimate.hpp"

namespace mastrom::rom {

RomDesignEvaluator::RomDesignEvaluator(const RomDatabase& db,
                                       const std::vector<std::string>& overrides)
    : db_(db), config_(evaluationConfig(db, overrides)) {
  // The screen's ROM step and continuous peaks: the numbers `mastrom screen` gives the design.
  const double step = screenStep(overrides, kDefaultScreenStepS, PeakResolution::Continuous);
  cases_.push_back(freeCaseOf(config_, step));
  interpolator_ = makeInterpolator(db, db.default_method);
  stress_ = screenStressColumns(db, config_, db.default_method);
  // Mass and the default number of frequencies at the deployed angle, as `screen` gives them.
  describer_ = std::make_unique<DesignDescriber>(db, config_, FrequencyRequest{},
                                                 std::vector<double>{config_.drive.angle_deg},
                                                 BoxPolicy::Refuse);
  columns_ = screenColumns(stress_, describer_.get());
  names_ = screenMetricNames(stress_, describer_.get());
  units_ = screenMetricUnits(stress_, describer_.get());
  base_point_ = parameterPoint(db, config_);
  pointwise_ = !db.probes.empty();
  box_estimate_ = databaseErrorEstimate(db);
}

std::vector<double> RomDesignEvaluator::metrics(const std::vector<double>& point) const {
  std::vector<double> out;
  out.reserve(names_.size());
  const DesignDecoder decode = [&point](long, std::vector<double>& p, long& free_case) {
    p = point;
    free_case = 0;
  };
  screenDesignRange(*interpolator_, cases_, PeakResolution::Continuous, 0, 1, decode, {}, out,
                    stress_, describer_.get());
  return out;
}

std::pair<double, double> RomDesignEvaluator::upperErrorEstimate(
    const std::vector<double>& point) const {
  if (pointwise_) return pointErrorUpperEstimate(db_, point);
  return box_estimate_;
}

}  // namespace mastrom::rom
