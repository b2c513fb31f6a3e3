// `mastrom validate`: the ROM against the nonlinear full order at random points of the database box
// (docs/theory.md §4.4 "validate compares against full-order runs at held-out points"). Per point:
// one full-order deployment (generalized-α), one ROM deployment (interpolated modal model), a
// direct modal solve for the first-frequency error, and the comparison of rom/model/comparison.hpp.
// Points are drawn uniformly in the box by a seeded generator (same seed → same points),
// distributed round-robin over MPI ranks and merged on rank 0 in point order, so results do not
// depend on the number of ranks.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/model/comparison.hpp"
#include "rom/studies/design_description.hpp"

namespace mastrom::rom {

struct ValidationOptions {
  int points = 4;
  std::uint64_t seed = 1;
  std::vector<std::string> overrides;  ///< free keys (drive, simulation) applied to every point
  InterpolationMethod method = InterpolationMethod::Manifold;
  MPI_Comm communicator = MPI_COMM_NULL;  ///< MPI_COMM_NULL = serial
  /// The lowest natural frequencies of every point at the deployed angle, from the ROM with the
  /// database's estimate and from a direct modal solve (rom/studies/design_description.hpp).
  FrequencyRequest frequencies;
};

struct ValidationPoint {
  std::vector<double> parameters;
  DeploymentComparison errors;
  double first_frequency_error = 0.0;  ///< |f₁,rom − f₁,direct| / f₁,direct
  double full_wall_s = 0.0;
  double rom_wall_s = 0.0;
  /// The full order's own estimated discretisation error (NRMSE of the relative end angular
  /// acceleration, fullorder/deployment_accuracy.hpp); NaN for fixed steps.
  double full_estimated_nrmse = 0.0;
  /// The database's estimate of the ROM's NRMSE at the point (rom/database/probe_point_estimate.hpp);
  /// −1 where it has none (no probes, or a method other than its default validated).
  double rom_estimated_nrmse = -1.0;
  double mass_kg = 0.0;  ///< the design's mass (docs/theory.md (1.12))
  /// Per frequency k (ValidationReport::frequencies of them): the ROM's at the deployed angle, the
  /// database's estimate of its relative error (4.15) (−1: none), and a direct modal solve's.
  std::vector<double> frequency_hz, frequency_error_estimate, frequency_direct_hz;
  double speedup() const { return rom_wall_s > 0 ? full_wall_s / rom_wall_s : 0.0; }
};

struct ValidationReport {
  std::vector<std::string> parameter_names;
  std::vector<ValidationPoint> points;  ///< on rank 0 only (empty elsewhere)
  std::string config_toml;              ///< the evaluation config (free keys applied)
  int frequencies = 0;                  ///< natural frequencies per point
  std::string no_frequency_reason;      ///< why none, when frequencies = 0
  /// Wall time of the whole run [s] on rank 0: interpolator, every point's full-order and ROM
  /// runs (and the full order's estimate), the gather. The file's root attribute wall_time_s.
  double wall_s = 0.0;
  /// Largest error of any kind over all points (DeploymentComparison::worst, first frequency).
  double worst() const;
};

/// The random validation points (deterministic in the seed).
std::vector<std::vector<double>> validationPoints(const RomDatabase& db, int count,
                                                  std::uint64_t seed);

/// Run the validation. `progress(done, total)` is called on rank 0 after each local point.
ValidationReport runValidation(const RomDatabase& db, const ValidationOptions& options,
                               const std::function<void(int, int)>& progress = {});

/// HDF5 layout: /validation/parameter_names, /validation/parameters [N,p], /validation/error_names,
/// /validation/errors [N,q] (relative), /validation/first_frequency_error [N],
/// /validation/full_wall_time [N], /validation/rom_wall_time [N],
/// /validation/full_order_estimated_nrmse [N], /validation/rom_estimated_nrmse [N] (−1: none),
/// /validation/mass [N] (kg), and with frequencies /validation/frequencies [N,K] (Hz, the ROM's),
/// /validation/frequency_error_estimate [N,K] (relative, −1: none), /validation/frequencies_direct
/// [N,K] (Hz, a direct modal solve at the deployed angle);
/// root attributes source = "validation", config, mastrom_version, method, seed, worst_error,
/// wall_time_s (ValidationReport::wall_s).
void writeValidationFile(const std::string& path, const ValidationReport& report,
                         const ValidationOptions& options);

}  // namespace mastrom::rom
