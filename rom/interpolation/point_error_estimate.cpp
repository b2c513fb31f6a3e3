// The default method's error at a point (see point_error_estimate.hpp).
#include "rom/interpolation/point_error_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "rom/database/probe_point_estimate.hpp"
#include "rom/interpolation/rbf_weights.hpp"

namespace mastrom::rom {

namespace {

/// P(x) and the probes' scales ε_j = e_j / P(x_j) (ω₁, response) of a scattered database, in its
/// sampled axes; probes at P = 0 are dropped (they say nothing about the scale).
struct ScatteredScales {
  double power = 0.0;
  std::vector<double> frequency, response;
};

ScatteredScales scatteredScales(const RomDatabase& db, const std::vector<double>& point) {
  MASTROM_REQUIRE(point.size() == db.axes.size(), InputError, "rom: a point of ", point.size(),
                  " parameters for a database of ", db.axes.size());
  const int exact = db.exactModulusAxis();
  const auto sampledPart = [exact](std::vector<double> x) {
    if (exact >= 0) x.erase(x.begin() + exact);
    return x;
  };
  const RomDatabase sampled = sampledDatabase(db);
  std::vector<std::vector<double>> samples, at{sampledPart(point)};
  for (const RomSample& s : sampled.samples) samples.push_back(s.parameters);
  for (const ProbeError& e : db.probes) at.push_back(sampledPart(e.parameters));
  const Eigen::VectorXd power = RadialBasisWeights(sampled.axes, samples).powerFunctions(at);
  constexpr double kFloor = 1e-300;  // an error of exactly 0 would make the log −∞
  ScatteredScales out;
  out.power = power[0];
  for (std::size_t j = 0; j < db.probes.size(); ++j) {
    const double pj = power[static_cast<Eigen::Index>(j + 1)];
    if (!(pj > 0)) continue;
    out.frequency.push_back(std::max(db.probes[j].frequency_error, kFloor) / pj);
    out.response.push_back(std::max(db.probes[j].response_error, kFloor) / pj);
  }
  return out;
}

double geometricMean(const std::vector<double>& v) {
  double sum = 0.0;
  for (const double x : v) sum += std::log(x);
  return std::exp(sum / static_cast<double>(v.size()));
}

}  // namespace

std::pair<double, double> pointErrorEstimate(const RomDatabase& db, const std::vector<double>& point) {
  if (db.probes.empty()) return {-1.0, -1.0};
  if (db.isGrid()) return probePointEstimate(db, point);
  const ScatteredScales s = scatteredScales(db, point);  // (4.14)
  if (s.response.empty()) return {-1.0, -1.0};
  return {s.power * geometricMean(s.frequency), s.power * geometricMean(s.response)};
}

std::pair<double, double> pointErrorUpperEstimate(const RomDatabase& db,
                                                  const std::vector<double>& point) {
  if (db.probes.empty()) return {-1.0, -1.0};
  if (db.isGrid()) return probePointEstimate(db, point);
  const ScatteredScales s = scatteredScales(db, point);  // e⁺ of (4.14)
  if (s.response.empty()) return {-1.0, -1.0};
  return {s.power * *std::max_element(s.frequency.begin(), s.frequency.end()),
          s.power * *std::max_element(s.response.begin(), s.response.end())};
}

}  // namespace mastrom::rom
