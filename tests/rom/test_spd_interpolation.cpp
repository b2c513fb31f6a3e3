// Interpolation method (b) of docs/theory.md §4.4 (rom/interpolation/spd_interpolation.hpp) and its SPD matrix
// functions (rom/interpolation/spd_math.hpp): round trips and the failure path of the matrix functions; the
// interpolant reproducing every database sample; accuracy against direct modal solves inside a
// smooth box; and a box with a mode crossing, where (b) keeps its accuracy and a per-index
// interpolation of the sorted modal quantities does not; and a box with a mode veering, where (b)
// keeps its accuracy and the MAC-tracked interpolation (a) does not.
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SparseCore>
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "rom/offline/database_build.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/spd_interpolation.hpp"
#include "rom/interpolation/spd_math.hpp"
#include "rom/interpolation/tracked_interpolation.hpp"
#include "tests/rom/direct_modal_solve.hpp"

namespace mastrom::rom {
namespace {

using testing::compareRoms;
using testing::directModalSolve;
using testing::frequencyError;
using testing::scheme1Config;

double relDiff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / b.norm();
}

/// Seeded random SPD matrix with eigenvalues spread log-uniformly over `decades`.
Eigen::MatrixXd randomSpd(int n, double decades, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd g(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) g(i, j) = normal(gen);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(g);
  const Eigen::MatrixXd u = qr.householderQ();
  Eigen::VectorXd l(n);
  for (int i = 0; i < n; ++i) l[i] = std::pow(10.0, decades * i / (n - 1));
  Eigen::MatrixXd a = u * l.asDiagonal() * u.transpose();
  return 0.5 * (a + a.transpose());
}

TEST(SpdMath, SquareRootLogAndExpRoundTrip) {
  const Eigen::MatrixXd a = 3e7 * randomSpd(8, 6.0, 1);  // ω²-like scale and spread
  const Eigen::MatrixXd s = spdSqrt(a), is = spdInverseSqrt(a);
  EXPECT_LT(relDiff(s * s, a), 1e-12);
  EXPECT_LT((is * a * is - Eigen::MatrixXd::Identity(8, 8)).norm(), 1e-9);
  EXPECT_LT(relDiff(symmetricExp(spdLog(a)), a), 1e-11);
  Eigen::MatrixXd t = randomSpd(8, 1.0, 2) - 2.0 * Eigen::MatrixXd::Identity(8, 8);  // indefinite
  EXPECT_LT(relDiff(spdLog(symmetricExp(t)), t), 1e-12);
  // Diagonal matrices: the functions act on the diagonal.
  const Eigen::Vector3d d(0.5, 2.0, 7.0);
  const Eigen::MatrixXd dm = d.asDiagonal();
  EXPECT_LT((spdLog(dm).diagonal() - d.array().log().matrix()).norm(), 1e-15);
}

TEST(SpdMath, AffineInvariantMapsRoundTripAndGiveTheGeometricMean) {
  const Eigen::MatrixXd p = 1e8 * randomSpd(6, 4.0, 3), s = 1e8 * randomSpd(6, 4.0, 4);
  const SpdBasePoint base(p);
  EXPECT_LT(relDiff(base.exp(base.log(s)), s), 1e-11);
  EXPECT_LT(base.log(p).norm(), 1e-10 * p.norm());  // Log_P(P) = 0
  EXPECT_LT(relDiff(base.exp(Eigen::MatrixXd::Zero(6, 6)), p), 1e-13);
  EXPECT_LT(relDiff(base.expWhitened(base.logWhitened(s)), s), 1e-11);
  // The midpoint of the geodesic from P to S is the geometric mean G = P # S, the unique SPD
  // solution of G P⁻¹ G = S (an independent characterisation).
  const Eigen::MatrixXd g = base.exp(0.5 * base.log(s));
  EXPECT_LT(relDiff(g * p.inverse() * g, s), 1e-9);
  // Congruence invariance of the affine-invariant log map: Log_{APAᵀ}(ASAᵀ) = A Log_P(S) Aᵀ.
  const Eigen::MatrixXd a = randomSpd(6, 1.0, 5) + Eigen::MatrixXd::Identity(6, 6) * 0.1;
  const SpdBasePoint moved(a * p * a.transpose());
  EXPECT_LT(relDiff(moved.log(a * s * a.transpose()), a * base.log(s) * a.transpose()), 1e-9);
}

TEST(SpdMath, RejectsMatricesThatAreNotSpd) {
  Eigen::MatrixXd indefinite = Eigen::Vector3d(1.0, -1e-3, 2.0).asDiagonal();
  EXPECT_THROW(spdLog(indefinite), NumericalError);
  EXPECT_THROW(SpdBasePoint{indefinite}, NumericalError);
  const Eigen::MatrixXd singular = Eigen::Vector3d(1.0, 0.0, 2.0).asDiagonal();
  EXPECT_THROW(spdSqrt(singular), NumericalError);
  Eigen::MatrixXd unsymmetric = Eigen::Matrix3d::Identity();
  unsymmetric(0, 1) = 0.1;
  EXPECT_THROW(spdInverseSqrt(unsymmetric), NumericalError);
  Eigen::MatrixXd nan = Eigen::Matrix3d::Identity();
  nan(1, 1) = std::nan("");
  EXPECT_THROW(spdLog(nan), NumericalError);
  EXPECT_THROW(symmetricExp(1000.0 * Eigen::MatrixXd::Identity(2, 2)), NumericalError);
  try {
    spdLog(indefinite, "aligned stiffness of sample 7");
    FAIL() << "no exception";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("aligned stiffness of sample 7"), std::string::npos);
  }
}

TEST(MultilinearWeights, ReproduceNodesAndMultilinearFunctions) {
  const std::vector<ParameterAxis> axes = {{"a", {1.0, 2.0, 4.0}}, {"b", {10.0, 30.0}}};
  // At a node: one weight, exactly 1.
  const std::vector<GridWeight> node = multilinearWeights(axes, {2.0, 30.0});
  ASSERT_EQ(node.size(), 1u);
  EXPECT_EQ(node[0].sample, 1 + 3 * 1);
  EXPECT_EQ(node[0].weight, 1.0);
  for (AxisWeighting mode : {AxisWeighting::Linear, AxisWeighting::Logarithmic}) {
    const std::vector<GridWeight> last = multilinearWeights(axes, {4.0, 10.0}, mode);
    ASSERT_EQ(last.size(), 1u);
    EXPECT_EQ(last[0].weight, 1.0);
  }
  // Linear weights reproduce f = 3 + a − 2b + ab exactly (inside and, extrapolating, outside).
  auto f = [](double a, double b) { return 3.0 + a - 2.0 * b + a * b; };
  auto log_f = [](double a, double b) { return 0.5 + std::log(a) - 0.3 * std::log(b); };
  for (const std::vector<double>& p : {std::vector<double>{1.3, 17.0}, {3.1, 29.0}, {5.0, 5.0}}) {
    double lin = 0.0, sum = 0.0, geo = 0.0;
    for (const GridWeight& w : multilinearWeights(axes, p)) {
      const double a = axes[0].values[w.sample % 3], b = axes[1].values[w.sample / 3];
      lin += w.weight * f(a, b);
      sum += w.weight;
    }
    for (const GridWeight& w : multilinearWeights(axes, p, AxisWeighting::Logarithmic)) {
      const double a = axes[0].values[w.sample % 3], b = axes[1].values[w.sample / 3];
      geo += w.weight * log_f(a, b);
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_NEAR(lin, f(p[0], p[1]), 1e-12);
    EXPECT_NEAR(geo, log_f(p[0], p[1]), 1e-12);  // logarithmic: exact for power laws
  }
  EXPECT_THROW(multilinearWeights(axes, {1.0}), InputError);
  EXPECT_THROW(multilinearWeights(axes, {std::nan(""), 10.0}), InputError);
  EXPECT_THROW(multilinearWeights(axes, {-1.0, 10.0}, AxisWeighting::Logarithmic), InputError);
}

// ---- databases -------------------------------------------------------------------------------

constexpr int kModes = 12;  ///< per sample: the lowest 6 are checked, the rest is the buffer

ParameterAxis axis(const std::string& key, double lo, double hi, int n) {
  ParameterAxis a{key, {}};
  for (int i = 0; i < n; ++i) a.values.push_back(i + 1 == n ? hi : lo + (hi - lo) * i / (n - 1));
  return a;
}

RomDatabase buildGrid(const Config& base, const std::vector<ParameterAxis>& axes) {
  DatabaseBuildOptions o;
  o.axes = axes;
  o.modes = kModes;
  o.backend = EigenBackendKind::Dense;
  return buildDatabase(base, o);
}

/// The cell midpoints of a 2-axis grid.
std::vector<std::vector<double>> cellMidpoints(const RomDatabase& db) {
  std::vector<std::vector<double>> out;
  const std::vector<double>&a = db.axes[0].values, &b = db.axes[1].values;
  for (std::size_t j = 0; j + 1 < b.size(); ++j)
    for (std::size_t i = 0; i + 1 < a.size(); ++i)
      out.push_back({0.5 * (a[i] + a[i + 1]), 0.5 * (b[j] + b[j + 1])});
  return out;
}

/// The naive baseline: every per-mode array of the sorted samples interpolated index by index with
/// the same (linear) weights, no tracking, no alignment.
ModalModel perIndexInterpolation(const RomDatabase& db, const std::vector<double>& p) {
  const std::vector<GridWeight> w = multilinearWeights(db.axes, p);
  ModalModel out = db.samples[static_cast<std::size_t>(w[0].sample)].modal;
  auto axpy = [](double f, const ModalModel& m, ModalModel& o, bool init) {
    const double g = init ? 0.0 : 1.0;
    o.omega_rad_s = g * o.omega_rad_s + f * m.omega_rad_s;
    o.damping_ratio = g * o.damping_ratio + f * m.damping_ratio;
    o.rotation_participation = g * o.rotation_participation + f * m.rotation_participation;
    o.centrifugal_participation = g * o.centrifugal_participation + f * m.centrifugal_participation;
    o.end_rotation = g * o.end_rotation + f * m.end_rotation;
    o.end_translation = g * o.end_translation + f * m.end_translation;
    o.momentum_participation = g * o.momentum_participation + f * m.momentum_participation;
    o.coriolis = g * o.coriolis + f * m.coriolis;
    o.inertia_z_kg_m2 = g * o.inertia_z_kg_m2 + f * m.inertia_z_kg_m2;
    o.total_mass_kg = g * o.total_mass_kg + f * m.total_mass_kg;
    o.centroid_m = g * o.centroid_m + f * m.centroid_m;
    o.end_position_m = g * o.end_position_m + f * m.end_position_m;
  };
  for (std::size_t i = 0; i < w.size(); ++i)
    axpy(w[i].weight, db.samples[static_cast<std::size_t>(w[i].sample)].modal, out, i == 0);
  return out;
}

/// The smooth box: the paper's thickness range at about its radius, default 0.5 kg modules. No
/// mode among the lowest 12 crosses another (checked with the dense solver: the bending pair, the
/// torsion, the axial mode and the rocking pair stay below the shell modes everywhere).
const RomDatabase& smoothDatabase() {
  static const RomDatabase db = buildGrid(
      scheme1Config(kModes), {axis("interface.thickness", 0.5e-3, 2.0e-3, 7),
                              axis("interface.radius", 0.038, 0.044, 3)});
  return db;
}

TEST(ManifoldInterpolation, ReproducesEverySampleExactly) {
  const RomDatabase& db = smoothDatabase();
  const ManifoldInterpolator interp(db);
  const Config base = scheme1Config(kModes);
  for (const RomSample& s : db.samples) {
    const ModalModel m = interp.evaluate(s.parameters);
    // The aligned stiffness is the sample's own, through log and exp.
    const Eigen::VectorXd w2 = s.modal.omega_rad_s.cwiseAbs2();
    const Eigen::MatrixXd k = s.alignment.transpose() * w2.asDiagonal() * s.alignment;
    EXPECT_LT(relDiff(interp.alignedStiffness(s.parameters), k), 1e-12);
    for (int j = 0; j < kModes; ++j) {
      EXPECT_NEAR(m.omega_rad_s[j], s.modal.omega_rad_s[j], 1e-11 * s.modal.omega_rad_s[j]);
      EXPECT_NEAR(m.damping_ratio[j], s.modal.damping_ratio[j], 1e-9 * s.modal.damping_ratio[j]);
    }
    EXPECT_DOUBLE_EQ(m.inertia_z_kg_m2, s.modal.inertia_z_kg_m2);
    EXPECT_DOUBLE_EQ(m.total_mass_kg, s.modal.total_mass_kg);
    // Per-mode vectors are reproduced up to the sign of each mode and the basis of each degenerate
    // pair (the bending and shell pairs of the axisymmetric mast), which the eigensolver picks
    // freely: compare what does not depend on either — the deployment, Coriolis coupling included.
    ModalDeploymentOptions o;
    o.end_time_s = 0.05;
    o.step_s = 1e-5;
    o.coriolis_coupling = true;
    const fullorder::DriveLaw drive(fullorder::driveFromConfig(base));
    const fullorder::DeploymentSeries a = simulateModalDeployment(s.modal, drive, o);
    const fullorder::DeploymentSeries b = simulateModalDeployment(m, drive, o);
    double num = 0, den = 0, force = 0, force_err = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double x = a.end_relative_angular_acceleration_rad_s2[i];
      num += std::pow(b.end_relative_angular_acceleration_rad_s2[i] - x, 2);
      den += x * x;
      force = std::max(force, a.joint_force_n[i].norm());
      force_err = std::max(force_err, (a.joint_force_n[i] - b.joint_force_n[i]).norm());
    }
    EXPECT_LT(std::sqrt(num / den), 1e-9);
    EXPECT_LT(force_err, 1e-10 * force);
  }
}

TEST(ManifoldInterpolation, MatchesDirectModalSolvesInsideASmoothBox) {
  // Grid 7 × 3 over h ∈ [0.5, 2] mm × R ∈ [38, 44] mm; every cell midpoint against a direct modal
  // solve there. Measured (max over the 12 midpoints): lowest-6 frequencies 0.044 % (b) vs 0.54 %
  // for (a) tracked; NRMSE of the relative end angular acceleration 1.6 % (b), 26 % for (b) with
  // linear instead of logarithmic weights, 12.8 % (a); the other metrics of (b) ≤ 1.2 %. All are
  // worst in the thinnest cell, where the grid ratio h_{i+1}/h_i = 1.5 is largest.
  const RomDatabase& db = smoothDatabase();
  const Config base = scheme1Config(kModes);
  const std::unique_ptr<ModalInterpolator> spd = makeManifoldInterpolator(db);
  const std::unique_ptr<ModalInterpolator> spd_linear =
      makeManifoldInterpolator(db, {AxisWeighting::Linear});
  const TrackedInterpolator tracked(db);
  double worst_f = 0, worst_nrmse = 0, worst_metric = 0, lin_nrmse = 0, trk_f = 0, trk_nrmse = 0;
  for (const std::vector<double>& p : cellMidpoints(db)) {
    const Config c = applyOverrides(base, parameterOverrides(db.axes, p));
    const ModalModel truth = directModalSolve(c, kModes).modal;
    const ModalModel m = spd->evaluate(p);
    const DeploymentComparison cmp = compareRoms(truth, m, c);
    const DeploymentComparison cmp_lin = compareRoms(truth, spd_linear->evaluate(p), c);
    const ModalModel mt = tracked.evaluate(p);
    const DeploymentComparison cmp_trk = compareRoms(truth, mt, c);
    std::printf("[ measured ] h = %.4g mm, R = %.4g mm: freq err (b) %.2e (a) %.2e; NRMSE (b) %.4f"
                " (b, linear weights) %.4f (a) %.4f; worst metric (b) %.4f\n",
                p[0] * 1e3, p[1] * 1e3, frequencyError(truth, m, 6), frequencyError(truth, mt, 6),
                cmp.nrmse_relative_acceleration, cmp_lin.nrmse_relative_acceleration,
                cmp_trk.nrmse_relative_acceleration, cmp.worst());
    worst_f = std::max(worst_f, frequencyError(truth, m, 6));
    worst_nrmse = std::max(worst_nrmse, cmp.nrmse_relative_acceleration);
    worst_metric = std::max({worst_metric, cmp.peak_abs_error, cmp.peak_rel_error,
                             cmp.rms_rel_error, cmp.peak_force_error, cmp.peak_torque_error});
    lin_nrmse = std::max(lin_nrmse, cmp_lin.nrmse_relative_acceleration);
    trk_f = std::max(trk_f, frequencyError(truth, mt, 6));
    trk_nrmse = std::max(trk_nrmse, cmp_trk.nrmse_relative_acceleration);
  }
  std::printf("[ measured ] smooth box, max over midpoints: (b) freq %.2e NRMSE %.4f metrics %.4f;"
              " (b, linear weights) NRMSE %.4f; (a) freq %.2e NRMSE %.4f\n",
              worst_f, worst_nrmse, worst_metric, lin_nrmse, trk_f, trk_nrmse);
  EXPECT_LT(worst_f, 1e-3);       // lowest 6 frequencies within 0.1 %
  EXPECT_LT(worst_nrmse, 0.03);   // within the 3 % target of a database sample
  EXPECT_LT(worst_metric, 0.03);  // peak |abs|, peak/RMS |rel|, peak force and torque
}

// ---- the mode crossing ---------------------------------------------------------------------------
//
// Where the first bending pair meets a shell mode. Searched with the dense solver over
// R ∈ [41, 150] mm, h ∈ [0.3, 8] mm, module mass 0.1–0.5 kg, meshes 2×8 and 2×12 (lowest shell
// mode / first bending frequency): with the paper's 0.5 kg modules at R ≤ 80 mm the lowest shell
// mode stays ≥ 2× above the first bending pair — the shell modes of this short clamped interface
// are membrane-dominated and rise with h almost as fast as the bending pair does — so the crossing
// needs a wide, light interface: with 0.1 kg modules the 2×8 mesh's n = 4 ovalling mode crosses the
// first bending pair inside R ∈ [90, 110] mm, h ∈ [1, 2] mm (at R = 100 mm between h = 1.5 and
// 1.75 mm, at 5.84 kHz; at R = 110 mm between 1.0 and 1.25 mm; at 90 mm just above 2 mm), and at
// R = 110 mm the pair also passes the n = 3 pair between h = 1.75 and 2 mm. (With 0.5 kg modules
// the second bending pair — the rocking pair — crosses the n = 4 mode at R = 60 mm, h ≈ 1.1 mm.)

const RomDatabase& crossingDatabase() {
  static const RomDatabase db = [] {
    Config c = scheme1Config(kModes);
    c.module.mass_kg = 0.1;
    return buildGrid(c, {axis("interface.thickness", 1.0e-3, 2.0e-3, 5),
                         axis("interface.radius", 0.09, 0.11, 3)});
  }();
  return db;
}

TEST(ManifoldInterpolation, SurvivesAModeCrossingThatBreaksPerIndexInterpolation) {
  // Grid 5 × 3 over h ∈ [1, 2] mm × R ∈ [90, 110] mm, 0.1 kg modules; every cell midpoint against
  // a direct modal solve. Measured (max over the 8 midpoints): lowest-6 frequencies 0.25 % (b),
  // 1.6 % per-index, 0.38 % (a); NRMSE 2.1 % (b), 49 % per-index, 2.2 % (a). The per-index
  // interpolation fails (NRMSE 34–49 %) in exactly the six cells where the first bending pair
  // changes its place in the sorted list — it crosses the n = 4 mode in five of them, the n = 3
  // pair in the sixth (R = 110 mm, h ≈ 1.9 mm) — and gives 1.6–1.9 % in the other two.
  const RomDatabase& db = crossingDatabase();
  Config base = scheme1Config(kModes);
  base.module.mass_kg = 0.1;
  // The crossing is inside the box: at R = 100 mm the lowest mode moves the end module (a bending
  // mode, ψ ≠ 0) at h = 1.5 mm and does not (the n = 4 shell mode, ψ = 0) at h = 1.75 mm.
  const RomSample& before = db.samples[static_cast<std::size_t>(db.sampleIndex({2, 1}))];
  const RomSample& after = db.samples[static_cast<std::size_t>(db.sampleIndex({3, 1}))];
  EXPECT_GT(before.modal.end_rotation.col(0).norm(), 1.0);
  EXPECT_LT(after.modal.end_rotation.col(0).norm(), 1e-6);

  const std::unique_ptr<ModalInterpolator> spd = makeManifoldInterpolator(db);
  const TrackedInterpolator tracked(db);
  double worst_f = 0, worst_nrmse = 0, naive_f = 0, naive_nrmse = 0, trk_f = 0, trk_nrmse = 0;
  for (const std::vector<double>& p : cellMidpoints(db)) {
    const Config c = applyOverrides(base, parameterOverrides(db.axes, p));
    const ModalModel truth = directModalSolve(c, kModes).modal;
    const ModalModel m = spd->evaluate(p), naive = perIndexInterpolation(db, p);
    const ModalModel mt = tracked.evaluate(p);
    const double f = frequencyError(truth, m, 6), fn = frequencyError(truth, naive, 6);
    const double e = compareRoms(truth, m, c).nrmse_relative_acceleration;
    const double en = compareRoms(truth, naive, c).nrmse_relative_acceleration;
    const double ft = frequencyError(truth, mt, 6);
    const double et = compareRoms(truth, mt, c).nrmse_relative_acceleration;
    std::printf("[ measured ] h = %.4g mm, R = %.4g mm: freq err (b) %.2e per-index %.2e (a) %.2e;"
                " NRMSE (b) %.4f per-index %.4f (a) %.4f\n",
                p[0] * 1e3, p[1] * 1e3, f, fn, ft, e, en, et);
    worst_f = std::max(worst_f, f);
    worst_nrmse = std::max(worst_nrmse, e);
    naive_f = std::max(naive_f, fn);
    naive_nrmse = std::max(naive_nrmse, en);
    trk_f = std::max(trk_f, ft);
    trk_nrmse = std::max(trk_nrmse, et);
  }
  std::printf("[ measured ] crossing box, max over midpoints: (b) freq %.2e NRMSE %.4f; per-index "
              "freq %.2e NRMSE %.4f; (a) freq %.2e NRMSE %.4f\n",
              worst_f, worst_nrmse, naive_f, naive_nrmse, trk_f, trk_nrmse);
  // (b) meets the accuracy target everywhere; the per-index interpolation misses it.
  EXPECT_LT(worst_f, 0.01);
  EXPECT_LT(worst_nrmse, 0.05);
  EXPECT_TRUE(naive_f > 0.01 || naive_nrmse > 0.05);
  EXPECT_GT(naive_nrmse, 0.05);
  // The honest result for (a): MAC tracking passes this crossing too. The crossing modes differ in
  // symmetry (the n = 4 ovalling mode and the bending pair do not interact), so every sample's
  // modes match the reference's shapes one to one and the tracked per-mode quantities are smooth;
  // what (a) cannot follow is a veering (modes of one symmetry exchanging shapes): next test.
  EXPECT_LT(trk_nrmse, 0.05);
}

// ---- a mode veering -----------------------------------------------------------------------------
//
// What MAC tracking (a) cannot follow: two modes of the same symmetry that approach, exchange their
// shapes and repel. Per bending plane the end module of Scheme 1 has two such modes, centroid
// translation u and rocking φ about the centroid, coupled through the interface. In (u, φ) the
// mass is diag(m, J) and a Timoshenko model of the interface's tip stiffness (shear parameter
// Φ = 12EI/(κ_s GA L²) ≈ 32 (R/L)² for a thin tube, κ_s = ½) couples them with
//     κ = K_uφ/√(K_uu K_φφ) = (12e + 6L) / √(12 (12e² + 12eL + (4 + Φ)L²)),   e = d/2,
// so the branches come closest, ω₂²/ω₁² = (1 + κ)/(1 − κ), where K_uu/m = K_φφ/J. The cube
// module of the paper's layout (d = 0.1 m, L = 0.05 m: κ ≈ 0.7) exchanges only broadly: scanned
// with the dense solver at J = module.inertia = 8.3e-4 (the cube's) … 1e-1 kg·m², 7 values, the
// two pairs come no closer than a frequency ratio ≈ 2.5 (near J = 5e-3), and the lower pair keeps
// its shape (end rotation per end translation 7.7 → 13 rad/m) — a tracked grid follows that. The
// coupling drops with the offset e and with a short, shear-dominated interface (J = 1e-4 … 3e-2,
// 6 values each): closest ratios ≈ 1.6 for d = 20 mm at L = 50 mm, 1.33 for d = 20 mm at
// L = 20 mm (κ ≈ 0.29 predicts 1.34), ≈ 1.26 for d = 10 mm at L = 20 mm; d = 50 mm at L = 0.1 m
// and d = 20 mm at L = 0.1 m stay above 2. The box below uses the second: a flat module (20 mm
// along the axis) with the lateral inertia of a wide panel, Iyy = Izz = 2.8e-3 kg·m² (Ixx =
// 5.5e-3), on a 20 mm interface, its mass m ∈ [0.1, 3.2] kg varied at fixed inertia (a payload at
// the centroid; the shear-dominated frequency ratio goes with J/m). Scanned at 41 masses: the gap
// between the two bending pairs, ω_upper/ω_lower − 1, falls from 1.36 at 0.1 kg to its minimum
// 0.33 at 0.52 kg (the model above: 0.34 at 0.57 kg) and rises again to 1.56 at 3.2 kg, while the
// lower pair turns from rocking (41 rad/m) to translation (4.6 rad/m) and the upper the other
// way. The torsion (2.29 kHz) and the axial mode cross the bending pairs inside the box too —
// different symmetry, true crossings. With the samples m = 0.1 · 2^i, i = 0 … 5, the tracking
// against the reference sample (0.4 kg) pairs the lower pair of the 3.2 kg sample with the
// reference's upper pair: that sample's branches are exchanged in (a)'s features.

constexpr double kVeeringMassLowKg = 0.1, kVeeringMassHighKg = 3.2;

Config veeringConfig() {
  Config c = scheme1Config(kModes);
  c.module.side_m = 0.02;
  c.interface.length_m = 0.02;
  c.module.inertia_kg_m2 = std::array<double, 3>{5.5e-3, 2.8e-3, 2.8e-3};
  return c;
}

const RomDatabase& veeringDatabase() {
  static const RomDatabase db = [] {
    ParameterAxis mass{"module.mass", {}};
    for (double m = kVeeringMassLowKg; m < 1.01 * kVeeringMassHighKg; m *= 2.0)
      mass.values.push_back(m);
    return buildGrid(veeringConfig(), {mass});
  }();
  return db;
}

Config withModuleMass(const Config& base, double mass_kg) {
  Config c = base;
  c.module.mass_kg = mass_kg;
  return c;
}

/// The bending modes (both planes): the modes that move the end module sideways, i.e. across the
/// mast axis (x at θ₀ = 0). Shell modes with n ≥ 2 circumferential waves leave the module at rest,
/// the torsion and the axial mode move it about and along the axis only.
std::vector<int> bendingModes(const ModalModel& m) {
  Eigen::VectorXd lateral(m.modeCount());
  for (int k = 0; k < m.modeCount(); ++k) lateral[k] = m.end_translation.col(k).tail<2>().norm();
  std::vector<int> out;
  for (int k = 0; k < m.modeCount(); ++k)
    if (lateral[k] > 1e-6 * lateral.maxCoeff()) out.push_back(k);
  return out;
}

/// MAC of mode pair (a0, a0 + 1) of `a` against pair (b0, b0 + 1) of `b` in the mass matrix
/// `mass`: ‖AᵀMB‖²_F / 2, every column M-normalised. The bending pairs of the axisymmetric mast are
/// degenerate and the eigensolver picks any basis of each; this mean is the same for every basis
/// (the two planes are mirror images, so the members stay M-orthogonal in any mass matrix of the
/// same symmetry), and it is the MAC of one plane's mode when the solver splits the planes.
double pairMac(const testing::DirectSolve& a, int a0, const testing::DirectSolve& b, int b0,
               const Eigen::SparseMatrix<double>& mass) {
  Eigen::MatrixXd pa(a.eig.modes.rows(), 2), pb(b.eig.modes.rows(), 2);
  for (int j = 0; j < 2; ++j) {
    pa.col(j) = a.eig.modes.col(a0 + j);
    pb.col(j) = b.eig.modes.col(b0 + j);
    pa.col(j) /= std::sqrt(pa.col(j).dot(mass * pa.col(j)));
    pb.col(j) /= std::sqrt(pb.col(j).dot(mass * pb.col(j)));
  }
  const Eigen::MatrixXd mb = mass * pb;
  return (pa.transpose() * mb).squaredNorm() / 2.0;
}

TEST(ManifoldInterpolation, FollowsAModeVeeringThatBreaksMacTracking) {
  const RomDatabase& db = veeringDatabase();
  const Config base = veeringConfig();
  const int last = static_cast<int>(db.samples.size()) - 1;

  // The veering is real. (1) The shapes exchange: in the reference sample's mass matrix (the one
  // the tracking uses), the lower bending pair at 0.1 kg has MAC 0.36 with the lower pair at
  // 3.2 kg and 0.89 with the upper one; the upper pair at 0.1 kg has 0.82 with the lower at 3.2 kg.
  const testing::DirectSolve lo = directModalSolve(withModuleMass(base, kVeeringMassLowKg), kModes);
  const testing::DirectSolve hi =
      directModalSolve(withModuleMass(base, kVeeringMassHighKg), kModes);
  const testing::DirectSolve ref = directModalSolve(
      withModuleMass(base, db.samples[static_cast<std::size_t>(db.reference_sample)].parameters[0]),
      kModes);
  const std::vector<int> b_lo = bendingModes(lo.modal), b_hi = bendingModes(hi.modal);
  ASSERT_GE(b_lo.size(), 4u);
  ASSERT_GE(b_hi.size(), 4u);
  const Eigen::SparseMatrix<double>& m_ref = ref.lin.problem.mass;
  const double lower_lower = pairMac(lo, b_lo[0], hi, b_hi[0], m_ref);
  const double lower_upper = pairMac(lo, b_lo[0], hi, b_hi[2], m_ref);
  const double upper_lower = pairMac(lo, b_lo[2], hi, b_hi[0], m_ref);
  std::printf("[ measured ] veering, pair MAC 0.1 kg vs 3.2 kg: lower-lower %.3f lower-upper %.3f "
              "upper-lower %.3f\n",
              lower_lower, lower_upper, upper_lower);
  EXPECT_LT(lower_lower, 0.5);
  EXPECT_GT(lower_upper, 0.8);
  EXPECT_GT(upper_lower, 0.8);
  // (2) The branches repel instead of crossing: over 25 masses (log-spaced) the two bending pairs
  // keep a gap ω_upper/ω_lower − 1 well above zero, with its minimum inside the box.
  double min_gap = 1e9, gap_lo = 0, gap_hi = 0;
  int min_at = -1;
  constexpr int kScan = 25;
  for (int i = 0; i < kScan; ++i) {
    const double t = static_cast<double>(i) / (kScan - 1);
    const double m_kg = kVeeringMassLowKg * std::pow(kVeeringMassHighKg / kVeeringMassLowKg, t);
    const ModalModel s = directModalSolve(withModuleMass(base, m_kg), kModes).modal;
    const std::vector<int> b = bendingModes(s);
    ASSERT_GE(b.size(), 4u) << "m = " << m_kg << " kg";
    // Pairs: members 0, 1 degenerate, then the next pair.
    EXPECT_NEAR(s.omega_rad_s[b[1]] / s.omega_rad_s[b[0]], 1.0, 1e-8);
    EXPECT_NEAR(s.omega_rad_s[b[3]] / s.omega_rad_s[b[2]], 1.0, 1e-8);
    const double gap = s.omega_rad_s[b[2]] / s.omega_rad_s[b[0]] - 1.0;
    if (gap < min_gap) {
      min_gap = gap;
      min_at = i;
    }
    if (i == 0) gap_lo = gap;
    if (i == kScan - 1) gap_hi = gap;
  }
  std::printf("[ measured ] veering, bending-pair gap: %.3f at 0.1 kg, min %.3f (scan point %d of "
              "%d), %.3f at 3.2 kg\n",
              gap_lo, min_gap, min_at, kScan, gap_hi);
  EXPECT_GT(min_gap, 0.2);
  EXPECT_GT(min_at, 0);
  EXPECT_LT(min_at, kScan - 1);
  // (3) The tracking exchanges the branches at the 3.2 kg sample: the reference's lower pair is
  // matched to that sample's upper pair.
  {
    const std::vector<int> r =
        bendingModes(db.samples[static_cast<std::size_t>(db.reference_sample)].modal);
    const RomSample& s = db.samples[static_cast<std::size_t>(last)];
    const std::vector<int> b = bendingModes(s.modal);
    ASSERT_GE(r.size(), 4u);
    ASSERT_GE(b.size(), 4u);
    for (int j : {r[0], r[1]}) {
      const int matched = s.tracking[static_cast<std::size_t>(j)];
      EXPECT_TRUE(matched == b[2] || matched == b[3])
          << "reference mode " << j << " -> " << matched;
    }
  }

  // Every cell midpoint against a direct modal solve. Measured (m = 0.15, 0.3, 0.6, 1.2, 2.4 kg):
  //              lowest-6 frequencies                        NRMSE, relative end angular accel.
  //   (b)        0.25 %, 0.13 %, 0.086 %, 0.042 %, 0.024 %   0.42 %, 0.91 %, 2.5 %, 2.4 %, 2.2 %
  //   (a)        0.25 %, 0.84 %, 2.3 %, 0.61 %, 29 %         1.0 %, 5.2 %, 15 %, 8.8 %, 105 %
  //   per-index  5.7 %, 4.3 %, 4.4 %, 4.9 %, 5.6 %           0.36 %, 2.9 %, 8.6 %, 83 %, 49 %
  // (b) meets the targets everywhere (also at 0.2, 0.35, 0.65 and 0.8 of each cell: ≤ 0.25 % and
  // ≤ 2.5 %). (a) meets them only in the first cell, where the shapes hardly change. In the
  // veering cells (0.2 – 1.6 kg) the participations and end rotations of each tracked mode turn
  // with the shapes, far from linearly over a cell (factor 2 in m), while the aligned reduced
  // stiffness that (b) interpolates changes smoothly; in the last cell the features of the 3.2 kg
  // sample carry the other branch, so each bending frequency of (a) lands inside the gap (2.34 and
  // 3.14 kHz where the direct solve has 1.81 and 4.05 kHz). The per-index interpolation fails as
  // well: besides the veering, the torsion and the axial mode cross the bending pairs and shell
  // modes.
  const std::unique_ptr<ModalInterpolator> spd = makeManifoldInterpolator(db);
  const TrackedInterpolator tracked(db);
  double worst_f = 0, worst_nrmse = 0, trk_f = 0, trk_nrmse = 0, naive_f = 0, naive_nrmse = 0;
  for (std::size_t i = 0; i + 1 < db.axes[0].values.size(); ++i) {
    const std::vector<double> p = {0.5 * (db.axes[0].values[i] + db.axes[0].values[i + 1])};
    const Config c = withModuleMass(base, p[0]);
    const ModalModel truth = directModalSolve(c, kModes).modal;
    const ModalModel m = spd->evaluate(p), mt = tracked.evaluate(p);
    const ModalModel naive = perIndexInterpolation(db, p);
    const double f = frequencyError(truth, m, 6), ft = frequencyError(truth, mt, 6);
    const double fn = frequencyError(truth, naive, 6);
    const double e = compareRoms(truth, m, c).nrmse_relative_acceleration;
    const double et = compareRoms(truth, mt, c).nrmse_relative_acceleration;
    const double en = compareRoms(truth, naive, c).nrmse_relative_acceleration;
    std::printf("[ measured ] m = %.3g kg: freq err (b) %.2e (a) %.2e per-index %.2e; NRMSE (b) "
                "%.4f (a) %.4f per-index %.4f\n",
                p[0], f, ft, fn, e, et, en);
    worst_f = std::max(worst_f, f);
    worst_nrmse = std::max(worst_nrmse, e);
    trk_f = std::max(trk_f, ft);
    trk_nrmse = std::max(trk_nrmse, et);
    naive_f = std::max(naive_f, fn);
    naive_nrmse = std::max(naive_nrmse, en);
    if (i == 0) {  // outside the exchange (a) is fine: the failure below is the veering's
      EXPECT_LT(ft, 0.01);
      EXPECT_LT(et, 0.05);
    }
    if (static_cast<int>(i) + 1 == last) {  // the cell whose samples the tracking exchanged
      const std::vector<int> bt = bendingModes(truth), ba = bendingModes(mt);
      ASSERT_GE(bt.size(), 4u);
      ASSERT_GE(ba.size(), 4u);
      for (int k : {ba[0], ba[1], ba[2], ba[3]}) {  // the two lowest bending pairs
        EXPECT_GT(mt.omega_rad_s[k], 1.1 * truth.omega_rad_s[bt[0]]) << "mode " << k;
        EXPECT_LT(mt.omega_rad_s[k], truth.omega_rad_s[bt[2]] / 1.1) << "mode " << k;
      }
    }
  }
  std::printf("[ measured ] veering box, max over midpoints: (b) freq %.2e NRMSE %.4f; (a) freq "
              "%.2e NRMSE %.4f; per-index freq %.2e NRMSE %.4f\n",
              worst_f, worst_nrmse, trk_f, trk_nrmse, naive_f, naive_nrmse);
  EXPECT_LT(worst_f, 0.01);      // the targets: lowest frequencies within 1 %,
  EXPECT_LT(worst_nrmse, 0.05);  // relative end angular acceleration within 5 % NRMSE
  EXPECT_GT(trk_f, 0.01);        // (a) misses both
  EXPECT_GT(trk_nrmse, 0.05);
}

TEST(ManifoldInterpolation, StaysTheDefaultWhereAVeeringBreaksTheTracking) {
  // The build sees the exchange above in its tracking report (a drive-excited bending mode of the
  // 3.2 kg sample pairs with the reference's other branch) and keeps the manifold method, which
  // follows it, instead of the cubic weights on tracked features, which cannot
  // (rom/offline/probe_estimate.hpp).
  EXPECT_EQ(veeringDatabase().default_method, InterpolationMethod::Manifold);
  EXPECT_FALSE(veeringDatabase().estimate_from_probes);
}

TEST(ManifoldInterpolation, RejectsAnInconsistentDatabase) {
  RomDatabase db = smoothDatabase();
  EXPECT_THROW(makeManifoldInterpolator(db)->evaluate({1e-3}), InputError);  // one value, two axes
  RomDatabase bad = db;
  bad.samples[3].alignment(0, 0) += 1e-3;  // no longer orthogonal
  EXPECT_THROW(ManifoldInterpolator{bad}, InputError);
  bad = db;
  bad.samples.pop_back();
  EXPECT_THROW(ManifoldInterpolator{bad}, InputError);
  bad = db;
  bad.samples[5].modal.omega_rad_s[0] = 0.0;  // a rigid-body mode: K̃ singular
  EXPECT_THROW(ManifoldInterpolator{bad}, NumericalError);
}

}  // namespace
}  // namespace mastrom::rom
