// The stress peaks from the starts of a deployment's blocks (rom/model/stress_blocks.hpp,
// docs/theory.md §6.5 "Blocks instead of samples"): each block's stress bound against the
// stresses of the same deployment sampled 32 times finer (brute force), and the peaks against
// those of every sample's recorded state (findStressPeaks), bit for bit. And the closed-form state
// inside an interval that the peaks' polish evaluates (stress_interval_refiner.hpp) against the
// exact maps of the same length.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "direct_modal_solve.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_stress_extraction.hpp"
#include "rom/model/modal_stress_response.hpp"
#include "rom/model/quiet_blocks.hpp"
#include "rom/model/stress_blocks.hpp"
#include "rom/model/stress_interval_refiner.hpp"

namespace mastrom::rom {
namespace {

/// Scheme 3 on a coarse interface mesh (1 × 8), 10 modes, with its modal stresses: solved once.
const ModalModel& coarseScheme3WithStresses() {
  static const ModalModel m = [] {
    testing::DirectSolve d = testing::directModalSolve(testing::coarseScheme3Config(), 10);
    d.modal.stress =
        extractModalStress(d.model, d.lin.problem, d.lin.q, d.eig.modes, d.eig.eigenvalues_rad2_s2);
    d.modal.validate();
    return d.modal;
  }();
  return m;
}

ModalDeploymentOptions optionsWithStep(double step_s, double end_time_s) {
  ModalDeploymentOptions o;
  o.end_time_s = end_time_s;
  o.step_s = step_s;
  return o;
}

/// The block record of one metrics pass.
void recordBlocks(const ModalModel& m, const SampledDrive& sampled, double drive_end_s,
                  StressBlockRecord& record) {
  const ModalBlockObserver observe = record.observer();
  modalDeploymentMetrics(m, sampled, false, drive_end_s, fullorder::kDefaultSettlingBandRadS2,
                         PeakResolution::Continuous, nullptr, &observe);
}

/// Restores the default (quiet blocks on) when a test ends.
struct QuietBlocksSetting {
  explicit QuietBlocksSetting(bool on) { metrics_detail::quietBlocksEnabled() = on; }
  ~QuietBlocksSetting() { metrics_detail::quietBlocksEnabled() = true; }
};

TEST(StressBlocks, BoundsHoldOverEveryBlockAgainstFineSamples) {
  // Each interface's bound over each block against its largest von Mises stress at every sample
  // of the same deployment stepped 32 times finer (whose forcing's first-order hold differs from
  // the coarse one by O(Δ²) of the drive's curvature: a relative 1e-6 allowance, as for the
  // quiet blocks' own bounds).
  const ModalModel& m = coarseScheme3WithStresses();
  const ModalStressEvaluator ev(m);
  constexpr long kFine = 32;
  const double step = 2e-3, end = 1.0;
  for (const DriveLawKind law :
       {DriveLawKind::Trapezoidal, DriveLawKind::Cubic, DriveLawKind::Cycloidal}) {
    const fullorder::DriveLawParameters p = testing::compressedDrive(law);
    const fullorder::DriveLaw drive(p);
    SCOPED_TRACE(toString(law));
    const SampledDrive sampled = sampleDrive(drive, optionsWithStep(step, end));
    StressBlockRecord record(ev, m, sampled, false);
    recordBlocks(m, sampled, p.duration_s, record);
    const SampledDrive fine = sampleDrive(drive, optionsWithStep(step / kFine, end));
    const Eigen::MatrixXd states = modalStressStates(m, ev, fine, false);
    long bounded = 0;
    for (int i = 0; i < ev.interfaceCount(); ++i) {
      std::vector<double> history;
      ev.largestHistory(i, states, history);
      double worst = 0.0;  // largest stress / its block's bound
      for (long b = 0; b < record.blockCount(); ++b) {
        const double bound = record.blockBound(i, b);
        if (!std::isfinite(bound)) continue;
        ++bounded;
        const long first = b * SampledDrive::kBlockSteps * kFine;
        const long last =
            std::min(first + SampledDrive::kBlockSteps * kFine, sampled.steps * kFine);
        for (long j = first; j <= last; ++j) {
          const double v = history[static_cast<std::size_t>(j)];
          EXPECT_LE(v, bound * (1.0 + 1e-6)) << "interface " << i << " block " << b;
          worst = std::max(worst, v / bound);
        }
      }
      std::printf("[ measured ] %s, interface %d: largest stress / block bound %.4f\n",
                  toString(law).c_str(), i + 1, worst);
    }
    // Most blocks are bounded (only those with a breakpoint are not), or the check proves little.
    EXPECT_GT(bounded, ev.interfaceCount() * record.blockCount() / 2);
  }
}

TEST(StressBlocks, PeaksAreThoseOfEverySamplesRecordedState) {
  // The peaks from the blocks (best block first, re-stepped) against findStressPeaks on every
  // sample's recorded η, η̇ and x: value, instant, sample and station bit for bit, and the state at
  // each peak's instant too — on a grid coarse for the polish (refined between samples: 2 ms and
  // 1 ms, ωΔ ≈ 2–4 for the bending modes) and on a fine one (0.1 ms, ωΔ ≈ 0.2). Without quiet
  // blocks (no bounds: every block re-stepped) as well. The search must also have pruned: fewer
  // blocks re-stepped than the deployment has, or the comparison would not test the bounds.
  const ModalModel& m = coarseScheme3WithStresses();
  const ModalStressEvaluator ev(m);
  for (const DriveLawKind law :
       {DriveLawKind::Trapezoidal, DriveLawKind::Cubic, DriveLawKind::Cycloidal}) {
    for (const double step : {2e-3, 1e-3, 1e-4}) {
      for (const bool quiet : {true, false}) {
        SCOPED_TRACE(toString(law) + " step " + std::to_string(step) +
                     (quiet ? "" : " without quiet blocks"));
        const QuietBlocksSetting setting(quiet);
        const fullorder::DriveLawParameters p = testing::compressedDrive(law);
        const SampledDrive sampled =
            sampleDrive(fullorder::DriveLaw(p), optionsWithStep(step, 1.0));
        const std::vector<char> no_polish = samplesNearBreakpoints(sampled);
        StressBlockRecord record(ev, m, sampled, false);
        recordBlocks(m, sampled, p.duration_s, record);
        const std::vector<ModalStressEvaluator::Peak> from_blocks = record.peaks(no_polish);
        const long replayed = record.distinctBlocksReplayed();
        const std::vector<Eigen::VectorXd> at_blocks =
            stressPeakStates(ev, m, sampled, record, from_blocks);

        Eigen::MatrixXd eta, eta_dot;
        const Eigen::MatrixXd states = modalStressStates(m, ev, sampled, false, &eta, &eta_dot);
        const bool refine = stressPeaksNeedRefinement(ev, m, step);
        if (!refine) eta.resize(0, 0);
        const std::vector<ModalStressEvaluator::Peak> recorded =
            findStressPeaks(ev, states, no_polish, m, sampled, eta, eta_dot);
        ASSERT_EQ(from_blocks.size(), recorded.size());
        for (std::size_t i = 0; i < recorded.size(); ++i) {
          EXPECT_EQ(from_blocks[i].von_mises_pa, recorded[i].von_mises_pa) << "interface " << i;
          EXPECT_EQ(from_blocks[i].sample, recorded[i].sample);
          EXPECT_EQ(from_blocks[i].nearest_sample, recorded[i].nearest_sample);
          EXPECT_EQ(from_blocks[i].station, recorded[i].station);
          EXPECT_EQ(from_blocks[i].sample_von_mises_pa, recorded[i].sample_von_mises_pa);
        }
        if (refine) {
          const std::vector<Eigen::VectorXd> at_recorded =
              stressPeakStates(ev, m, sampled, eta, eta_dot, recorded);
          for (std::size_t i = 0; i < recorded.size(); ++i) {
            EXPECT_TRUE(at_blocks[i] == at_recorded[i]) << "interface " << i;
          }
        }
        std::printf(
            "[ measured ] %s, %g ms%s: %ld of %ld blocks re-stepped (%ld times; "
            "refined: %s)\n",
            toString(law).c_str(), 1e3 * step, quiet ? "" : ", no quiet blocks", replayed,
            record.blockCount(), record.blocksReplayed(), refine ? "yes" : "no");
        if (quiet) {
          EXPECT_LT(replayed, record.blockCount() / 2);
        }
      }
    }
  }
}

TEST(StressBlocks, ClosedFormStateInsideAnIntervalIsTheExactMapsState) {
  // The state a share of the way into an interval, in closed form (under-damped modes: the
  // particular solution of the linear forcing plus the decaying free oscillation) against one
  // step of the exact maps of that length (4 × 4 exponentials, docs/theory.md (4.4)): both exact,
  // so equal to round-off — 1e-11 of the state's largest modal entry (the maps' balanced Padé
  // exponential is good to ≈ 1e-13 relative per step). Intervals in the ramps (θ̈ and θ̇² change
  // over them), the cruise and after the drive (free decay), fractions across (0, 1].
  const ModalModel& m = coarseScheme3WithStresses();
  const ModalStressEvaluator ev(m);
  const fullorder::DriveLawParameters p = testing::compressedDrive(DriveLawKind::Trapezoidal);
  const SampledDrive sampled = sampleDrive(fullorder::DriveLaw(p), optionsWithStep(2e-3, 1.0));
  Eigen::MatrixXd eta, eta_dot;
  modalStressStates(m, ev, sampled, false, &eta, &eta_dot);
  const ModalStepping ms = prepareModalStepping(m, sampled, false);
  StressRefinementStats stats;
  stress_detail::IntervalRefiner refiner(ev, m, ms, stats);
  Eigen::VectorXd closed(ev.inputSize()), maps(ev.inputSize());
  long checked = 0;
  for (const long n : {3L, 11L, 40L, 100L, 180L, 250L, 400L}) {
    ASSERT_LT(n, sampled.steps);
    refiner.prepare(eta.col(n), eta_dot.col(n), sampled.startOf(n), sampled.endAt(n + 1),
                    sampled.step_s);
    for (const double fraction : {0.013, 0.25, 0.5, 0.71, 0.999, 1.0}) {
      refiner.stateAt(fraction, closed);
      refiner.stateAtByMaps(fraction, maps);
      const double scale = maps.head(m.modeCount()).cwiseAbs().maxCoeff();
      ASSERT_GT(scale, 0.0);
      for (int j = 0; j < ev.inputSize(); ++j) {
        EXPECT_NEAR(closed[j], maps[j], 1e-11 * scale)
            << "step " << n << " fraction " << fraction << " input " << j;
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 42);
}

}  // namespace
}  // namespace mastrom::rom
