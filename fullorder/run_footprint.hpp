// What a full-order model and run will hold in memory and write, counted from the configuration
// alone, before anything is built (common/resource_budget.hpp checks it against the machine).
//
// Sizes (docs/theory.md §2): module k has 12 natural coordinates and 6 internal constraints; an
// interface of N_a × N_c elements has (N_a + 1) N_c nodes of 9 coordinates and 7 bonded-edge
// equations per node of its two end rings; the base joint adds 6 equations.
//
// Memory: a fixed part (the program, its libraries, MPI and PETSc initialisation) plus a part per
// shell element for the model, its sparse matrices with fixed patterns and the factorisations the
// integrator keeps (current and spare iteration matrix, the mass saddle factor), and a part in
// elements × interfaces: today's memory grows faster than the chain's length (measured). The
// coefficients are measured peaks (benchmarks/README.md "Resource estimates" compares the
// estimate with the measured peak RSS at several sizes).
//
// Result: per output instant the §5.3 time series (23 doubles and one 32-bit int) and, per
// interface, the stress histories (21 doubles in the file, 13 in memory). `simulate` streams both
// to its file (fullorder/result_stream.hpp), so its memory does not grow with the horizon.
#pragma once

#include <string>

#include "common/config.hpp"
#include "common/resource_budget.hpp"

namespace mastrom::fullorder {

/// The sizes of a mast described by a configuration.
struct MastSize {
  int modules = 0;
  int interfaces = 0;
  double elements = 0;     ///< shell elements
  double dofs = 0;         ///< coordinates before elimination
  double constraints = 0;  ///< constraint equations before elimination
};
MastSize mastSize(const Config& config);

/// Peak resident memory of a process that builds the mast and integrates it (or solves its modes
/// with a sparse factorisation) [bytes], without the outputs.
double fullOrderModelBytes(const MastSize& size);

/// Output instants of a `simulate` run: adaptive runs every output.step up to end_time and the end;
/// fixed steps every output.every-th step and the last.
double outputSampleCount(const Config& config);

/// Bytes per output instant in a result file: the §5.3 datasets and the interface stress
/// histories (`with_stresses`).
double resultBytesPerSample(const MastSize& size, bool with_stresses);

/// The estimate of `simulate`. Streamed (series_in_memory false), the series and the interface
/// stress histories (with_stresses) cost one block each in memory; the relative end angular
/// acceleration for the error estimate (estimate_error, 8 bytes per instant) is held. A caller
/// that holds the series (series_in_memory: `validate`'s full-order runs; `simulate` streams, with
/// checkpoints too) holds the step points, the output series and the stress histories (the series
/// twice with the estimate's second run).
ResourceEstimate simulateEstimate(const Config& config, bool series_in_memory, bool with_stresses,
                                  bool estimate_error = false);

/// Memory of `samples` output instants of interface stress histories while a run gathers and
/// resamples them [bytes].
double stressHistoryMemoryBytes(const MastSize& size, double samples);
/// Memory of a deployment series of `samples` instants held in memory [bytes].
double seriesMemoryBytes(double samples);

/// The keys that size the mast, with their values, for refusal messages.
std::vector<ResourceDriver> mastDrivers(const Config& config);
/// The keys that set the number of output instants, with their values.
std::vector<ResourceDriver> horizonDrivers(const Config& config);

/// "%.3g" of a count, for the detail of an estimate.
std::string countText(double count);

}  // namespace mastrom::fullorder
