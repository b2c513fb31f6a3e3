#include "fullorder/checkpoint.hpp"

#include <array>
#include <climits>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "common/version.hpp"
#include "fullorder/results_io.hpp"

namespace mastrom::fullorder {
namespace {

constexpr const char* kFormat = "mastrom-checkpoint";
// Version 2: adds the predictor's previous (q̈, λ); version 3: which solver factorised
// the iteration matrix (FactorizationInputs::general_lu). An older file cannot continue bit for bit
// and is refused.
// 4: step sizes and the adaptive step controller; 5: its noise floor and growth barrier; 6: its
// velocity criterion (peak vibration velocity and noise floor); 7: streamed runs (the last
// output, the count streamed and the file holding them); 8: streamed adaptive runs (the
// continuous response's window and peaks, /stream).
constexpr int kFormatVersion = 8;
constexpr const char* kSeriesGroup = "/series";
constexpr const char* kStatisticsGroup = "/statistics";
constexpr const char* kStateGroup = "/integrator/state";
constexpr const char* kIterationGroup = "/integrator/iteration_factor";
constexpr const char* kMassGroup = "/integrator/mass_factor";
constexpr const char* kSpareGroup = "/integrator/spare_iteration_factor";
constexpr const char* kControllerGroup = "/step_control";
constexpr const char* kStreamGroup = "/stream";
constexpr const char* kStreamWindowGroup = "/stream/window";
// Generalized coordinates mix positions [m], NCF direction vectors [1] and multipliers [N, N*m].
constexpr const char* kGeneralizedUnits = "SI, per generalized coordinate";

int toIntAttribute(long long value, const char* name) {
  MASTROM_REQUIRE(value >= INT_MIN && value <= INT_MAX, IoError, "checkpoint: ", name, " = ", value,
                  " does not fit a 32-bit attribute");
  return static_cast<int>(value);
}

void writeVector(h5::File& file, const std::string& path, const Eigen::VectorXd& v) {
  file.writeDoubles(path, std::vector<double>(v.data(), v.data() + v.size()), kGeneralizedUnits);
}

Eigen::VectorXd readVector(const h5::File& file, const std::string& path) {
  const std::vector<double> values = file.readDoubles(path);
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

void writeFactorization(h5::File& file, const std::string& group, const FactorizationInputs& f) {
  file.createGroup(group);
  file.setIntAttribute(group, "valid", f.valid ? 1 : 0);
  file.setDoubleAttribute(group, "time_s", f.time_s);
  file.setDoubleAttribute(group, "c_mass", f.coefficients.mass);
  file.setDoubleAttribute(group, "c_damping", f.coefficients.damping);
  file.setDoubleAttribute(group, "c_stiffness", f.coefficients.stiffness);
  file.setDoubleAttribute(group, "c_constraint", f.coefficients.constraint_scale);
  file.setIntAttribute(group, "general_lu", f.general_lu ? 1 : 0);
  if (!f.valid) return;
  writeVector(file, group + "/q", f.q);
  writeVector(file, group + "/qdot", f.qdot);
  writeVector(file, group + "/lambda", f.lambda);
}

FactorizationInputs readFactorization(const h5::File& file, const std::string& group) {
  FactorizationInputs f;
  f.valid = file.readIntAttribute(group, "valid") != 0;
  f.time_s = file.readDoubleAttribute(group, "time_s");
  f.coefficients.mass = file.readDoubleAttribute(group, "c_mass");
  f.coefficients.damping = file.readDoubleAttribute(group, "c_damping");
  f.coefficients.stiffness = file.readDoubleAttribute(group, "c_stiffness");
  f.coefficients.constraint_scale = file.readDoubleAttribute(group, "c_constraint");
  f.general_lu = file.readIntAttribute(group, "general_lu") != 0;
  if (!f.valid) return f;
  f.q = readVector(file, group + "/q");
  f.qdot = readVector(file, group + "/qdot");
  f.lambda = readVector(file, group + "/lambda");
  return f;
}

// The peaks of the continuous response (fullorder/continuous_response.hpp), as attributes.
constexpr const char* kPeakNames[] = {"abs_end_angular_acceleration",
                                      "rel_end_angular_acceleration",
                                      "residual_rel_end_angular_acceleration",
                                      "joint_force",
                                      "drive_torque",
                                      "square_rel_integral",
                                      "square_span_s"};

std::array<double*, 7> peakFields(ContinuousPeaks& p) {
  return {&p.abs_end_angular_acceleration,
          &p.rel_end_angular_acceleration,
          &p.residual_rel_end_angular_acceleration,
          &p.joint_force,
          &p.drive_torque,
          &p.square_rel_integral,
          &p.square_span_s};
}

/// A streamed adaptive run's StepPointStream state and piece start times (absent otherwise).
void writeStreamState(h5::File& file, const DeploymentCheckpoint& checkpoint) {
  const StepPointStream::State& stream = checkpoint.stream;
  if (stream.points == 0) return;
  file.createGroup(kStreamGroup);
  file.setIntAttribute(kStreamGroup, "points",
                       toIntAttribute(static_cast<long long>(stream.points), "points"));
  file.setIntAttribute(kStreamGroup, "piece_points",
                       toIntAttribute(stream.piece_points, "piece_points"));
  file.setIntAttribute(kStreamGroup, "next_interval",
                       toIntAttribute(stream.next_interval, "next_interval"));
  file.setIntAttribute(kStreamGroup, "next_output",
                       toIntAttribute(stream.next_output, "next_output"));
  file.setDoubleAttribute(kStreamGroup, "first_time_s", stream.first_time_s);
  ContinuousPeaks peaks = stream.peaks;
  const auto fields = peakFields(peaks);
  for (std::size_t k = 0; k < fields.size(); ++k)
    file.setDoubleAttribute(kStreamGroup, kPeakNames[k], *fields[k]);
  file.writeDoubles(std::string(kStreamGroup) + "/piece_start_times",
                    checkpoint.piece_start_times_s, "s");
  writeDeploymentSeries(file, kStreamWindowGroup, stream.window);
}

void readStreamState(const h5::File& file, DeploymentCheckpoint& checkpoint) {
  if (!file.exists(kStreamGroup)) return;
  StepPointStream::State& stream = checkpoint.stream;
  stream.points = static_cast<std::size_t>(file.readIntAttribute(kStreamGroup, "points"));
  stream.piece_points = file.readIntAttribute(kStreamGroup, "piece_points");
  stream.next_interval = file.readIntAttribute(kStreamGroup, "next_interval");
  stream.next_output = file.readIntAttribute(kStreamGroup, "next_output");
  stream.first_time_s = file.readDoubleAttribute(kStreamGroup, "first_time_s");
  const auto fields = peakFields(stream.peaks);
  for (std::size_t k = 0; k < fields.size(); ++k)
    *fields[k] = file.readDoubleAttribute(kStreamGroup, kPeakNames[k]);
  checkpoint.piece_start_times_s =
      file.readDoubles(std::string(kStreamGroup) + "/piece_start_times");
  stream.window = readDeploymentSeries(file, kStreamWindowGroup);
}

/// "section.key = value" lines of a toToml() text (comments dropped).
std::vector<std::pair<std::string, std::string>> keyLines(const std::string& toml) {
  std::vector<std::pair<std::string, std::string>> lines;
  std::istringstream in(toml);
  std::string line, section;
  while (std::getline(in, line)) {
    // A '#' may only appear inside a quoted string value; the comment starts after the last quote.
    const std::size_t last_quote = line.rfind('"');
    const std::size_t hash = line.find('#', last_quote == std::string::npos ? 0 : last_quote);
    if (hash != std::string::npos) line.erase(hash);
    while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
    if (line.empty()) continue;
    if (line.front() == '[') {
      section = line.substr(1, line.find(']') - 1);
      continue;
    }
    const std::size_t eq = line.find(" = ");
    if (eq == std::string::npos) continue;
    lines.emplace_back(section + "." + line.substr(0, eq), line.substr(eq + 3));
  }
  return lines;
}

}  // namespace

void writeCheckpointFile(const std::string& path, const DeploymentCheckpoint& checkpoint,
                         const std::string& resolved_config_toml, double wall_time_s,
                         const std::string& series_file) {
  const IntegratorSnapshot& snap = checkpoint.integrator;
  const DaeState& state = snap.state;
  h5::AtomicH5Writer writer(path);
  h5::File& file = writer.file();
  file.setStringAttribute("/", "format", kFormat);
  file.setIntAttribute("/", "format_version", kFormatVersion);
  file.setStringAttribute("/", "config", resolved_config_toml);
  file.setStringAttribute("/", "mastrom_version", kVersion);
  file.setIntAttribute("/", "step", toIntAttribute(checkpoint.step, "step"));
  file.setDoubleAttribute("/", "wall_time_s", wall_time_s);
  file.setIntAttribute("/", "streamed_outputs",
                       toIntAttribute(checkpoint.streamed_outputs, "streamed_outputs"));
  file.setStringAttribute("/", "series_file", series_file);

  writeDeploymentSeries(file, kSeriesGroup, checkpoint.series);
  writeStreamState(file, checkpoint);

  const DeploymentStatistics& stats = checkpoint.statistics;
  file.createGroup(kStatisticsGroup);
  file.setIntAttribute(kStatisticsGroup, "steps", toIntAttribute(stats.steps, "steps"));
  file.setIntAttribute(kStatisticsGroup, "newton_iterations",
                       toIntAttribute(stats.newton_iterations, "newton_iterations"));
  file.setIntAttribute(kStatisticsGroup, "factorizations",
                       toIntAttribute(stats.factorizations, "factorizations"));
  file.setDoubleAttribute(kStatisticsGroup, "max_constraint_residual",
                          stats.max_constraint_residual);
  file.setIntAttribute(kStatisticsGroup, "rejected_steps",
                       toIntAttribute(stats.rejected_steps, "rejected_steps"));
  file.setDoubleAttribute(kStatisticsGroup, "min_step_s", stats.min_step_s);
  file.setDoubleAttribute(kStatisticsGroup, "max_step_s", stats.max_step_s);

  // The step controller of an adaptive run: its history (up to four step points of the current
  // smooth piece), scale and PI memory, and the piece starts.
  const StepControlState& control = checkpoint.controller;
  file.createGroup(kControllerGroup);
  file.setDoubleAttribute(kControllerGroup, "peak", control.peak);
  file.setDoubleAttribute(kControllerGroup, "previous_error", control.previous_error);
  file.setDoubleAttribute(kControllerGroup, "step_s", control.step_s);
  file.setDoubleAttribute(kControllerGroup, "noise_floor", control.noise_floor);
  file.setDoubleAttribute(kControllerGroup, "peak_velocity", control.peak_velocity);
  file.setDoubleAttribute(kControllerGroup, "noise_floor_velocity", control.noise_floor_velocity);
  file.setIntAttribute(kControllerGroup, "noise_limited",
                       toIntAttribute(control.noise_limited, "noise_limited"));
  file.setDoubleAttribute(kControllerGroup, "accepted_step_s", control.accepted_step_s);
  file.setDoubleAttribute(kControllerGroup, "growth_barrier_s", control.growth_barrier_s);
  file.setIntAttribute(kControllerGroup, "growth_wait",
                       toIntAttribute(control.growth_wait, "growth_wait"));
  file.setIntAttribute(kControllerGroup, "growth_backoff",
                       toIntAttribute(control.growth_backoff, "growth_backoff"));
  file.setIntAttribute(kControllerGroup, "rejected", toIntAttribute(control.rejected, "rejected"));
  file.writeDoubles(std::string(kControllerGroup) + "/times", control.times, "s");
  for (std::size_t k = 0; k < control.values.size(); ++k) {
    writeVector(file, detail::concat(kControllerGroup, "/values_", k), control.values[k]);
  }
  file.writeDoubles(
      std::string(kControllerGroup) + "/piece_starts",
      std::vector<double>(checkpoint.piece_starts.begin(), checkpoint.piece_starts.end()), "1");

  const std::string g = kStateGroup;
  file.createGroup(g);
  writeVector(file, g + "/q", state.q);
  writeVector(file, g + "/qdot", state.qdot);
  writeVector(file, g + "/qddot", state.qddot);
  writeVector(file, g + "/pseudo_acceleration", state.pseudo_acceleration);
  writeVector(file, g + "/lambda", state.lambda);
  // Empty when the index-1 recovery has not run yet; absent then, so that a reader restores
  // "empty".
  if (state.qddot_index1.size() > 0) writeVector(file, g + "/qddot_index1", state.qddot_index1);
  if (state.lambda_index1.size() > 0) writeVector(file, g + "/lambda_index1", state.lambda_index1);
  file.setDoubleAttribute(g, "time_s", state.time_s);
  file.setDoubleAttribute(g, "start_time_s", snap.start_time_s);
  file.setIntAttribute(g, "step_count", toIntAttribute(snap.step_count, "step_count"));
  file.setIntAttribute(g, "last_iterations", snap.last_iterations);
  file.setIntAttribute(g, "factor_valid", snap.factor_valid ? 1 : 0);
  file.setIntAttribute(g, "factorizations", toIntAttribute(snap.factorizations, "factorizations"));
  file.setDoubleAttribute(g, "step_size_s", snap.step_size_s);
  file.setDoubleAttribute(g, "previous_step_size_s", snap.previous_step_size_s);
  writeFactorization(file, kIterationGroup, snap.iteration);
  writeFactorization(file, kMassGroup, snap.mass);
  writeFactorization(file, kSpareGroup, snap.spare_iteration);
  file.setIntAttribute(kSpareGroup, "in_use_valid", snap.spare_factor_valid ? 1 : 0);
  // The predictor's older point; absent right after a (re)start, when there is none.
  if (snap.previous_qddot.size() > 0) {
    writeVector(file, g + "/previous_qddot", snap.previous_qddot);
    writeVector(file, g + "/previous_lambda", snap.previous_lambda);
  }
  writer.commit();
}

CheckpointFile readCheckpointFile(const std::string& path) {
  const h5::File file = h5::File::open(path, h5::OpenMode::ReadOnly);
  MASTROM_REQUIRE(file.hasAttribute("/", "format"), IoError, "'", path,
                  "' is not a mastrom checkpoint (no root attribute 'format')");
  const std::string format = file.readStringAttribute("/", "format");
  MASTROM_REQUIRE(format == kFormat, IoError, "'", path, "' is not a mastrom checkpoint (format '",
                  format, "', expected '", kFormat, "')");
  const int version = file.readIntAttribute("/", "format_version");
  MASTROM_REQUIRE(version == kFormatVersion, IoError, "'", path, "' is checkpoint format version ",
                  version, "; this mastrom reads version ", kFormatVersion);
  for (const char* group : {kSeriesGroup, kStatisticsGroup, kStateGroup, kIterationGroup,
                            kMassGroup, kControllerGroup}) {
    MASTROM_REQUIRE(file.exists(group), IoError, "'", path, "' is an incomplete checkpoint: no ",
                    group);
  }

  CheckpointFile result;
  result.config_toml = file.readStringAttribute("/", "config");
  result.mastrom_version = file.readStringAttribute("/", "mastrom_version");
  result.wall_time_s = file.readDoubleAttribute("/", "wall_time_s");
  DeploymentCheckpoint& c = result.checkpoint;
  c.step = file.readIntAttribute("/", "step");
  c.streamed_outputs = file.readIntAttribute("/", "streamed_outputs");
  result.series_file = file.readStringAttribute("/", "series_file");
  MASTROM_REQUIRE(
      c.streamed_outputs >= 0 && (c.streamed_outputs == 0 || !result.series_file.empty()), IoError,
      "'", path, "' is an inconsistent checkpoint: streamed_outputs = ", c.streamed_outputs,
      " with series_file '", result.series_file, "'");
  c.series = readDeploymentSeries(file, kSeriesGroup);
  readStreamState(file, c);

  DeploymentStatistics& stats = c.statistics;
  stats.steps = file.readIntAttribute(kStatisticsGroup, "steps");
  stats.newton_iterations = file.readIntAttribute(kStatisticsGroup, "newton_iterations");
  stats.factorizations = file.readIntAttribute(kStatisticsGroup, "factorizations");
  stats.max_constraint_residual =
      file.readDoubleAttribute(kStatisticsGroup, "max_constraint_residual");
  stats.rejected_steps = file.readIntAttribute(kStatisticsGroup, "rejected_steps");
  stats.min_step_s = file.readDoubleAttribute(kStatisticsGroup, "min_step_s");
  stats.max_step_s = file.readDoubleAttribute(kStatisticsGroup, "max_step_s");

  StepControlState& control = c.controller;
  control.peak = file.readDoubleAttribute(kControllerGroup, "peak");
  control.previous_error = file.readDoubleAttribute(kControllerGroup, "previous_error");
  control.step_s = file.readDoubleAttribute(kControllerGroup, "step_s");
  control.noise_floor = file.readDoubleAttribute(kControllerGroup, "noise_floor");
  control.peak_velocity = file.readDoubleAttribute(kControllerGroup, "peak_velocity");
  control.noise_floor_velocity = file.readDoubleAttribute(kControllerGroup, "noise_floor_velocity");
  control.noise_limited = file.readIntAttribute(kControllerGroup, "noise_limited");
  stats.noise_limited_steps = control.noise_limited;
  control.accepted_step_s = file.readDoubleAttribute(kControllerGroup, "accepted_step_s");
  control.growth_barrier_s = file.readDoubleAttribute(kControllerGroup, "growth_barrier_s");
  control.growth_wait = file.readIntAttribute(kControllerGroup, "growth_wait");
  control.growth_backoff = file.readIntAttribute(kControllerGroup, "growth_backoff");
  control.rejected = file.readIntAttribute(kControllerGroup, "rejected");
  control.times = file.readDoubles(std::string(kControllerGroup) + "/times");
  for (std::size_t k = 0; k < control.times.size(); ++k) {
    control.values.push_back(readVector(file, detail::concat(kControllerGroup, "/values_", k)));
  }
  for (double start : file.readDoubles(std::string(kControllerGroup) + "/piece_starts")) {
    c.piece_starts.push_back(static_cast<long>(start));
  }

  IntegratorSnapshot& snap = c.integrator;
  DaeState& state = snap.state;
  const std::string g = kStateGroup;
  state.q = readVector(file, g + "/q");
  state.qdot = readVector(file, g + "/qdot");
  state.qddot = readVector(file, g + "/qddot");
  state.pseudo_acceleration = readVector(file, g + "/pseudo_acceleration");
  state.lambda = readVector(file, g + "/lambda");
  if (file.exists(g + "/qddot_index1")) state.qddot_index1 = readVector(file, g + "/qddot_index1");
  if (file.exists(g + "/lambda_index1")) {
    state.lambda_index1 = readVector(file, g + "/lambda_index1");
  }
  state.time_s = file.readDoubleAttribute(g, "time_s");
  snap.start_time_s = file.readDoubleAttribute(g, "start_time_s");
  snap.step_count = file.readIntAttribute(g, "step_count");
  snap.last_iterations = file.readIntAttribute(g, "last_iterations");
  snap.factor_valid = file.readIntAttribute(g, "factor_valid") != 0;
  snap.factorizations = file.readIntAttribute(g, "factorizations");
  snap.step_size_s = file.readDoubleAttribute(g, "step_size_s");
  snap.previous_step_size_s = file.readDoubleAttribute(g, "previous_step_size_s");
  snap.iteration = readFactorization(file, kIterationGroup);
  snap.mass = readFactorization(file, kMassGroup);
  MASTROM_REQUIRE(file.exists(kSpareGroup), IoError, "'", path,
                  "' is an incomplete checkpoint: no ", kSpareGroup);
  snap.spare_iteration = readFactorization(file, kSpareGroup);
  snap.spare_factor_valid = file.readIntAttribute(kSpareGroup, "in_use_valid") != 0;
  if (file.exists(g + "/previous_qddot")) {
    snap.previous_qddot = readVector(file, g + "/previous_qddot");
    snap.previous_lambda = readVector(file, g + "/previous_lambda");
  }
  return result;
}

void requireSameConfiguration(const std::string& checkpoint_path, const std::string& saved_toml,
                              const std::string& current_toml) {
  if (saved_toml == current_toml) return;
  const auto saved = keyLines(saved_toml);
  const auto current = keyLines(current_toml);
  const auto ignored = [](const std::string& key) { return key == "output.file"; };
  std::size_t i = 0, j = 0;
  while (i < saved.size() || j < current.size()) {
    if (i < saved.size() && ignored(saved[i].first)) {
      ++i;
      continue;
    }
    if (j < current.size() && ignored(current[j].first)) {
      ++j;
      continue;
    }
    MASTROM_REQUIRE(i < saved.size() && j < current.size(), InputError, "--restart '",
                    checkpoint_path, "': the checkpoint's configuration has ",
                    i < saved.size() ? "more" : "fewer", " keys than this run's (",
                    i < saved.size() ? saved[i].first : current[j].first, ")");
    MASTROM_REQUIRE(saved[i] == current[j], InputError, "--restart '", checkpoint_path,
                    "' was written with a different configuration: ", saved[i].first, " = ",
                    saved[i].second, " in the checkpoint, ",
                    current[j].first == saved[i].first ? std::string() : current[j].first + " = ",
                    current[j].second, " now");
    ++i;
    ++j;
  }
}

}  // namespace mastrom::fullorder
