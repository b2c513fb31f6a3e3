// What a ROM database build reports besides the database (and a database file records in /build): where its time went, how well the modes
// tracked, and the leave-one-out error estimate of every interpolation method.
#pragma once

#include <vector>

#include "rom/database/interpolation_method.hpp"

namespace mastrom::rom {

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
  double leave_one_out_s = 0.0;  ///< Σ over ranks: the estimate's deployments and bookkeeping
  /// Σ over ranks: the modal solves of the held-out probes (of `probes`), apart from the estimate's
  /// other work — they are measurements at new points, like samples that are not stored.
  double probe_solves_s = 0.0;
  double affine_s = 0.0;         ///< rank 0: the affine terms and their errors at the samples
  int probes = 0;  ///< held-out probes solved for the estimate (rom/offline/probe_estimate.hpp)
  double wall_s = 0.0;           ///< rank 0, whole build
};

/// A reference mode with an effective-mass fraction Γ²/J at least this counts as drive-excited
/// for the tracking report (1e-4: |Γ| ≥ 1 % of a mode that took the whole rotary inertia).
constexpr double kExcitedMassFraction = 1e-4;

struct BuildReport {
  BuildTiming timing;
  double min_mac = 1.0;  ///< smallest MAC of a tracked pair over all samples
  int min_mac_sample = 0;
  int min_mac_mode = -1;  ///< the reference mode of that pair (−1: none below 1)
  /// The same over the modes the drive excites (reference effective-mass fraction Γ_j²/J ≥
  /// kExcitedMassFraction): the ones that matter for the response; shell modes entering or
  /// leaving the window of stored modes do not.
  double min_coupled_mac = 1.0;
  int min_coupled_mac_sample = 0;
  int min_coupled_mac_mode = -1;
  /// One per method estimated (tracked, manifold, then affine when the database carries its terms:
  /// for affine the errors are at the samples themselves, unscaled — nothing is interpolated).
  std::vector<LeaveOneOutResult> leave_one_out;
};

}  // namespace mastrom::rom
