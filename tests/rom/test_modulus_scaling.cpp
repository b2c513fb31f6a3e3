// Young's modulus handled exactly (rom/model/modulus_scaling.hpp, rom/offline/modulus_reduction.hpp,
// docs/theory.md §4.4 (e)) on a small real mast (Scheme 1, mesh 2 × 8, dense modal solves,
// compressed drive): the scaled model against direct modal solves at another E, a database that
// samples the other axes only against a direct solve at a held-out E, and gravity, which breaks
// the scaling and keeps E sampled.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include <Eigen/QR>

#include "common/error.hpp"
#include "rom/database/database_io.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/model/modal_stress_extraction.hpp"
#include "rom/model/modulus_scaling.hpp"
#include "rom/offline/adaptive_build.hpp"
#include "rom/offline/leave_one_out.hpp"
#include "rom/offline/modulus_reduction.hpp"
#include "direct_modal_solve.hpp"

namespace mastrom::rom {
namespace {

constexpr int kModes = 6;  // three whole pairs of the symmetric mast

Config atModulus(double youngs_modulus_pa, bool gravity = false) {
  Config c = testing::scheme1Config(kModes);
  c.material.youngs_modulus_pa = youngs_modulus_pa;
  // Along the stowed mast: its axial preload changes the bending frequencies to first order (a
  // load across the mast does so only to second order, by symmetry).
  if (gravity) c.simulation.gravity_m_s2 = {-9.81, 0.0, 0.0};
  return c;
}

/// The direct solve at `c`, with the interfaces' modal stresses.
testing::DirectSolve solveWithStresses(const Config& c) {
  testing::DirectSolve d = testing::directModalSolve(c, kModes);
  d.modal.stress = extractModalStress(d.model, d.lin.problem, d.lin.q, d.eig.modes,
                                      d.eig.eigenvalues_rad2_s2);
  return d;
}

/// Largest relative residual ‖Kφ − ω²Mφ‖ / (ω²‖Mφ‖) of the computed modes: the backward error of
/// the solve, which bounds how far a computed ω² and φ can be from the exact ones (relative to the
/// gaps) [Bat96 §11.3; Par98 ch. 11] — the round-off level the comparisons below are held to.
double relativeResidual(const testing::DirectSolve& d) {
  const auto& p = d.lin.problem;
  double r = 0.0;
  for (int k = 0; k < kModes; ++k) {
    const Eigen::VectorXd phi = d.eig.modes.col(k);
    const double w2 = d.eig.eigenvalues_rad2_s2[k];
    const Eigen::VectorXd m_phi = p.mass * phi;
    const Eigen::VectorXd res = p.stiffness * phi - w2 * m_phi;
    // Gᵀμ absorbs the part of the residual in the constraints' range: project it out.
    const Eigen::MatrixXd gt = Eigen::MatrixXd(p.constraint_jacobian.transpose());
    const Eigen::VectorXd mu = gt.colPivHouseholderQr().solve(res);
    r = std::max(r, (res - gt * mu).norm() / (w2 * m_phi.norm()));
  }
  return r;
}

TEST(ModulusScaling, ScaledModesEqualADirectSolveAtAnotherModulus) {
  const double e0 = 70e9, e1 = 80e9, ratio = e1 / e0;
  const testing::DirectSolve d0 = solveWithStresses(atModulus(e0));
  const testing::DirectSolve d1 = solveWithStresses(atModulus(e1));
  ModalModel scaled = d0.modal;
  scaleYoungsModulus(scaled, ratio);
  const ModalModel& direct = d1.modal;
  ASSERT_EQ(scaled.modeCount(), kModes);
  ASSERT_EQ(direct.modeCount(), kModes);

  // The solves' own accuracy: eigenvalues to O(residual), shapes to O(residual / relative gap);
  // the closest distinct pairs here are 10 % apart, so 100 × the residual covers both.
  const double eps = std::numeric_limits<double>::epsilon();
  const double residual = std::max(relativeResidual(d0), relativeResidual(d1));
  const double tol = 100.0 * std::max(residual, eps);
  std::printf("[ measured ] relative residual of the solves %.2g; tolerance %.2g\n", residual, tol);
  ASSERT_LT(tol, 1e-8);  // a round-off-level check, not a loose one

  for (int k = 0; k < kModes; ++k) {
    EXPECT_NEAR(scaled.omega_rad_s[k] / direct.omega_rad_s[k], 1.0, tol) << "mode " << k;
    EXPECT_NEAR(scaled.damping_ratio[k] / direct.damping_ratio[k], 1.0, tol) << "mode " << k;
  }
  // Shapes up to the basis of each degenerate pair (and sign): Q = Φ₀ᵀMΦ₁ is orthogonal and maps
  // every quantity linear in the shapes, x₁ = Qᵀx₀ (per mode), S₁ = r S₀ Q.
  const Eigen::MatrixXd q = d0.eig.modes.transpose() * (d1.lin.problem.mass * d1.eig.modes);
  EXPECT_LT((q.transpose() * q - Eigen::MatrixXd::Identity(kModes, kModes)).norm(), tol);
  const auto relative = [](const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    return (a - b).norm() / b.norm();
  };
  EXPECT_LT(relative(q.transpose() * scaled.rotation_participation, direct.rotation_participation),
            tol);
  EXPECT_LT(relative(scaled.end_rotation * q, direct.end_rotation), tol);
  EXPECT_LT(relative(scaled.momentum_participation * q, direct.momentum_participation), tol);
  EXPECT_LT(relative(q.transpose() * scaled.coriolis * q, direct.coriolis) , tol);
  EXPECT_DOUBLE_EQ(scaled.inertia_z_kg_m2, direct.inertia_z_kg_m2);
  // Stresses: modal ones × r, the static correction's unchanged, no preload.
  ASSERT_FALSE(direct.stress.empty());
  EXPECT_LT(relative(scaled.stress.modes * q, direct.stress.modes), tol);
  EXPECT_LT(relative(scaled.stress.loads, direct.stress.loads), tol);
  EXPECT_EQ(direct.stress.preload.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(scaled.stress.damping_s, direct.stress.damping_s);
}

TEST(ModulusScaling, DoesNotHoldWithGravityAndIsRefused) {
  // With gravity the preload's geometric stiffness does not scale with E: the frequency ratio of
  // two direct solves departs from √(E₁/E₀) far beyond the solves' accuracy. The scaling refuses
  // such a model, and a build keeps E sampled, saying why.
  const double e0 = 70e9, e1 = 80e9;
  const ModalModel m0 = testing::directModalSolve(atModulus(e0, true), kModes).modal;
  const ModalModel m1 = testing::directModalSolve(atModulus(e1, true), kModes).modal;
  double departure = 0.0;
  for (int k = 0; k < kModes; ++k)
    departure = std::max(departure,
                         std::abs(m1.omega_rad_s[k] / m0.omega_rad_s[k] / std::sqrt(e1 / e0) - 1));
  std::printf("[ measured ] with gravity, largest departure from sqrt(E1/E0): %.2g\n", departure);
  EXPECT_GT(departure, 1e-8);
  ModalModel copy = m0;
  EXPECT_THROW(scaleYoungsModulus(copy, e1 / e0), InputError);

  const Config g = atModulus(e0, true);
  const std::vector<ParameterAxis> axes = {
      parseParameterAxis("interface.thickness=0.001:0.002", g, AxisForm::Range),
      parseParameterAxis("material.youngs_modulus=60e9:80e9", g, AxisForm::Range)};
  const ModulusReduction with_gravity = planModulusReduction(g, axes);
  EXPECT_FALSE(with_gravity.applies());
  EXPECT_NE(with_gravity.reason.find("with gravity"), std::string::npos) << with_gravity.reason;
  const ModulusReduction without = planModulusReduction(atModulus(e0), axes);
  EXPECT_TRUE(without.applies());
  EXPECT_EQ(without.axis, 1);
  EXPECT_DOUBLE_EQ(without.reference_pa, std::sqrt(60e9 * 80e9));
  EXPECT_NE(without.reason.find("handled exactly"), std::string::npos) << without.reason;
  // E alone: nothing else to sample, so it is sampled.
  EXPECT_FALSE(planModulusReduction(atModulus(e0), {axes[1]}).applies());
}

TEST(ModulusScaling, ADatabaseThatSamplesTheOtherAxesMatchesADirectSolveAtAHeldOutModulus) {
  const Config c = atModulus(70e9);
  DatabaseBuildOptions o;
  o.axes = {parseParameterAxis("material.youngs_modulus=60e9:80e9", c, AxisForm::Range),
            parseParameterAxis("interface.thickness=0.001:0.002", c, AxisForm::Range)};
  AdaptiveBuildOptions a;
  a.tolerance = 0.5;  // the initial design is enough: 2p + 1 = 3 samples along the thickness
  a.max_samples = 5;
  const RomDatabase db = buildAdaptiveDatabase(c, o, a);
  const double e0 = std::sqrt(60e9 * 80e9);
  ASSERT_TRUE(db.exact_modulus.has_value());
  EXPECT_DOUBLE_EQ(db.exact_modulus->reference_pa, e0);
  ASSERT_EQ(db.axes.size(), 2u);
  EXPECT_EQ(db.axes[0].key, kYoungsModulusKey);
  EXPECT_EQ(db.axes[0].values, (std::vector<double>{60e9, 80e9}));
  ASSERT_GE(db.samples.size(), 3u);
  for (const RomSample& s : db.samples) EXPECT_EQ(s.parameters[0], e0);
  // The stored configuration keeps the user's E.
  EXPECT_EQ(parseConfigText(db.base_config_toml, "db").material.youngs_modulus_pa, 70e9);

  // Through a file and back: the reduction is recorded, the checksum covers it.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("mastrom_modulus_scaling_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "db.h5").string();
  writeDatabase(path, db);
  const RomDatabase back = readDatabase(path);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(back.exact_modulus.has_value());
  EXPECT_EQ(back.exact_modulus->reference_pa, e0);
  EXPECT_EQ(databaseChecksum(back), databaseChecksum(db));

  // At a sample's thickness the rbf weights pick that sample alone, so what remains is the scaling:
  // the ROM response must be the direct solve's at the held-out E to round-off.
  const double e = 63e9, h = db.samples[1].parameters[1];
  const std::unique_ptr<ModalInterpolator> rbf = makeInterpolator(back, InterpolationMethod::Rbf);
  const ModalModel interpolated = rbf->evaluateWithStresses({e, h});
  Config at = c;
  at.material.youngs_modulus_pa = e;
  at.interface.thickness_m = h;
  const testing::DirectSolve direct = solveWithStresses(at);
  const double freq = testing::frequencyError(direct.modal, interpolated, kModes);
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(c));
  const ModalDeploymentOptions deploy = deploymentOptionsFromConfig(c);
  const double nrmse =
      responseNrmse(relativeAccelerationSeries(direct.modal, drive, deploy),
                    relativeAccelerationSeries(interpolated, drive, deploy));
  std::printf("[ measured ] held-out E = 63 GPa: omega error %.2g, response NRMSE %.2g\n", freq,
              nrmse);
  EXPECT_LT(freq, 1e-10);
  EXPECT_LT(nrmse, 1e-8);
  // Stresses: the largest modal stress of each mode (basis-free within a pair: use the pair's norm).
  ASSERT_FALSE(interpolated.stress.empty());
  EXPECT_NEAR(interpolated.stress.modes.norm() / direct.modal.stress.modes.norm(), 1.0, 1e-9);
  EXPECT_NEAR(interpolated.stress.loads.norm() / direct.modal.stress.loads.norm(), 1.0, 1e-9);
  // A batch of points (a screen's) gives every point's model bit for bit.
  const std::vector<std::vector<double>> points = {{e, h}, {71e9, 0.5 * (h + 1.5e-3)}, {e, h}};
  const std::vector<ModalModel> batch = rbf->evaluateWithStressesAt(points);
  ASSERT_EQ(batch.size(), points.size());
  for (std::size_t b = 0; b < points.size(); ++b) {
    const ModalModel one = rbf->evaluateWithStresses(points[b]);
    EXPECT_TRUE(batch[b].omega_rad_s == one.omega_rad_s) << b;
    EXPECT_TRUE(batch[b].stress.modes == one.stress.modes) << b;
    EXPECT_TRUE(batch[b].stress.loads == one.stress.loads) << b;
    EXPECT_TRUE(batch[b].stress.preload == one.stress.preload) << b;
    EXPECT_TRUE(batch[b].stress.points == one.stress.points) << b;
    EXPECT_EQ(batch[b].stress.damping_s, one.stress.damping_s) << b;
  }

  // The user's axes, E included, are what an evaluation takes.
  EXPECT_THROW(rbf->evaluate({e}), InputError);
}

}  // namespace
}  // namespace mastrom::rom
