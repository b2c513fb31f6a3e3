// The offline stage of the ROM (DESIGN §4.2): sample a box of configuration parameters on a tensor
// grid, run the modal solve at every sample, track every sample's modes against the reference
// sample (the box centre), and estimate the database's own interpolation error by leave-one-out.
//
// Per sample: configuration with the sample's parameter values → mast locked at modes.angle_deg →
// static equilibrium and linearisation (modes/linearize.hpp) → constrained eigenproblem
// (modes/eigen_solver.hpp, each rank solving its own problem on MPI_COMM_SELF) → ModalModel
// (rom/modal_extraction.hpp) → MAC tracking, signs and Procrustes alignment against the reference
// modes (rom/mode_tracking.hpp). Mode shapes Φ never leave the rank that computed them: every rank
// solves the reference sample first (one extra solve per rank, the same wall time as a broadcast
// that waits for it), so tracking happens where the sample was solved and only the small per-mode
// data are gathered.
//
// Distribution: sample s is solved by rank s mod P of the communicator (round-robin: neighbouring
// grid samples cost alike, so the ranks finish together); the samples' modal data are gathered to
// every rank, which computes the leave-one-out estimate of its own samples again; rank 0 collects
// the estimate and returns the database. The result does not depend on P: every sample is computed
// by the same code from the same input.
//
// Leave-one-out (DESIGN §4.3 "every database carries its own error estimate"): a sample that is
// interior along at least one axis is interpolated from the grid without it — along each axis where
// it is interior only its two neighbours remain (the coarsened stencil), along the others the full
// axis (where it is a node, so that direction contributes no error). Per sample two relative
// errors are stored: of the lowest frequency ω₁, and the NRMSE of the relative end angular
// acceleration of a reference deployment (the base configuration's drive, end time and output
// step, simulated with the ROM on the interpolated and on the sample's own modal model) — the
// quantity `mastrom validate` reports, restricted to the interpolation error.
//
// From the stencil to the full grid (leaveOneOutScale). Multilinear interpolation in the
// coordinate u the weights are linear in (u = log p on an axis of positive values, p otherwise) has
// the error e(t) ≈ ½ t(1 − t) H² f''(u) at the local coordinate t of a cell of width H (f smooth,
// the response NRMSE linear in the modal errors while they are small). The left-out sample sits in
// its stencil of width h₁ + h₂ at t = h₁/(h₁ + h₂): e_LOO = ½ h₁h₂ f''. The largest error in
// the two full-grid cells next to it is at their midpoints, ⅛ max(h₁, h₂)² f''. Hence
//     e_interior ≈ ρ e_LOO,   ρ = max(h₁, h₂)² / (4 h₁ h₂)   (= ¼ on a uniform axis),
// and the database's estimate is max over samples of ρ_s e_LOO,s (ρ_s the largest over the axes
// where sample s is interior). What it bounds: the interpolation error (interpolated ROM against
// the ROM of a direct modal solve at the same point), which `validate` reports next to the error
// against the full order; the latter adds the modal model's own error at a sample (DESIGN §4.1,
// ≤ 3 % target). The estimate is an estimate, not a bound: it is exact to O(H³) for smooth f, and
// it underestimates when the stencil's error leaves the linear range (a phase error of the
// response beyond ≈ 1 rad, NRMSE ≳ 50 %).
#pragma once

#include <mpi.h>

#include <functional>
#include <optional>
#include <vector>

#include "common/config.hpp"
#include "fullorder/drive_law.hpp"
#include "rom/modal_deployment.hpp"
#include "rom/rom_database.hpp"

namespace mastrom::rom {

struct DatabaseBuildOptions {
  std::vector<ParameterAxis> axes;          ///< from parseParameterAxis; at least one
  int modes = 0;                            ///< modes per sample; 0 = the config's modes.count
  std::optional<EigenBackendKind> backend;  ///< default: the config's modes.backend
  /// Ranks the samples are distributed over. MPI_COMM_NULL = everything in this process, no MPI
  /// call at all. Otherwise the call is collective over the communicator.
  MPI_Comm communicator = MPI_COMM_NULL;
  /// Called on every rank after each of its own samples: (done, total) of this rank's share.
  std::function<void(int done, int total)> progress;
};

/// Where the build's time went, in seconds. "Modal solve" is the eigen-solver backend alone;
/// assembly = mast model + static equilibrium + linearisation. Per-phase times are summed over
/// ranks (CPU-like); wall_s is rank 0's wall clock for the whole build.
struct BuildTiming {
  int ranks = 1;
  int solves = 0;             ///< modal solves run (samples + one reference solve per extra rank)
  double assembly_s = 0.0;    ///< Σ over ranks
  double eigensolve_s = 0.0;  ///< Σ over ranks
  double extraction_s = 0.0;  ///< modal extraction + tracking, Σ over ranks
  double communication_s = 0.0;  ///< rank 0 waiting for the other ranks and gathering
  double leave_one_out_s = 0.0;  ///< Σ over ranks
  double affine_s = 0.0;         ///< rank 0: the affine terms and their errors at the samples
  double wall_s = 0.0;           ///< rank 0, whole build
};

/// Leave-one-out errors of one interpolation method; −1 where not estimated (boundary samples).
struct LeaveOneOutResult {
  InterpolationMethod method = InterpolationMethod::Tracked;
  std::vector<double> frequency_error;  ///< |ω₁,interp − ω₁| / ω₁ per sample
  std::vector<double> response_error;   ///< NRMSE of the relative end angular acceleration
  int estimated = 0;                    ///< samples with an estimate
  double max_frequency_error = -1.0;    ///< −1 when nothing was estimated
  double max_response_error = -1.0;
  /// The database's estimate of the error between samples: max_s ρ_s e_s (see the header).
  double frequency_estimate = -1.0;
  double response_estimate = -1.0;
};

struct BuildReport {
  BuildTiming timing;
  double min_mac = 1.0;  ///< smallest MAC of a tracked pair over all samples
  int min_mac_sample = 0;
  /// The same over the modes the drive excites (reference |Γ_j| ≥ 1e-3 max |Γ|): the ones that
  /// matter for the response; shell modes entering or leaving the window do not.
  double min_coupled_mac = 1.0;
  int min_coupled_mac_sample = 0;
  /// One per method estimated (tracked, manifold, then affine when the database carries its terms:
  /// for affine the errors are at the samples themselves, unscaled — nothing is interpolated).
  std::vector<LeaveOneOutResult> leave_one_out;
};

/// Build the database over `options.axes` from the base configuration (already carrying any --set
/// overrides). Collective over options.communicator; the complete database is returned on rank 0,
/// an empty one (no samples) on the other ranks. Throws InputError for bad options, NumericalError
/// naming the sample and its parameters when a modal solve fails (on every rank alike).
RomDatabase buildDatabase(const Config& base, const DatabaseBuildOptions& options,
                          BuildReport* report = nullptr);

/// The parameter values of grid sample `index` (first axis fastest).
std::vector<double> gridPoint(const std::vector<ParameterAxis>& axes, int index);
/// The multi-index of grid sample `index`.
std::vector<int> gridIndex(const std::vector<ParameterAxis>& axes, int index);

/// The database without sample `index`, coarsened around it as described in the header, or
/// nothing when the sample lies on the box boundary along every axis.
std::optional<RomDatabase> leaveOneOutStencil(const RomDatabase& db, int index);

/// ρ of the header for grid sample `index`: how the leave-one-out error of the sample translates to
/// the largest error inside the full grid's cells next to it; 0 for a sample on the boundary of
/// every axis (no estimate).
double leaveOneOutScale(const std::vector<ParameterAxis>& axes, int index);

/// Leave-one-out errors of `method` for every sample, with the reference deployment given by
/// `drive` and `options`. Throws InputError when the method is not available.
LeaveOneOutResult leaveOneOut(const RomDatabase& db, InterpolationMethod method,
                              const fullorder::DriveLaw& drive,
                              const ModalDeploymentOptions& options);

/// The reference deployment of the leave-one-out estimate: the configuration's drive law, end time
/// and output step (simulation.time_step × output.every).
ModalDeploymentOptions deploymentOptionsFromConfig(const Config& config);

}  // namespace mastrom::rom
