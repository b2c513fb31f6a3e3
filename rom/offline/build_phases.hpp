// The per-rank phases a database build is made of, shared by the tensor-grid build
// (rom/offline/database_build.hpp) and the adaptive one (rom/offline/adaptive_build.hpp): solve and
// track this rank's samples against the reference (which every rank solves itself), pack them for
// the gather, and turn what every rank packed into the database's samples and the tracking report.
#pragma once

#include <chrono>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "rom/database/build_report.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/offline/sample_exchange.hpp"
#include "rom/offline/sample_solve.hpp"

namespace mastrom::rom {

using BuildClock = std::chrono::steady_clock;

inline double secondsSince(BuildClock::time_point start) {
  return std::chrono::duration<double>(BuildClock::now() - start).count();
}

/// What one rank's phase produced, and how it failed (if it did): every rank must learn of a
/// failure anywhere before the next collective call (throwIfAnyRankFailed).
struct RankOutcome {
  std::vector<double> values;
  std::string error;
  bool numerical = false;
};

/// Run `work` and turn its exception, if any, into the outcome's error (prefixed by `what`).
template <class Work>
void runCatching(RankOutcome& outcome, const char* what, Work&& work) {
  try {
    work();
  } catch (const NumericalError& e) {
    outcome.error = e.what();
    outcome.numerical = true;
  } catch (const Error& e) {
    outcome.error = e.what();
  } catch (const std::exception& e) {
    outcome.error = std::string(what) + e.what();
  }
}

/// What every sample of a build is solved with.
struct SampleSettings {
  Config base;
  std::vector<ParameterAxis> axes;
  int modes = 0;
  EigenBackendKind backend = EigenBackendKind::Slepc;
  bool stresses = true;
};

/// Solve times summed over a rank's solves [s]: assembly, eigensolve, extraction + tracking, and
/// the number of solves.
struct SolveTimes {
  double assembly_s = 0.0, eigensolve_s = 0.0, extraction_s = 0.0;
  int solves = 0;
  void add(const SampleSolution& s);
};

/// The reference sample's solution (every rank solves it; its degenerate clusters made canonical).
SampleSolution solveReference(const SampleSettings& settings, const std::vector<double>& point,
                              int index, SolveTimes& times);

/// This rank's share of the samples `points` (sample index first + i for points[i]; this rank
/// takes the indices ≡ rank mod size), each solved and tracked against `reference`, packed into
/// `out.values`. The reference's own index (`reference_index`) is packed from `reference` without
/// a solve. `progress(done, share)` after each.
void solveShare(const SampleSettings& settings, const std::vector<std::vector<double>>& points,
                int first, const SampleSolution& reference, int reference_index, int rank, int size,
                SolveTimes& times, RankOutcome& out,
                const std::function<void(int, int)>& progress = {});

/// The gathered samples (`all`, every rank's packing) into db.samples[index] (db.samples already
/// sized; every index in [first, first + count) must arrive exactly once), with their parameters
/// from `points` (index − first) and the tracking quality in `rep`.
void collectSamples(const std::vector<double>& all, const std::vector<std::vector<double>>& points,
                    int first, RomDatabase& db, BuildReport& rep);

}  // namespace mastrom::rom
