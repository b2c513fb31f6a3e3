// rom eval's stress peaks (rom/studies/rom_evaluation.hpp, docs/theory.md §6.5): found on the
// metrics' grid (a screen's 2 ms, refined between its samples) or, with a fine output step the
// user set, streamed over the output samples; either way the peak of the continuous response. The
// reference is the same modal model's brute force: every 1 µs sample of the stress history
// (ωΔ ≈ 0.01 for the mode that carries the stress), polished by the parabola through its
// neighbours.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "fullorder/mast_config.hpp"
#include "rom/model/modal_stress_extraction.hpp"
#include "rom/model/modal_stress_response.hpp"
#include "rom/studies/rom_evaluation.hpp"
#include "rom/studies/screen_kernel.hpp"
#include "tests/rom/direct_modal_solve.hpp"
#include "tests/rom/fixed_model.hpp"

namespace mastrom::rom {
namespace {

using testing::FixedModel;

TEST(RomEvalStressPeaks, PeaksOnTheMetricsGridAreTheContinuousPeaks) {
  Config c = testing::scheme1Config(10);
  testing::DirectSolve d = testing::directModalSolve(c, 10);
  d.modal.stress =
      extractModalStress(d.model, d.lin.problem, d.lin.q, d.eig.modes, d.eig.eigenvalues_rad2_s2);
  const ModalModel& m = d.modal;
  const FixedModel interpolator(m);

  // The brute force: every 1 µs sample of the history, its peak polished between them.
  ModalDeploymentOptions fine;
  fine.end_time_s = c.simulation.end_time_s;
  fine.step_s = 1e-6;
  const fullorder::InterfaceStressResult ref =
      modalInterfaceStresses(m, fullorder::DriveLaw(fullorder::driveFromConfig(c)), fine, false);

  // (a) the default: metrics and peaks on a screen's 2 ms grid, a coarse output step;
  // (b) an output step the user set, fine enough for the samples' polish: the stream over them.
  RomEvaluationInput coarse;
  coarse.config = c;
  coarse.config.output.step_s = 1e-4;
  coarse.metrics_step_s = kDefaultScreenStepS;
  RomEvaluationInput streamed;
  streamed.config = c;
  streamed.config.output.step_s = 1e-5;
  streamed.metrics_step_s = 0.0;
  const double omega_1 = m.omega_rad_s[0];
  for (const RomEvaluationInput* input : {&coarse, &streamed}) {
    const RomEvaluation e = evaluateRomDeployment(interpolator, *input);
    ASSERT_TRUE(e.stresses.has_value());
    ASSERT_EQ(e.stresses->peak.size(), ref.peak.size());
    EXPECT_EQ(e.stresses->time_s.size(), e.series.size());  // the output instants
    for (std::size_t i = 0; i < ref.peak.size(); ++i) {
      const fullorder::InterfaceStressPeak& p = e.stresses->peak[i];
      const fullorder::InterfaceStressPeak& r = ref.peak[i];
      const double field_max =
          *std::max_element(p.field_von_mises_pa.begin(), p.field_von_mises_pa.end());
      std::printf(
          "[ measured ] metrics step %.3g s, interface %zu: peak %+.2e of the 1 us "
          "brute force's, at %+.2e s of its instant; field at the peak's instant, max "
          "%+.2e of the peak\n",
          e.metrics_step_s, i + 1, p.von_mises_pa / r.von_mises_pa - 1.0, p.time_s - r.time_s,
          field_max / p.von_mises_pa - 1.0);
      // The refinement's tolerance is 1e-4 of the peak on an estimated polish error, the brute
      // force's own polish error 0.0234 (ωΔ)⁴ ≈ 1e-10: the bound of CoarseGridPeaksAreRefined-
      // BetweenSamples (test_modal_stress.cpp), 5e-4.
      EXPECT_NEAR(p.von_mises_pa, r.von_mises_pa, 5e-4 * r.von_mises_pa);
      // A value within δ of a smooth maximum A cos(ω(t − t*)) is within (2δ)^½/ω of its instant.
      EXPECT_NEAR(p.time_s, r.time_s, std::sqrt(2.0 * 5e-4) / omega_1);
      // Continuous in time: the field is the state's at the peak's own instant, whose largest
      // station is the peak (up to the polish, which the exact value replaces where trusted).
      EXPECT_NEAR(field_max, p.von_mises_pa, 5e-4 * p.von_mises_pa);
    }
  }
}

}  // namespace
}  // namespace mastrom::rom
