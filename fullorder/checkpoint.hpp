// Checkpoint files of a full-order deployment (`mastrom simulate --checkpoint-every N`
// crash safety). A checkpoint holds everything the remaining steps depend on — the integrator
// state, the inputs of the factorisations modified Newton keeps reusing
// (fullorder/generalized_alpha.hpp), the outputs recorded so far — plus the resolved configuration,
// so `--restart` continues bit for bit like the uninterrupted run and refuses a different
// configuration. Written atomically (temporary name, renamed over the previous checkpoint), so a
// run killed at any instant leaves the last complete checkpoint under the final name.
//
// HDF5 layout (doubles are stored exactly; vectors in the integrator's eliminated coordinates):
//   /                      attributes format = "mastrom-checkpoint", format_version, config,
//                          mastrom_version, step, wall_time_s
//   /series/...            the outputs so far, the docs/user_guide.md §5 columns
// (fullorder/results_io.hpp); a streamed run's (fixed or adaptive steps, DeploymentCheckpoint::
// streamed_outputs > 0, root attributes streamed_outputs and series_file) the last one only: the
// others are in the result file it was writing, series_file, which a restart rebuilds from
// (fullorder/streamed_result_file.hpp rebuildStreamedSeries)
//   /stream                a streamed adaptive run only: the continuous response's state
//                          (fullorder/step_point_stream.hpp; attributes points, piece_points,
//                          next_interval, next_output, first_time_s and the peaks), /stream/window
//                          its step points (the §5 columns), /stream/piece_start_times [s]
//   /statistics            attributes steps, newton_iterations, factorizations,
//                          max_constraint_residual
//   /integrator/state/{q, qdot, qddot, pseudo_acceleration, lambda[, qddot_index1, lambda_index1]}
//                          attributes time_s, start_time_s, step_count, last_iterations,
//                          factor_valid, factorizations
//   /integrator/iteration_factor, /integrator/mass_factor: {q, qdot, lambda}, attributes valid,
//                          time_s, c_mass, c_damping, c_stiffness, c_constraint
#pragma once

#include <string>

#include "fullorder/deployment.hpp"

namespace mastrom::fullorder {

/// What a checkpoint file holds besides the checkpoint itself.
struct CheckpointFile {
  DeploymentCheckpoint checkpoint;
  std::string config_toml;      ///< resolved configuration of the run that wrote it
  std::string mastrom_version;  ///< of the program that wrote it
  double wall_time_s = 0.0;     ///< wall time spent up to the checkpoint (all earlier legs)
  /// A streamed run: the file holding its first checkpoint.streamed_outputs output instants (the
  /// result file under its temporary name while the run went on).
  std::string series_file;
};

/// Write `checkpoint` atomically to `path`, replacing an earlier checkpoint only once the new one is
/// complete. IoError when the file cannot be written.
void writeCheckpointFile(const std::string& path, const DeploymentCheckpoint& checkpoint,
                         const std::string& resolved_config_toml, double wall_time_s,
                         const std::string& series_file = {});

/// Read a checkpoint. IoError (one line, naming the file) when it is missing, not HDF5, not a mastrom
/// checkpoint or incomplete.
CheckpointFile readCheckpointFile(const std::string& path);

/// InputError naming the first differing key and both values when the configuration a checkpoint
/// was written with differs from the current one ([output] file excepted: it does not change the
/// results). Both texts are toToml() output.
void requireSameConfiguration(const std::string& checkpoint_path, const std::string& saved_toml,
                              const std::string& current_toml);

}  // namespace mastrom::fullorder
