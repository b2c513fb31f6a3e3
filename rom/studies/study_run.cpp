#include "rom/studies/study_run.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "common/version.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/deployment_accuracy.hpp"
#include "fullorder/drive_law.hpp"
#include "fullorder/mast_config.hpp"
#include "rom/offline/direct_modal_model.hpp"
#include "rom/database/h5_arrays.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_deployment.hpp"

namespace mastrom::rom {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// (rom − full)/|full|; NaN when the full-order value is 0 (no relative difference defined).
double relativeDifference(double full, double rom) {
  return full != 0.0 ? (rom - full) / std::abs(full) : kNaN;
}

std::string csvNumber(double v) {
  if (std::isnan(v)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  return buffer;
}

/// Every table column of the rows, with names and units: what both files write.
struct Table {
  std::vector<double> full, rom, difference;  // row-major [cases, metrics]
  std::vector<double> nrmse, bending_hz, decay_s, full_wall, rom_wall;
};

Table tabulate(const std::vector<StudyRow>& rows) {
  const std::size_t m = studyMetricNames().size();
  Table t;
  for (const StudyRow& r : rows) {
    const std::vector<double> nan(m, kNaN);
    const std::vector<double> f = r.full ? studyMetricValues(r.full->metrics) : nan;
    const std::vector<double> q = r.rom ? studyMetricValues(r.rom->metrics) : nan;
    t.full.insert(t.full.end(), f.begin(), f.end());
    t.rom.insert(t.rom.end(), q.begin(), q.end());
    for (std::size_t j = 0; j < m; ++j)
      t.difference.push_back(r.full && r.rom ? relativeDifference(f[j], q[j]) : kNaN);
    t.nrmse.push_back(r.comparison ? r.comparison->nrmse_relative_acceleration : kNaN);
    t.bending_hz.push_back(r.rom ? r.rom->first_bending_hz : kNaN);
    t.decay_s.push_back(r.rom ? r.rom->first_bending_decay_s : kNaN);
    t.full_wall.push_back(r.full ? r.full->wall_s : kNaN);
    t.rom_wall.push_back(r.rom ? r.rom->wall_s : kNaN);
  }
  return t;
}

}  // namespace

CaseResult runFullOrderCase(const Config& config, const FullOrderProgress& progress) {
  const auto start = Clock::now();
  fullorder::MastModel model = fullorder::buildMast(fullorder::mastParametersFromConfig(config));
  const fullorder::DeploymentOptions options = fullorder::deploymentFromConfig(config);
  fullorder::DeploymentProgress report;
  if (progress) {
    report = [&progress](double t, double end, const fullorder::DeploymentStatistics& s) {
      progress(t, end, s.steps ? double(s.newton_iterations) / double(s.steps) : 0.0);
    };
  }
  CaseResult r;
  fullorder::DeploymentStatistics stats;
  r.series = fullorder::simulateDeployment(model, options, &stats, report);
  r.metrics = fullorder::fullOrderMetrics(r.series, stats, config.drive.duration_s);
  r.wall_s = secondsSince(start);
  return r;
}

RomCaseResult runRomCase(const Config& config, int modes) {
  const auto start = Clock::now();
  const ModalModel model = directModalModel(config, modes);
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(config));
  RomCaseResult r;
  const ModalDeploymentOptions options = deploymentOptionsFromConfig(config);
  r.series = simulateModalDeployment(model, drive, options);
  // Continuous peaks, as the full order's (runFullCase).
  r.metrics = modalDeploymentMetrics(model, drive, options, config.drive.duration_s);
  r.wall_s = secondsSince(start);
  r.modes = model.modeCount();
  const int k = firstExcitedMode(model);
  r.first_bending_hz = k >= 0 ? model.omega_rad_s[k] / (2.0 * M_PI) : kNaN;
  const double zeta_omega = k >= 0 ? model.damping_ratio[k] * model.omega_rad_s[k] : 0.0;
  r.first_bending_decay_s = zeta_omega > 0 ? 1.0 / zeta_omega : kNaN;
  return r;
}

std::vector<std::string> studyMetricNames() {
  return {"peak_abs_end_angular_acceleration_rad_s2",
          "peak_rel_end_angular_acceleration_rad_s2",
          "rms_rel_end_angular_acceleration_rad_s2",
          "residual_rel_end_angular_acceleration_rad_s2",
          "settling_time_s",
          "peak_joint_force_n",
          "peak_drive_torque_nm"};
}

std::vector<double> studyMetricValues(const fullorder::DeploymentMetrics& m) {
  return {m.peak_abs_end_angular_acceleration,
          m.peak_rel_end_angular_acceleration,
          m.rms_rel_end_angular_acceleration,
          m.residual_rel_end_angular_acceleration,
          m.settling_time,
          m.peak_joint_force,
          m.peak_drive_torque};
}

void compareRow(StudyRow& row) {
  if (!row.full || !row.rom) return;
  try {
    row.comparison =
        compareDeployments(row.full->series, row.full->metrics, row.rom->series, row.rom->metrics);
  } catch (const InputError& e) {
    throw InputError(detail::concat("study ", row.study, ", case '", row.name, "': ", e.what(),
                                    " (make simulation.end_time a multiple of "
                                    "simulation.time_step x output.every)"));
  }
}

void writeStudyCsv(const std::string& path, const std::vector<StudyRow>& rows) {
  h5::checkWritable(path);
  const std::vector<std::string> names = studyMetricNames();
  const Table t = tabulate(rows);
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary);
    MASTROM_REQUIRE(out.good(), IoError, "cannot write '", temporary, "'");
    out << "study,case";
    for (const char* model : {"full", "rom", "reldiff"})
      for (const std::string& n : names) out << ',' << model << '_' << n;
    out << ",nrmse_rel_end_angular_acceleration,first_bending_hz,first_bending_decay_s,"
           "full_wall_s,rom_wall_s\n";
    const std::size_t m = names.size();
    for (std::size_t i = 0; i < rows.size(); ++i) {
      out << rows[i].study << ',' << rows[i].name;
      for (const std::vector<double>* block : {&t.full, &t.rom, &t.difference})
        for (std::size_t j = 0; j < m; ++j) out << ',' << csvNumber((*block)[i * m + j]);
      for (const std::vector<double>* column :
           {&t.nrmse, &t.bending_hz, &t.decay_s, &t.full_wall, &t.rom_wall})
        out << ',' << csvNumber((*column)[i]);
      out << '\n';
    }
    out.flush();
    if (!out.good()) {
      std::remove(temporary.c_str());
      throw IoError(detail::concat("cannot write '", temporary, "'"));
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::remove(temporary.c_str());
    throw IoError(
        detail::concat("cannot rename '", temporary, "' to '", path, "': ", ec.message()));
  }
}

void writeStudyH5(const std::string& path, const std::vector<StudyRow>& rows) {
  const std::vector<std::string> names = studyMetricNames();
  const Table t = tabulate(rows);
  const std::size_t n = rows.size(), m = names.size();
  std::vector<std::string> studies, cases, configs;
  for (const StudyRow& r : rows) {
    studies.push_back(r.study);
    cases.push_back(r.name);
    configs.push_back(toToml(r.config));
  }
  h5::AtomicH5Writer writer(path);
  h5::File& f = writer.file();
  f.setStringAttribute("/", "source", "study");
  f.setStringAttribute("/", "mastrom_version", std::string(kVersion));
  h5x::writeStrings(f, "/study/study_names", studies);
  h5x::writeStrings(f, "/study/case_names", cases);
  h5x::writeStrings(f, "/study/metric_names", names);
  h5x::writeStrings(f, "/study/configs", configs);
  const std::string units = "SI (see metric_names)";
  h5x::writeDoubles(f, "/study/full_metrics", {n, m}, t.full.data(), units);
  h5x::writeDoubles(f, "/study/rom_metrics", {n, m}, t.rom.data(), units);
  h5x::writeDoubles(f, "/study/relative_difference", {n, m}, t.difference.data(), "1");
  f.writeDoubles("/study/nrmse_relative_acceleration", t.nrmse, "1");
  f.writeDoubles("/study/first_bending_frequency", t.bending_hz, "Hz");
  f.writeDoubles("/study/first_bending_decay_time", t.decay_s, "s");
  f.writeDoubles("/study/full_wall_time", t.full_wall, "s");
  f.writeDoubles("/study/rom_wall_time", t.rom_wall, "s");
  writer.commit();
}

}  // namespace mastrom::rom
