// The paper's qualitative findings (Liu & Wen 2024 §3; docs/theory.md §1), asserted on the metrics
// of our model for the study files in configs/studies/ — not tuned: where our model (aluminium
// shells and Kelvin–Voigt damping μ = 1e-5 s are assumptions) gives something else, the test
// asserts what the model gives and says why.
//
// Models. Scheme 1/2/3 run with the nonlinear full order on a short drive (0.15 s, record 0.18 s),
// each with a time step that resolves its own first bending mode by ≥ 30 steps per period (the
// frequency taken from the case's modal model). Every other study runs the full-size case (90° in
// 6.1 s, 8 s record, Δt = 0.1 ms) with the ROM solved at the case's own parameters
// (rom/offline/direct_modal_model.hpp; ≈ 0.1 s per case): its agreement with the full order is what
// `mastrom compare` / `validate` check elsewhere; on the short Scheme runs it must at least give
// the full order's orderings.
//
// Margins. An ordering a > b is asserted as a > (1 + kRomMargin) b, so that it survives the ROM's
// own error against the full order: kRomMargin = 5 % is above the ROM-vs-full differences of every
// metric on the full-size cases (`mastrom study schemes`, measured 2026-11: Scheme 3 at Δt = 100 µs
// ≤ 3.6 %, Scheme 1 at 25 µs ≤ 1.5 %). Orderings whose gap is below that margin are asserted
// without it and say so (shell thickness 1.0 vs 1.5 mm peak, inner diameter peak).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "rom/studies/study_definition.hpp"
#include "rom/studies/study_run.hpp"

namespace mastrom::rom {
namespace {

constexpr double kRomMargin = 0.05;

std::string studyFile(const std::string& name) {
  return std::string(MASTROM_SOURCE_DIR) + "/configs/studies/" + name + ".toml";
}

/// ROM results of every case of a study at its full size, by case name.
std::map<std::string, RomCaseResult> romStudy(const std::string& name) {
  const Study study = loadStudy(studyFile(name), {});
  std::map<std::string, RomCaseResult> out;
  for (const StudyCase& c : study.cases) {
    out[c.name] = runRomCase(c.config);
    const fullorder::DeploymentMetrics& m = out[c.name].metrics;
    std::printf(
        "  %s/%-12s ROM: f1 %.2f Hz, decay 1/(zeta w) %.4f s, peak|abs| %.5g, peak|rel| "
        "%.5g, rms rel %.5g, residual %.5g rad/s^2, settling %.4f s, F %.4g N\n",
        name.c_str(), c.name.c_str(), out[c.name].first_bending_hz,
        out[c.name].first_bending_decay_s, m.peak_abs_end_angular_acceleration,
        m.peak_rel_end_angular_acceleration, m.rms_rel_end_angular_acceleration,
        m.residual_rel_end_angular_acceleration, m.settling_time, m.peak_joint_force);
  }
  return out;
}

/// a > (1 + margin) b, with both values in the message.
::testing::AssertionResult clearlyGreater(double a, double b, const char* what,
                                          double margin = kRomMargin) {
  if (a > (1.0 + margin) * b) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << what << ": " << a << " is not > (1 + " << margin << ") x " << b;
}

// [LW24] §3.1, P-Figs 7–8: more modules → larger peak joint force and peak end angular
// acceleration. Full order, short drive; the ROM of the same cases must agree with it on the
// metrics.
TEST(PaperFindings, SchemeThreeAboveTwoAboveOneFullOrder) {
  const std::vector<std::string> shorten = {"drive.duration=0.15", "drive.ramp=0.0375",
                                            "simulation.end_time=0.18"};
  const Study study = loadStudy(studyFile("schemes"), shorten);
  ASSERT_EQ(study.cases.size(), 3u);
  std::vector<fullorder::DeploymentMetrics> full, rom_metrics;
  for (const StudyCase& c : study.cases) {
    const RomCaseResult rom = runRomCase(c.config);
    // ≥ 30 steps per period of the first bending mode (Scheme 1: 1.66 kHz → 20 µs), and a step
    // that divides the record so that both models sample the same instants.
    Config config = c.config;
    const double period_s = 1.0 / rom.first_bending_hz;
    const double steps = std::ceil(config.simulation.end_time_s / (period_s / 32.0));
    config.simulation.time_step_s = config.simulation.end_time_s / steps;
    ASSERT_GE(period_s / config.simulation.time_step_s, 30.0);
    const CaseResult f = runFullOrderCase(config);
    full.push_back(f.metrics);
    const RomCaseResult r = runRomCase(config);
    std::printf(
        "  %s: f1 %.1f Hz, dt %.3g s; full: peak|abs| %.5g rad/s^2, F %.5g N, wall %.2f "
        "s; ROM: peak|abs| %.5g rad/s^2, F %.5g N, wall %.3f s\n",
        c.name.c_str(), rom.first_bending_hz, config.simulation.time_step_s,
        f.metrics.peak_abs_end_angular_acceleration, f.metrics.peak_joint_force, f.wall_s,
        r.metrics.peak_abs_end_angular_acceleration, r.metrics.peak_joint_force, r.wall_s);
    rom_metrics.push_back(r.metrics);
  }
  // The full order is the reference here, so the orderings need no ROM margin; the ROM must give
  // the same orderings (its metrics differ from the full order's by up to 7 % on this violent
  // drive — 90° in 0.15 s, θ̇ up to 13 rad/s — against ≤ 3.6 % on the 6.1 s drive).
  for (int i : {1, 2}) {
    for (const auto* m : {&full, &rom_metrics}) {
      const char* model = m == &full ? "full order" : "ROM";
      EXPECT_GT((*m)[i].peak_joint_force, (*m)[i - 1].peak_joint_force)
          << model << ", peak joint force, scheme " << i + 1 << " vs " << i;
      EXPECT_GT((*m)[i].peak_abs_end_angular_acceleration,
                (*m)[i - 1].peak_abs_end_angular_acceleration)
          << model << ", peak |abs| end angular acceleration, scheme " << i + 1 << " vs " << i;
    }
  }
}

// The same finding on the full-size cases (trapezoidal drive, 90° in 6.1 s), with the ROM.
TEST(PaperFindings, SchemeThreeAboveTwoAboveOneFullSizeRom) {
  const std::map<std::string, RomCaseResult> r = romStudy("schemes");
  for (const auto& [hi, lo] : {std::pair{"scheme3", "scheme2"}, std::pair{"scheme2", "scheme1"}}) {
    EXPECT_TRUE(clearlyGreater(r.at(hi).metrics.peak_joint_force, r.at(lo).metrics.peak_joint_force,
                               "peak joint force"))
        << hi << " vs " << lo;
    EXPECT_TRUE(clearlyGreater(r.at(hi).metrics.peak_abs_end_angular_acceleration,
                               r.at(lo).metrics.peak_abs_end_angular_acceleration,
                               "peak |abs| end angular acceleration"))
        << hi << " vs " << lo;
  }
}

// [LW24] §3.2, P-Figs 9–10, 14: thinner shell → larger relative end vibration and slower decay. In
// our model the decay of the first bending mode is set by Kelvin–Voigt damping, ζω = μω²/2, so a
// softer (thinner) shell decays more slowly by construction; the settling time shows it in the
// response.
TEST(PaperFindings, ThinnerShellVibratesMoreAndDecaysSlower) {
  const std::map<std::string, RomCaseResult> r = romStudy("shell_thickness");
  for (const auto& [thin, thick] : {std::pair{"h0.5mm", "h1.0mm"}, std::pair{"h1.0mm", "h1.5mm"}}) {
    const fullorder::DeploymentMetrics& a = r.at(thin).metrics;
    const fullorder::DeploymentMetrics& b = r.at(thick).metrics;
    // Peak: 6.52 > 5.59 > 5.35 rad/s²; the 1.0 → 1.5 mm step (4.4 %) is inside the ROM margin,
    // so it is asserted without it (the RMS below separates them by 21 %).
    const double peak_margin = std::string(thin) == "h1.0mm" ? 0.0 : kRomMargin;
    EXPECT_TRUE(clearlyGreater(a.peak_rel_end_angular_acceleration,
                               b.peak_rel_end_angular_acceleration, "peak |rel|", peak_margin))
        << thin << " vs " << thick;
    EXPECT_TRUE(clearlyGreater(a.rms_rel_end_angular_acceleration,
                               b.rms_rel_end_angular_acceleration, "rms rel"))
        << thin << " vs " << thick;
    EXPECT_TRUE(clearlyGreater(r.at(thin).first_bending_decay_s, r.at(thick).first_bending_decay_s,
                               "decay time 1/(zeta omega) of the first bending mode"))
        << thin << " vs " << thick;
    // Settling after the drive stops at 6.1 s: compare the time spent settling, t_s − t_d.
    EXPECT_TRUE(clearlyGreater(a.settling_time - a.drive_end_time,
                               b.settling_time - b.drive_end_time, "settling time after the drive"))
        << thin << " vs " << thick;
  }
}

// [LW24] §3.2, P-Figs 11–12: larger inner diameter → smaller vibration. In our model the RMS of the
// relative end angular acceleration (the vibration over the whole record) falls clearly with the
// diameter (measured 15.3, 14.2, 12.5 deg/s² for 85/90/100 mm). Its peak does not separate 85 from
// 90 mm (261.1 vs 260.8 deg/s², 0.1 %, far inside the ROM's error), and the residual amplitude
// after the drive is not monotonic at all (252, 248, 253 deg/s²): the peak sits at the drive's
// stop, where the phase of the bending oscillation at the instant of the deceleration jump (f1 =
// 351, 379, 436 Hz) decides whether the jump adds to or cancels the vibration. So only the RMS
// ordering and the 85 → 100 mm peak drop (3 %) are properties of our model; the peak drop is below
// the 5 % margin and is therefore asserted without it.
TEST(PaperFindings, LargerInnerDiameterVibratesLess) {
  const std::map<std::string, RomCaseResult> r = romStudy("inner_diameter");
  EXPECT_TRUE(clearlyGreater(r.at("D85mm").metrics.rms_rel_end_angular_acceleration,
                             r.at("D90mm").metrics.rms_rel_end_angular_acceleration, "rms rel"));
  EXPECT_TRUE(clearlyGreater(r.at("D90mm").metrics.rms_rel_end_angular_acceleration,
                             r.at("D100mm").metrics.rms_rel_end_angular_acceleration, "rms rel"));
  EXPECT_GT(r.at("D85mm").metrics.peak_rel_end_angular_acceleration,
            r.at("D100mm").metrics.peak_rel_end_angular_acceleration);
  // Stiffer interfaces: the first bending frequency rises with the diameter (R³ h bending).
  EXPECT_LT(r.at("D85mm").first_bending_hz, r.at("D90mm").first_bending_hz);
  EXPECT_LT(r.at("D90mm").first_bending_hz, r.at("D100mm").first_bending_hz);
}

// [LW24] §3.3, P-Figs 13–14: of the cubic, quintic and cycloidal laws the cubic excites the largest
// end vibration (θ̈ jumps by 6Θ/T² at start and stop), the cycloidal the smallest. In our model the
// quintic and cycloidal laws (θ̈ continuous) leave almost no vibration (≈ 1e-4 rad/s² against
// ≈ 0.46 rad/s² for the cubic, 6.1 s drive), and the cycloidal is below the quintic by ≈ 35 %.
TEST(PaperFindings, CubicLawVibratesMostCycloidalLeast) {
  const std::map<std::string, RomCaseResult> r = romStudy("drive_laws");
  const auto peak = [&r](const char* law) {
    return r.at(law).metrics.peak_rel_end_angular_acceleration;
  };
  const auto rms = [&r](const char* law) {
    return r.at(law).metrics.rms_rel_end_angular_acceleration;
  };
  EXPECT_TRUE(clearlyGreater(peak("cubic"), peak("quintic"), "peak |rel| cubic vs quintic"));
  EXPECT_TRUE(
      clearlyGreater(peak("quintic"), peak("cycloidal"), "peak |rel| quintic vs cycloidal"));
  EXPECT_TRUE(clearlyGreater(rms("cubic"), rms("quintic"), "rms rel cubic vs quintic"));
  EXPECT_TRUE(clearlyGreater(rms("quintic"), rms("cycloidal"), "rms rel quintic vs cycloidal"));
}

}  // namespace
}  // namespace mastrom::rom
