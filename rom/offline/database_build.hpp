// The offline stage of the ROM (docs/theory.md §4.3): sample a box of configuration parameters on a
// tensor grid, run the modal solve at every sample, track every sample's modes against the
// reference sample (the box centre), and estimate the database's own interpolation error by
// leave-one-out.
//
// Per sample (rom/offline/sample_solve.hpp): configuration with the sample's parameter values → locked
// mast, equilibrium, linearisation and modes (rom/offline/locked_modal_solve.hpp, each rank solving its
// own problem on MPI_COMM_SELF) → ModalModel → MAC tracking, signs and Procrustes alignment against
// the reference modes (rom/offline/mode_tracking.hpp). Mode shapes Φ never leave the rank that computed them: every rank
// solves the reference sample first (one extra solve per rank, the same wall time as a broadcast
// that waits for it), so tracking happens where the sample was solved and only the small per-mode
// data are gathered.
//
// Distribution: sample s is solved by rank s mod P of the communicator (round-robin: neighbouring
// grid samples cost alike, so the ranks finish together); the samples' modal data are gathered to
// every rank (one flat serialisation, rom/offline/sample_exchange.hpp), which computes the leave-one-out
// estimate of its own samples again; rank 0 collects the estimate and returns the database. The result does not depend on P: every sample is computed
// by the same code from the same input.
//
// The estimate of the interpolation error is rom/offline/leave_one_out.hpp; what a build reports,
// rom/database/build_report.hpp.
#pragma once

#include <mpi.h>

#include <functional>
#include <optional>
#include <vector>

#include "common/config.hpp"
#include "common/kinds.hpp"
#include "rom/database/build_report.hpp"
#include "rom/database/interpolation_method.hpp"
#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

struct DatabaseBuildOptions {
  std::vector<ParameterAxis> axes;          ///< from parseParameterAxis; at least one
  int modes = 0;                            ///< modes per sample; 0 = the config's modes.count
  std::optional<EigenBackendKind> backend;  ///< default: the config's modes.backend
  /// The database's default interpolation method (what rom eval, screen and validate use unless
  /// told otherwise; its leave-one-out errors are stored). Default: affine where the exact terms
  /// apply, else cubic where the drive-excited modes track cleanly (rom/offline/probe_estimate.hpp),
  /// else manifold. Affine is refused where they do not apply.
  std::optional<InterpolationMethod> method;
  /// Estimate every interpolation method's error (leave-one-out of tracked, manifold, cubic where
  /// an axis has 5 nodes, and rbf) for the build report, not only the default method's. false:
  /// the default's alone — on a 3⁵ Scheme 3 grid the others took the build from 9.6 to 22.5 s
  /// (benchmarks/README.md "Held-out probes of a scattered database", last paragraph).
  bool compare_methods = false;
  /// Recover the interfaces' modal stresses with every sample (docs/theory.md §6.5; about
  /// 6 × points × (modes + 5) values per sample). false: a vibration-only database.
  bool stresses = true;
  /// Ranks the samples are distributed over. MPI_COMM_NULL = everything in this process, no MPI
  /// call at all. Otherwise the call is collective over the communicator.
  MPI_Comm communicator = MPI_COMM_NULL;
  /// Called on every rank after each of its own samples: (done, total) of this rank's share.
  std::function<void(int done, int total)> progress;
};

/// Build the database over `options.axes` from the base configuration (already carrying any --set
/// overrides). Collective over options.communicator; the complete database is returned on rank 0,
/// an empty one (no samples) on the other ranks. Throws InputError for bad options, NumericalError
/// naming the sample and its parameters when a modal solve fails (on every rank alike).
RomDatabase buildDatabase(const Config& base, const DatabaseBuildOptions& options,
                          BuildReport* report = nullptr);

}  // namespace mastrom::rom
