// Running one study case (rom/studies/study_definition.hpp) with the nonlinear full order (docs/theory.md
// §5, generalized-α, the same call as `mastrom simulate`) and with the modal ROM solved at the
// case's own parameters (rom/offline/direct_modal_model.hpp), both sampled at simulation.time_step ×
// output.every, and the row of the comparison table built from the two results.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "fullorder/deployment_result.hpp"
#include "rom/model/comparison.hpp"

namespace mastrom::rom {

/// One model's deployment of one case.
struct CaseResult {
  fullorder::DeploymentSeries series;
  fullorder::DeploymentMetrics metrics;
  double wall_s = 0.0;  ///< wall time of the run (for the ROM: modal solve + deployment)
};

/// Progress of a full-order run: (simulated time, end time, Newton iterations per step so far).
using FullOrderProgress = std::function<void(double t_s, double end_s, double newton_per_step)>;

/// The full-order deployment of `config` (simulation.* keys, drive.*, output.every).
CaseResult runFullOrderCase(const Config& config, const FullOrderProgress& progress = {});

/// The ROM deployment of `config` with `modes` modes (0 = modes.count). The modal model's first
/// drive-excited mode is returned too: its frequency [Hz] and decay time 1/(ζω) [s].
struct RomCaseResult : CaseResult {
  int modes = 0;                       ///< modes in the model (a cut degenerate pair is completed)
  double first_bending_hz = 0.0;       ///< first drive-excited mode (NaN when none)
  double first_bending_decay_s = 0.0;  ///< 1/(ζ₁ω₁): the e-folding time of its free vibration
};
RomCaseResult runRomCase(const Config& config, int modes = 0);

/// One row of the study table: a case and whichever models were run.
struct StudyRow {
  std::string study;
  std::string name;
  Config config;
  std::optional<CaseResult> full;
  std::optional<RomCaseResult> rom;
  /// ROM vs full order (rom/model/comparison.hpp), when both ran.
  std::optional<DeploymentComparison> comparison;
};

/// The scalar metrics of a deployment in table order (SI), and their names with units.
std::vector<std::string> studyMetricNames();
std::vector<double> studyMetricValues(const fullorder::DeploymentMetrics& metrics);

/// Fill row.comparison from row.full and row.rom (nothing when one is missing).
void compareRow(StudyRow& row);

/// The table as CSV (one line per case; columns study, case, then every metric for the full
/// order, the ROM and their relative difference (rom − full)/|full|, then the NRMSE, the ROM's
/// first bending frequency and decay time, the wall times). Missing values are empty fields.
/// Written atomically (temporary file + rename); IoError when it cannot be written.
void writeStudyCsv(const std::string& path, const std::vector<StudyRow>& rows);

/// The table as HDF5 (atomic): string datasets /study/study_names, /study/case_names,
/// /study/metric_names, /study/configs (the resolved TOML of every case); [cases, metrics] datasets
/// /study/full_metrics, /study/rom_metrics, /study/relative_difference (SI, NaN where a model did
/// not run); per case /study/nrmse_relative_acceleration [1], /study/first_bending_frequency [Hz],
/// /study/first_bending_decay_time [s], /study/full_wall_time, /study/rom_wall_time [s]; root
/// attributes source = "study", mastrom_version.
void writeStudyH5(const std::string& path, const std::vector<StudyRow>& rows);

}  // namespace mastrom::rom
