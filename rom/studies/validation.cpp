#include "rom/studies/validation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <random>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "common/version.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/deployment_accuracy.hpp"
#include "fullorder/mast_config.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"
#include "rom/database/h5_arrays.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/interpolation/point_error_estimate.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/offline/locked_modal_solve.hpp"
#include "rom/offline/mpi_gather.hpp"

namespace mastrom::rom {
namespace {

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

/// Everything one point needs; the point's record is [index, p…, errors…, f-error, walls].
std::vector<double> validateOnePoint(const RomDatabase& db, const ModalInterpolator& interpolator,
                                     const Config& evaluation, const DesignDescriber& describer,
                                     int index, const std::vector<double>& p) {
  const Config config = applyOverrides(evaluation, parameterOverrides(db.axes, p));
  fullorder::MastModel model =
      fullorder::buildMast(fullorder::mastParametersFromConfig(config));
  const fullorder::DeploymentOptions options = fullorder::deploymentFromConfig(config);
  const auto t_full = std::chrono::steady_clock::now();
  fullorder::DeploymentStatistics stats;
  const fullorder::DeploymentSeries full = fullorder::simulateDeployment(model, options, &stats);
  const double full_wall = seconds(t_full);
  fullorder::DeploymentMetrics full_metrics =
      fullorder::fullOrderMetrics(full, stats, config.drive.duration_s);
  // The reference's own discretisation error, so that a disagreement can be told apart (adaptive
  // steps only; NaN for fixed steps). Not counted in the full order's wall time.
  if (options.adaptive) fullorder::estimateDiscretisationError(model, options, full, full_metrics);

  const auto t_rom = std::chrono::steady_clock::now();
  const ModalModel mm = interpolator.evaluate(p);
  const ModalDeploymentOptions ro = deploymentOptionsFromConfig(config);
  const fullorder::DriveLaw rom_drive(fullorder::driveFromConfig(config));
  const fullorder::DeploymentSeries rom = simulateModalDeployment(mm, rom_drive, ro);
  // What a user pays for the ROM's answer: the interpolation and one deployment (the second run
  // below only resolves the peaks for the comparison, as the full order's estimate is not timed).
  const double rom_wall = seconds(t_rom);
  // Peaks of the continuous response, as the full order's (fullOrderMetrics): sampled on the
  // output grid, the ROM's peak of a kHz ringing read up to 6 % low on Scheme 3.
  const fullorder::DeploymentMetrics rom_metrics =
      modalDeploymentMetrics(mm, rom_drive, ro, config.drive.duration_s);

  // Direct modal solve at the point: the first-frequency reference.
  const LockedModalSolve direct =
      solveLockedMast(config, std::min(std::max(4, describer.frequencies()), db.modes_per_sample),
                      0, config.modes.backend, detail::concat("validate: point ", index));
  const double f_direct = direct.eigen.frequencies_hz[0];
  const double f_rom = mm.omega_rad_s[0] / (2.0 * M_PI);

  const DeploymentComparison c = compareDeployments(full, full_metrics, rom, rom_metrics);
  std::vector<double> record{static_cast<double>(index)};
  record.insert(record.end(), p.begin(), p.end());
  const std::vector<double> errors = c.values();
  record.insert(record.end(), errors.begin(), errors.end());
  record.push_back(std::abs(f_rom - f_direct) / f_direct);
  record.push_back(full_wall);
  record.push_back(rom_wall);
  record.push_back(full_metrics.estimated_nrmse_rel_end_angular_acceleration);

  // The design: its mass, and its frequencies at the deployed angle from the ROM (with the
  // database's estimate) and from a direct solve there (the one above when the angle is θ₀ or
  // does not matter: no gravity in the plane of the turn).
  DesignValues design;
  describer.describe(interpolator, mm, p, 0, design);
  record.push_back(design.mass.total_kg);
  const int n = describer.frequencies();
  if (n > 0) {
    const bool turned =
        (config.simulation.gravity_m_s2[0] != 0.0 || config.simulation.gravity_m_s2[1] != 0.0) &&
        config.modes.angle_deg != config.drive.angle_deg;
    std::optional<LockedModalSolve> deployed;
    if (turned)
      deployed = solveLockedMast(
          applyOverrides(config, {formatOverride("modes.angle_deg", config.drive.angle_deg)}), n, 0,
          config.modes.backend,
          detail::concat("validate: point ", index, " at the deployed angle"));
    const Eigen::VectorXd& f =
        turned ? deployed->eigen.frequencies_hz : direct.eigen.frequencies_hz;
    for (int k = 0; k < n; ++k) {
      record.push_back(design.frequency_hz[static_cast<std::size_t>(k)]);
      record.push_back(design.frequency_error[static_cast<std::size_t>(k)]);
      record.push_back(k < f.size() ? f[k] : -1.0);
    }
  }
  return record;
}

}  // namespace

double ValidationReport::worst() const {
  double w = 0.0;
  for (const ValidationPoint& p : points)
    w = std::max({w, p.errors.worst(), p.first_frequency_error});
  return w;
}

std::vector<std::vector<double>> validationPoints(const RomDatabase& db, int count,
                                                  std::uint64_t seed) {
  MASTROM_REQUIRE(count >= 1, InputError, "validate: --points = ", count, " must be >= 1");
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<double>> points(static_cast<std::size_t>(count));
  for (auto& p : points)
    for (const ParameterAxis& axis : db.axes)
      p.push_back(axis.values.front() + unit(gen) * (axis.values.back() - axis.values.front()));
  return points;
}

ValidationReport runValidation(const RomDatabase& db, const ValidationOptions& options,
                               const std::function<void(int, int)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  int rank = 0, size = 1;
  communicatorRankSize(options.communicator, rank, size);
  const std::vector<std::vector<double>> points = validationPoints(db, options.points, options.seed);
  const Config evaluation = evaluationConfig(db, options.overrides);
  const std::unique_ptr<ModalInterpolator> interpolator = makeInterpolator(db, options.method);
  // The free keys are common to every point, so one deployed angle.
  const DesignDescriber describer(db, evaluation, options.frequencies, {evaluation.drive.angle_deg},
                                  BoxPolicy::Refuse);

  std::vector<double> local;
  std::string error;
  bool numerical = false;
  try {
    int done = 0;
    for (int i = rank; i < options.points; i += size) {
      const std::vector<double> record = validateOnePoint(db, *interpolator, evaluation, describer,
                                                          i, points[static_cast<std::size_t>(i)]);
      local.insert(local.end(), record.begin(), record.end());
      ++done;
      if (progress && rank == 0) progress(done * size, options.points);
    }
  } catch (const NumericalError& e) {
    error = e.what();
    numerical = true;
  } catch (const Error& e) {
    error = e.what();
  }
  throwIfAnyRankFailed(options.communicator, error, numerical);
  const std::vector<double> all = gatherToRoot(options.communicator, local);

  ValidationReport report;
  for (const ParameterAxis& axis : db.axes) report.parameter_names.push_back(axis.key);
  report.config_toml = toToml(evaluation);
  report.frequencies = describer.frequencies();
  report.no_frequency_reason = describer.columns(0, false).no_frequency_reason;
  if (rank != 0) return report;
  const std::size_t p = db.axes.size(), q = DeploymentComparison::names().size();
  const auto n_f = static_cast<std::size_t>(report.frequencies);
  const std::size_t width = 1 + p + q + 4 + 1 + 3 * n_f;
  MASTROM_REQUIRE(all.size() == width * static_cast<std::size_t>(options.points), NumericalError,
                  "validate: gathered ", all.size(), " values, expected ",
                  width * static_cast<std::size_t>(options.points));
  report.points.resize(static_cast<std::size_t>(options.points));
  for (std::size_t r = 0; r < all.size(); r += width) {
    ValidationPoint& vp = report.points[static_cast<std::size_t>(all[r])];
    vp.parameters.assign(all.begin() + static_cast<long>(r + 1),
                         all.begin() + static_cast<long>(r + 1 + p));
    const double* e = &all[r + 1 + p];
    vp.errors.nrmse_relative_acceleration = e[0];
    vp.errors.peak_abs_error = e[1];
    vp.errors.peak_rel_error = e[2];
    vp.errors.rms_rel_error = e[3];
    vp.errors.residual_error = e[4];
    vp.errors.peak_force_error = e[5];
    vp.errors.peak_torque_error = e[6];
    vp.first_frequency_error = all[r + 1 + p + q];
    vp.full_wall_s = all[r + 2 + p + q];
    vp.rom_wall_s = all[r + 3 + p + q];
    vp.full_estimated_nrmse = all[r + 4 + p + q];
    vp.mass_kg = all[r + 5 + p + q];
    for (std::size_t k = 0; k < n_f; ++k) {
      vp.frequency_hz.push_back(all[r + 6 + p + q + 3 * k]);
      vp.frequency_error_estimate.push_back(all[r + 7 + p + q + 3 * k]);
      vp.frequency_direct_hz.push_back(all[r + 8 + p + q + 3 * k]);
    }
    // The database's own estimate at the point, where it has one for the method validated.
    if (options.method == db.default_method)
      vp.rom_estimated_nrmse = pointErrorEstimate(db, vp.parameters).second;
  }
  report.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

void writeValidationFile(const std::string& path, const ValidationReport& report,
                         const ValidationOptions& options) {
  const std::size_t n = report.points.size(), p = report.parameter_names.size();
  const std::vector<std::string> error_names = DeploymentComparison::names();
  std::vector<double> params, errors, f_err, full_wall, rom_wall, full_estimate, rom_estimate;
  std::vector<double> mass, frequency, frequency_estimate, frequency_direct;
  for (const ValidationPoint& vp : report.points) {
    params.insert(params.end(), vp.parameters.begin(), vp.parameters.end());
    const std::vector<double> e = vp.errors.values();
    errors.insert(errors.end(), e.begin(), e.end());
    f_err.push_back(vp.first_frequency_error);
    full_wall.push_back(vp.full_wall_s);
    // -1: not estimated (fixed steps): files never hold NaN.
    full_estimate.push_back(std::isfinite(vp.full_estimated_nrmse) ? vp.full_estimated_nrmse
                                                                   : -1.0);
    rom_wall.push_back(vp.rom_wall_s);
    rom_estimate.push_back(vp.rom_estimated_nrmse);
    mass.push_back(vp.mass_kg);
    frequency.insert(frequency.end(), vp.frequency_hz.begin(), vp.frequency_hz.end());
    frequency_estimate.insert(frequency_estimate.end(), vp.frequency_error_estimate.begin(),
                              vp.frequency_error_estimate.end());
    frequency_direct.insert(frequency_direct.end(), vp.frequency_direct_hz.begin(),
                            vp.frequency_direct_hz.end());
  }
  const auto n_f = static_cast<std::size_t>(report.frequencies);
  h5::AtomicH5Writer writer(path);
  h5::File& f = writer.file();
  f.createGroup("/validation");
  h5x::writeStrings(f, "/validation/parameter_names", report.parameter_names);
  h5x::writeDoubles(f, "/validation/parameters", {n, p}, params.data(), "SI (see names)");
  h5x::writeStrings(f, "/validation/error_names", error_names);
  h5x::writeDoubles(f, "/validation/errors", {n, error_names.size()}, errors.data(), "1");
  h5x::writeDoubles(f, "/validation/first_frequency_error", {n}, f_err.data(), "1");
  h5x::writeDoubles(f, "/validation/full_wall_time", {n}, full_wall.data(), "s");
  h5x::writeDoubles(f, "/validation/rom_wall_time", {n}, rom_wall.data(), "s");
  h5x::writeDoubles(f, "/validation/rom_estimated_nrmse", {n}, rom_estimate.data(), "1 (-1: none)");
  h5x::writeDoubles(f, "/validation/full_order_estimated_nrmse", {n}, full_estimate.data(), "1");
  h5x::writeDoubles(f, "/validation/mass", {n}, mass.data(), "kg");
  if (n_f > 0) {
    h5x::writeDoubles(f, "/validation/frequencies", {n, n_f}, frequency.data(), "Hz");
    h5x::writeDoubles(f, "/validation/frequency_error_estimate", {n, n_f},
                      frequency_estimate.data(), "1 (-1: none)");
    h5x::writeDoubles(f, "/validation/frequencies_direct", {n, n_f}, frequency_direct.data(), "Hz");
  }
  f.setStringAttribute("/", "source", "validation");
  f.setStringAttribute("/", "config", report.config_toml);
  f.setStringAttribute("/", "mastrom_version", kVersion);
  f.setStringAttribute("/", "method", toString(options.method));
  f.setDoubleAttribute("/", "seed", static_cast<double>(options.seed));
  f.setDoubleAttribute("/", "worst_error", report.worst());
  f.setDoubleAttribute("/", "wall_time_s", report.wall_s);
  writer.commit();
}

}  // namespace mastrom::rom
