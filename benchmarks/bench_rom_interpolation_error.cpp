// The interpolation error of a ROM database at random held-out points, against what its own
// estimate says there (benchmarks/README.md "Scattered samples and adaptive sampling"). Per point
// (uniform in the box, seeded as `mastrom validate` draws them): the modal model interpolated by
// METHOD and the one of a direct modal solve at that point (rom/offline/direct_modal_model.hpp), each
// deployed by the ROM with the database's base drive; the NRMSE of the relative end angular
// acceleration between them (the interpolation error alone, which the database's estimate
// estimates), the error of ω₁, the database's estimate at the point where it has held-out probes
// ((4.13) on a grid, (4.14) and its upper value (4.14′) scattered:
// rom/interpolation/point_error_estimate.hpp), and for the
// rbf method the leave-one-out estimate (rom/offline/rbf_leave_one_out.hpp; with Young's modulus
// handled exactly, in the space of the sampled axes). Also the interpolation time per evaluation.
//
//   bench_rom_interpolation_error DB.h5 POINTS [METHOD] [SEED]
//   (METHOD "rbf2": the rbf method with a quadratic polynomial tail, RadialBasisWeights)
//   → one line per point, then "max_nrmse … max_estimate … interpolation_us …" (median of 201
//     evaluations at one point)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "fullorder/mast_config.hpp"
#include "modes/slepc_session.hpp"
#include "rom/database/database_io.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/point_error_estimate.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/interpolation/tracked_interpolation.hpp"
#include "rom/offline/direct_modal_model.hpp"
#include "rom/offline/leave_one_out.hpp"
#include "rom/offline/rbf_leave_one_out.hpp"
#include "rom/offline/sample_solve.hpp"
#include "rom/studies/validation.hpp"

int main(int argc, char** argv) {
  using namespace mastrom;
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_rom_interpolation_error DB.h5 POINTS [METHOD] [SEED]\n");
    return 2;
  }
  const modes::SlepcSession session(&argc, &argv);
  const rom::RomDatabase db = rom::readDatabase(argv[1]);
  const int count = std::max(1, std::atoi(argv[2]));
  const bool quadratic_tail = argc > 3 && std::string(argv[3]) == "rbf2";
  const rom::InterpolationMethod method = rom::interpolationMethodOr(
      argc > 3 && !quadratic_tail ? argv[3] : (quadratic_tail ? "rbf" : ""), db.default_method,
      "METHOD");
  const std::uint64_t seed = argc > 4 ? std::strtoull(argv[4], nullptr, 10) : 1;
  const Config base = parseConfigText(db.base_config_toml, "database");
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(base));
  const rom::ModalDeploymentOptions deploy = rom::deploymentOptionsFromConfig(base);
  // With Young's modulus handled exactly the samples span the other axes only (sampled): the
  // estimate lives there, and a point drops its E before it is estimated.
  const rom::RomDatabase sampled = rom::sampledDatabase(db);
  const int exact_axis = db.exactModulusAxis();
  const auto inSampledSpace = [exact_axis](std::vector<double> p) {
    if (exact_axis >= 0) p.erase(p.begin() + exact_axis);
    return p;
  };
  const std::unique_ptr<rom::ModalInterpolator> interpolator =
      quadratic_tail ? rom::withExactModulus(db, rom::TrackedInterpolator::radialBasis(sampled, 2))
                     : rom::makeInterpolator(db, method);
  std::unique_ptr<rom::RadialBasisErrorEstimate> estimate;
  if (method == rom::InterpolationMethod::Rbf) {
    // Timed: every sample's own and left-out model deployed (an adaptive build's first round).
    rom::LeaveOneOutCache cache;
    const auto start = std::chrono::steady_clock::now();
    rom::LeftOutErrors errors = rom::radialBasisLeaveOneOut(sampled, drive, deploy, cache);
    std::printf("leave-one-out of %zu samples: %.3f s (%d deployed)\n", db.samples.size(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                cache.deployed);
    estimate = std::make_unique<rom::RadialBasisErrorEstimate>(sampled, std::move(errors));
    // The estimate over the build's candidates: the corners apart from the Halton points.
    const int p = static_cast<int>(sampled.axes.size());
    std::vector<double> corners, inner;
    for (const std::vector<double>& c : rom::estimateCandidates(
             sampled.axes, rom::kCandidatesPerParameter * p, 2L * p + 1)) {
      bool corner = true;
      for (std::size_t a = 0; a < c.size(); ++a)
        corner = corner && (c[a] == sampled.axes[a].values.front() ||
                            c[a] == sampled.axes[a].values.back());
      (corner ? corners : inner).push_back(estimate->at(c).second);
    }
    std::sort(inner.begin(), inner.end());
    const auto quantile = [&inner](double q) {
      return inner[static_cast<std::size_t>(q * static_cast<double>(inner.size() - 1))];
    };
    std::printf("estimate over %zu Halton candidates: median %.3g %%, 90 %% %.3g %%, 95 %% %.3g %%, "
                "max %.3g %%; over the %zu corners max %.3g %%\n",
                inner.size(), 100 * quantile(0.5), 100 * quantile(0.9), 100 * quantile(0.95),
                100 * inner.back(), corners.size(),
                corners.empty() ? 0.0 : 100 * *std::max_element(corners.begin(), corners.end()));
  }
  std::printf("%s: %zu samples, method %s, %d points (seed %llu)\n", argv[1], db.samples.size(),
              rom::toString(method).c_str(), count, static_cast<unsigned long long>(seed));
  double max_nrmse = 0.0, max_estimate = 0.0, interpolation_s = 0.0;
  for (const std::vector<double>& p : rom::validationPoints(db, count, seed)) {
    const Config at = rom::applyOverrides(base, rom::parameterOverrides(db.axes, p));
    const auto start = std::chrono::steady_clock::now();
    const rom::ModalModel interpolated = interpolator->evaluate(p);
    interpolation_s +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const rom::ModalModel direct = rom::directModalModel(at, db.modes_per_sample);
    const double nrmse =
        rom::responseNrmse(rom::relativeAccelerationSeries(direct, drive, deploy),
                           rom::relativeAccelerationSeries(interpolated, drive, deploy));
    const double w = direct.omega_rad_s.minCoeff();
    const double frequency = std::abs(interpolated.omega_rad_s.minCoeff() - w) / w;
    // The database's default with probes: (4.13) on a grid, (4.14) scattered; rbf also the
    // leave-one-out product (4.11).
    const double est =
        method == db.default_method ? rom::pointErrorEstimate(db, p).second : -1.0;
    const double inferred = estimate ? estimate->at(inSampledSpace(p)).second : -1.0;
    max_nrmse = std::max(max_nrmse, nrmse);
    max_estimate = std::max(max_estimate, est);
    std::printf("  %s: nrmse %.4g %%  omega_1 %.3g %%  estimate %.4g %% (ratio %.3g)",
                rom::describePoint(db.axes, p).c_str(), 100 * nrmse, 100 * frequency, 100 * est,
                est / nrmse);
    if (!db.isGrid() && est >= 0)
      std::printf("  upper %.4g %% (ratio %.3g)", 100 * rom::pointErrorUpperEstimate(db, p).second,
                  rom::pointErrorUpperEstimate(db, p).second / nrmse);
    if (inferred >= 0) std::printf("  leave-one-out estimate %.4g %%", 100 * inferred);
    std::printf("\n");
    std::fflush(stdout);
  }
  // Interpolation alone, repeated at the first point (the per-point times above include the
  // first touch of the database's arrays).
  const std::vector<double> first = rom::validationPoints(db, 1, seed).front();
  std::vector<double> times;
  for (int r = 0; r < 201; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const rom::ModalModel m = interpolator->evaluate(first);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (m.modeCount() == 0) return 1;
  }
  std::sort(times.begin(), times.end());
  const auto [file_f, file_r] = rom::databaseErrorEstimate(db);
  std::printf("max_nrmse %.4g %% max_estimate_at_points %.4g %% database_estimate %.4g %% "
              "(omega_1 %.3g %%) interpolation_us %.1f (median of 201 repeats; %.1f first calls)\n",
              100 * max_nrmse, 100 * max_estimate, 100 * file_r, 100 * file_f,
              1e6 * times[times.size() / 2], 1e6 * interpolation_s / count);
  return 0;
}
