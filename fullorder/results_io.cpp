#include "fullorder/results_io.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "common/error.hpp"
#include "common/version.hpp"

namespace mastrom::fullorder {
namespace {

// One table per column kind maps the DeploymentSeries members onto the §5.3 datasets, so writing,
// checking and reading cannot drift apart.
struct ScalarColumn {
  const char* path;
  const char* units;
  std::vector<double> DeploymentSeries::*member;
};
struct VectorColumn {
  const char* path;
  const char* units;
  std::vector<Eigen::Vector3d> DeploymentSeries::*member;
};
struct MetricField {
  const char* name;
  double DeploymentMetrics::*member;
  /// May be absent: not available (NaN in memory; the file's not_available attribute says why).
  bool optional = false;
};

constexpr std::array<ScalarColumn, 7> kScalarColumns{{
    {"/time", "s", &DeploymentSeries::time_s},
    {"/drive/angle", "rad", &DeploymentSeries::drive_angle_rad},
    {"/drive/rate", "rad/s", &DeploymentSeries::drive_rate_rad_s},
    {"/drive/acceleration", "rad/s^2", &DeploymentSeries::drive_acceleration_rad_s2},
    {"/end/relative_angular_acceleration", "rad/s^2",
     &DeploymentSeries::end_relative_angular_acceleration_rad_s2},
    {"/joint/torque", "N*m", &DeploymentSeries::joint_torque_nm},
    {"/solver/constraint_residual", "1", &DeploymentSeries::constraint_residual},
}};
constexpr std::array<VectorColumn, 4> kVectorColumns{{
    {"/end/angular_acceleration", "rad/s^2", &DeploymentSeries::end_angular_acceleration_rad_s2},
    {"/end/position", "m", &DeploymentSeries::end_position_m},
    {"/end/acceleration", "m/s^2", &DeploymentSeries::end_acceleration_m_s2},
    {"/joint/force", "N", &DeploymentSeries::joint_force_n},
}};
constexpr const char* kIterationsPath = "/solver/newton_iterations";
constexpr const char* kTangentialPath = "/end/tangential_acceleration";

constexpr std::array<MetricField, 13> kMetricFields{{
    {"peak_abs_end_angular_acceleration", &DeploymentMetrics::peak_abs_end_angular_acceleration},
    {"peak_rel_end_angular_acceleration", &DeploymentMetrics::peak_rel_end_angular_acceleration},
    {"rms_rel_end_angular_acceleration", &DeploymentMetrics::rms_rel_end_angular_acceleration},
    {"residual_rel_end_angular_acceleration",
     &DeploymentMetrics::residual_rel_end_angular_acceleration, true},
    {"settling_time", &DeploymentMetrics::settling_time, true},
    {"estimated_nrmse_rel_end_angular_acceleration",
     &DeploymentMetrics::estimated_nrmse_rel_end_angular_acceleration, true},
    {"estimated_error_peak_rel_end_angular_acceleration",
     &DeploymentMetrics::estimated_error_peak_rel_end_angular_acceleration, true},
    {"estimated_error_peak_abs_end_angular_acceleration",
     &DeploymentMetrics::estimated_error_peak_abs_end_angular_acceleration, true},
    {"estimated_error_peak_joint_force", &DeploymentMetrics::estimated_error_peak_joint_force,
     true},
    {"peak_joint_force", &DeploymentMetrics::peak_joint_force},
    {"peak_drive_torque", &DeploymentMetrics::peak_drive_torque},
    {"drive_end_time", &DeploymentMetrics::drive_end_time},
    {"settling_band", &DeploymentMetrics::settling_band},
}};
constexpr const char* kSettledName = "settled";
constexpr const char* kNotAvailableName = "not_available";
constexpr const char* kPeaksName = "peaks_resolved";
constexpr const char* kMetricsGroup = "/metrics";
constexpr const char* kCompleteName = "complete";
constexpr std::array<const char*, 4> kRootAttributes{{"config", "mastrom_version", "source",
                                                      "wall_time_s"}};

/// NumericalError naming the dataset (or attribute), the index and the time of the first non-finite
/// value, so no NaN or infinity ever reaches a file.
void requireFinite(const std::string& file_path, const DeploymentSeries& series,
                   const DeploymentMetrics& metrics, double wall_time_s) {
  const auto fail = [&](const std::string& what, std::size_t i, double value) {
    throw NumericalError(detail::concat("refusing to write a non-finite value to '", file_path,
                                        "': ", what, " = ", value, " (t = ", series.time_s[i],
                                        " s)"));
  };
  for (const ScalarColumn& column : kScalarColumns) {
    const std::vector<double>& values = series.*column.member;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (!std::isfinite(values[i])) fail(detail::concat(column.path, "[", i, "]"), i, values[i]);
    }
  }
  for (const VectorColumn& column : kVectorColumns) {
    const std::vector<Eigen::Vector3d>& values = series.*column.member;
    for (std::size_t i = 0; i < values.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(values[i][k])) {
          fail(detail::concat(column.path, "[", i, ", ", k, "]"), i, values[i][k]);
        }
      }
    }
  }
  for (const MetricField& field : kMetricFields) {
    const double value = metrics.*field.member;
    MASTROM_REQUIRE(std::isfinite(value) || (field.optional && std::isnan(value)), NumericalError,
                    "refusing to write a non-finite value to '", file_path, "': ", kMetricsGroup,
                    " attribute ", field.name, " = ", value);
  }
  MASTROM_REQUIRE(std::isfinite(wall_time_s), NumericalError,
                  "refusing to write a non-finite value to '", file_path,
                  "': / attribute wall_time_s = ", wall_time_s);
}

}  // namespace

std::string toString(ResultSource source) {
  return source == ResultSource::FullOrder ? "full-order" : "rom";
}

std::optional<ResultSource> parseResultSource(std::string_view name) {
  if (name == "full-order") return ResultSource::FullOrder;
  if (name == "rom") return ResultSource::Rom;
  return std::nullopt;
}

void writeDeployment(h5::File& file, const DeploymentSeries& series,
                     const DeploymentMetrics& metrics, const std::string& resolved_config_toml,
                     double wall_time_s, ResultSource source) {
  series.checkConsistent();
  requireFinite(file.path(), series, metrics, wall_time_s);
  writeDeploymentSeries(file, "", series);
  writeDeploymentMetadata(file, metrics, resolved_config_toml, wall_time_s, source);
}

void writeDeploymentMetadata(h5::File& file, const DeploymentMetrics& metrics,
                             const std::string& resolved_config_toml, double wall_time_s,
                             ResultSource source) {
  requireFinite(file.path(), DeploymentSeries{}, metrics, wall_time_s);
  file.createGroup(kMetricsGroup);
  for (const MetricField& field : kMetricFields) {
    // A metric that is not available is left out, never written as NaN.
    if (std::isfinite(metrics.*field.member)) {
      file.setDoubleAttribute(kMetricsGroup, field.name, metrics.*field.member);
    }
  }
  file.setIntAttribute(kMetricsGroup, kSettledName, metrics.settled ? 1 : 0);
  if (!metrics.not_available.empty()) {
    file.setStringAttribute(kMetricsGroup, kNotAvailableName, metrics.not_available);
  }
  if (!metrics.peaks_resolved.empty()) {
    file.setStringAttribute(kMetricsGroup, kPeaksName, metrics.peaks_resolved);
  }

  file.setStringAttribute("/", "config", resolved_config_toml);
  file.setStringAttribute("/", "mastrom_version", kVersion);
  file.setStringAttribute("/", "source", toString(source));
  file.setDoubleAttribute("/", "wall_time_s", wall_time_s);
  file.setIntAttribute("/", kCompleteName, 1);
}

void markIncomplete(h5::File& file, double stopped_at_s) {
  file.setIntAttribute("/", kCompleteName, 0);
  file.setDoubleAttribute("/", "stopped_at_s", stopped_at_s);
}

void writeDeploymentSeries(h5::File& file, const std::string& group,
                           const DeploymentSeries& series) {
  series.checkConsistent();
  requireFinite(file.path(), series, DeploymentMetrics{}, 0.0);
  for (const ScalarColumn& column : kScalarColumns) {
    file.writeDoubles(group + column.path, series.*column.member, column.units);
  }
  for (const VectorColumn& column : kVectorColumns) {
    file.writeMatrix(group + column.path, series.*column.member, column.units);
  }
  file.writeInts(group + kIterationsPath, series.newton_iterations, "1");
  // Derived from /end/position and /end/acceleration (so not read back): the accelerometer's signal.
  file.writeDoubles(group + kTangentialPath, series.endTangentialAccelerations(), "m/s^2");
}

SeriesAppender::SeriesAppender(h5::File& file, std::size_t chunk_rows) : file_path_(file.path()) {
  for (const ScalarColumn& column : kScalarColumns)
    scalars_.emplace_back(file, column.path, h5::AppendType::Double, 0, chunk_rows, column.units);
  for (const VectorColumn& column : kVectorColumns)
    vectors_.emplace_back(file, column.path, h5::AppendType::Double, 3, chunk_rows, column.units);
  iterations_ =
      h5::AppendableDataset(file, kIterationsPath, h5::AppendType::Int32, 0, chunk_rows, "1");
  tangential_ =
      h5::AppendableDataset(file, kTangentialPath, h5::AppendType::Double, 0, chunk_rows, "m/s^2");
}

void SeriesAppender::append(const DeploymentSeries& rows) {
  rows.checkConsistent();
  requireFinite(file_path_, rows, DeploymentMetrics{}, 0.0);
  const std::size_t n = rows.size();
  for (std::size_t c = 0; c < kScalarColumns.size(); ++c)
    scalars_[c].append((rows.*kScalarColumns[c].member).data(), n);
  for (std::size_t c = 0; c < kVectorColumns.size(); ++c) {
    // Eigen::Vector3d is three packed doubles: the column is row-major [n, 3] already.
    static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double));
    vectors_[c].append((rows.*kVectorColumns[c].member).data(), n);
  }
  iterations_.append(rows.newton_iterations.data(), n);
  const std::vector<double> tangential = rows.endTangentialAccelerations();
  tangential_.append(tangential.data(), n);
  rows_ += n;
}

void SeriesAppender::close() {
  for (h5::AppendableDataset& d : scalars_) d.close();
  for (h5::AppendableDataset& d : vectors_) d.close();
  iterations_.close();
  tangential_.close();
}

DeploymentSeries readDeploymentSeries(const h5::File& file, const std::string& group) {
  const std::string& path = file.path();
  const std::string time_path = group + "/time";
  MASTROM_REQUIRE(file.exists(time_path), IoError, "'", path, "': missing ", time_path);
  DeploymentSeries series;
  const std::vector<std::size_t> time_shape = file.datasetShape(time_path);
  MASTROM_REQUIRE(time_shape.size() == 1, IoError, "'", path, "': ", time_path, " has rank ",
                  time_shape.size(), ", expected 1");
  const std::size_t n = time_shape[0];
  const auto requireLength = [&](const std::string& dataset, std::size_t length) {
    MASTROM_REQUIRE(length == n, IoError, "'", path, "': ", dataset, " has ", length,
                    " rows, ", time_path, " has ", n);
  };
  for (const ScalarColumn& column : kScalarColumns) {
    series.*column.member = file.readDoubles(group + column.path);
    requireLength(group + column.path, (series.*column.member).size());
  }
  for (const VectorColumn& column : kVectorColumns) {
    const Eigen::MatrixXd matrix = file.readMatrix(group + column.path);
    MASTROM_REQUIRE(matrix.cols() == 3, IoError, "'", path, "': ", group + column.path, " has ",
                    matrix.cols(), " columns, expected 3");
    requireLength(group + column.path, static_cast<std::size_t>(matrix.rows()));
    std::vector<Eigen::Vector3d>& rows = series.*column.member;
    rows.resize(static_cast<std::size_t>(matrix.rows()));
    for (Eigen::Index i = 0; i < matrix.rows(); ++i) {
      rows[static_cast<std::size_t>(i)] = matrix.row(i).transpose();
    }
  }
  series.newton_iterations = file.readInts(group + kIterationsPath);
  requireLength(group + kIterationsPath, series.newton_iterations.size());
  try {
    series.checkConsistent();
  } catch (const UsageError& e) {
    throw IoError(detail::concat("'", path, "': ", e.what()));
  }
  return series;
}

DeploymentSeries readDeploymentSeriesRows(const h5::File& file, std::size_t first,
                                          std::size_t count) {
  DeploymentSeries rows;
  for (const ScalarColumn& column : kScalarColumns) {
    std::vector<double>& values = rows.*column.member;
    values.resize(count);
    h5::readRows(file, column.path, h5::AppendType::Double, 0, first, count, values.data());
  }
  for (const VectorColumn& column : kVectorColumns) {
    std::vector<Eigen::Vector3d>& values = rows.*column.member;
    values.resize(count);
    static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double));  // row-major [count, 3]
    h5::readRows(file, column.path, h5::AppendType::Double, 3, first, count, values.data());
  }
  rows.newton_iterations.resize(count);
  static_assert(sizeof(int) == sizeof(std::int32_t));
  h5::readRows(file, kIterationsPath, h5::AppendType::Int32, 0, first, count,
               rows.newton_iterations.data());
  return rows;
}

void writeDeploymentFile(const std::string& path, const DeploymentSeries& series,
                         const DeploymentMetrics& metrics, const std::string& resolved_config_toml,
                         double wall_time_s, ResultSource source) {
  // Check everything before creating a file: a refused result leaves no trace on disk.
  series.checkConsistent();
  requireFinite(path, series, metrics, wall_time_s);
  h5::AtomicH5Writer writer(path);
  writeDeployment(writer.file(), series, metrics, resolved_config_toml, wall_time_s, source);
  writer.commit();
}

DeploymentFile readDeploymentFile(const std::string& path) {
  const h5::File file = h5::File::open(path, h5::OpenMode::ReadOnly);

  // A foreign file: say what is missing at once (the first few, so the message stays one line).
  constexpr std::size_t kListed = 6;
  std::string missing;
  std::size_t missing_count = 0;
  const auto note = [&](const std::string& what) {
    if (missing_count++ < kListed) missing += (missing.empty() ? "" : ", ") + what;
  };
  for (const ScalarColumn& column : kScalarColumns) {
    if (!file.exists(column.path)) note(column.path);
  }
  for (const VectorColumn& column : kVectorColumns) {
    if (!file.exists(column.path)) note(column.path);
  }
  if (!file.exists(kIterationsPath)) note(kIterationsPath);
  // An optional metric may be absent: the estimates always, the others only where the file's
  // not_available attribute names them.
  const std::string not_available = file.hasAttribute(kMetricsGroup, kNotAvailableName)
                                        ? file.readStringAttribute(kMetricsGroup, kNotAvailableName)
                                        : std::string();
  for (const MetricField& field : kMetricFields) {
    const bool may_be_absent =
        field.optional && (std::string_view(field.name).rfind("estimated_", 0) == 0 ||
                           not_available.find(field.name) != std::string::npos);
    if (!may_be_absent && !file.hasAttribute(kMetricsGroup, field.name)) {
      note(std::string(kMetricsGroup) + " attribute " + field.name);
    }
  }
  if (!file.hasAttribute(kMetricsGroup, kSettledName)) {
    note(std::string(kMetricsGroup) + " attribute " + kSettledName);
  }
  for (const char* name : kRootAttributes) {
    if (!file.hasAttribute("/", name)) note(std::string("/ attribute ") + name);
  }
  if (missing_count > kListed) {
    missing += detail::concat(" and ", missing_count - kListed, " more");
  }
  MASTROM_REQUIRE(missing_count == 0, IoError, "'", path,
                  "' is not a mastrom deployment file: missing ", missing);

  DeploymentFile result;
  result.series = readDeploymentSeries(file, "");

  for (const MetricField& field : kMetricFields) {
    result.metrics.*field.member = file.hasAttribute(kMetricsGroup, field.name)
                                       ? file.readDoubleAttribute(kMetricsGroup, field.name)
                                       : std::numeric_limits<double>::quiet_NaN();
  }
  result.metrics.settled = file.readIntAttribute(kMetricsGroup, kSettledName) != 0;
  if (file.hasAttribute(kMetricsGroup, kNotAvailableName)) {
    result.metrics.not_available = file.readStringAttribute(kMetricsGroup, kNotAvailableName);
  }
  if (file.hasAttribute(kMetricsGroup, kPeaksName)) {
    result.metrics.peaks_resolved = file.readStringAttribute(kMetricsGroup, kPeaksName);
  }

  result.config_toml = file.readStringAttribute("/", "config");
  result.mastrom_version = file.readStringAttribute("/", "mastrom_version");
  const std::string source = file.readStringAttribute("/", "source");
  const std::optional<ResultSource> parsed = parseResultSource(source);
  MASTROM_REQUIRE(parsed.has_value(), IoError, "'", path, "': root attribute source = '", source,
                  "'; allowed: full-order, rom");
  result.source = *parsed;
  result.wall_time_s = file.readDoubleAttribute("/", "wall_time_s");
  result.complete =
      !file.hasAttribute("/", kCompleteName) || file.readIntAttribute("/", kCompleteName) != 0;
  return result;
}

}  // namespace mastrom::fullorder
