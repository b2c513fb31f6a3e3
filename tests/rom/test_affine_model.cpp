// The exact parametric model of docs/theory.md §4.4 for thickness, Young's modulus and density
// (rom/interpolation/affine_model.hpp): K = E(h K_m + h³ K_b), M = M_rigid + ρh M_shell, C = μK checked on a third
// linearisation; evaluate() against the Galerkin projection of a direct linearisation and against
// extractModalModel run on the full matrices; the truncation error of the basis against full modal
// solves; the refusal of gravity and of points outside the box.
#include <cmath>
#include <cstdio>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "rom/interpolation/affine_model.hpp"
#include "tests/rom/direct_modal_solve.hpp"

namespace mastrom::rom {
namespace {

using testing::compareRoms;
using testing::directModalSolve;
using testing::frequencyError;
using testing::scheme1Config;

double maxAbs(const SparseMatrixD& a) {
  double m = 0.0;
  for (Eigen::Index k = 0; k < a.outerSize(); ++k)
    for (SparseMatrixD::InnerIterator it(a, k); it; ++it) m = std::max(m, std::abs(it.value()));
  return m;
}

/// max|A − B| / max|B|.
double relDiff(const SparseMatrixD& a, const SparseMatrixD& b) {
  return maxAbs(SparseMatrixD(a - b)) / maxAbs(b);
}

Config configAt(double h, double e, double rho) {
  Config c = scheme1Config(10);
  c.interface.thickness_m = h;
  c.material.youngs_modulus_pa = e;
  c.material.density_kg_m3 = rho;
  return c;
}

modes::Linearization linearizeAt(double h, double e, double rho) {
  const fullorder::MastModel model = modes::buildLockedMast(
      fullorder::mastParametersFromConfig(configAt(h, e, rho)), 0.0);
  return modes::linearizeMast(model);
}

TEST(AffineModel, StiffnessMassAndDampingAreExactlyAffine) {
  // Two linearisations at the paper's thickness extremes (E, ρ of aluminium) give the terms; a
  // third at other (h, E, ρ) must be reproduced to round-off.
  const double e0 = 70e9, rho0 = 2700.0, h1 = 0.5e-3, h2 = 2.0e-3;
  const modes::Linearization a = linearizeAt(h1, e0, rho0), b = linearizeAt(h2, e0, rho0);
  const AffineStiffness k = separateStiffness(a.problem.stiffness, h1, b.problem.stiffness, h2, e0);
  const AffineMass m = separateMass(a.problem.mass, rho0 * h1, b.problem.mass, rho0 * h2);
  const double h3 = 1.3e-3, e3 = 55e9, rho3 = 2200.0;
  const modes::Linearization c = linearizeAt(h3, e3, rho3);
  const double k_err = relDiff(k.at(h3, e3), c.problem.stiffness);
  const double m_err = relDiff(m.at(rho3 * h3), c.problem.mass);
  const double c_err = relDiff(SparseMatrixD(1e-5 * c.problem.stiffness), c.damping);  // C = μK
  std::printf("[ measured ] third linearisation: max|K − E(hK_m + h³K_b)|/max|K| = %.2e, "
              "mass %.2e, max|C − μK|/max|C| = %.2e\n", k_err, m_err, c_err);
  EXPECT_LT(k_err, 1e-12);
  EXPECT_LT(m_err, 1e-13);
  EXPECT_LT(c_err, 1e-12);
  // The bending term is a genuine part of K (not round-off): at h = 0.5 mm it carries a fraction
  // ~ (h/element size)² of the membrane stiffness.
  const double ratio = h3 * h3 * maxAbs(k.bending) / maxAbs(k.membrane);
  EXPECT_GT(ratio, 1e-5);
  // The modules' mass carries no shell term; the shell term is ∫SᵀS dA > 0.
  EXPECT_GT(maxAbs(m.shell), 0.0);
  EXPECT_THROW(separateStiffness(a.problem.stiffness, h1, b.problem.stiffness, h1, e0), InputError);
}

AffineModelOptions boxOptions() {
  AffineModelOptions o;
  o.box.thickness_min_m = 0.5e-3;
  o.box.thickness_max_m = 2.0e-3;
  o.box.youngs_modulus_min_pa = 50e9;
  o.box.youngs_modulus_max_pa = 90e9;
  o.box.density_min_kg_m3 = 2000.0;
  o.box.density_max_kg_m3 = 3200.0;
  o.snapshot_points = 3;
  o.snapshot_modes = 12;
  o.modes = 10;
  return o;
}

const AffineModalModel& affineModel() {
  static const AffineModalModel model = AffineModalModel::build(
      fullorder::mastParametersFromConfig(scheme1Config(10)), boxOptions());
  return model;
}

TEST(AffineModel, BasisIsMassOrthonormalAndSatisfiesTheConstraints) {
  const AffineModalModel& model = affineModel();
  const Eigen::MatrixXd& v = model.basis();
  const int r = model.basisSize();
  std::printf("[ measured ] basis: %d vectors from %d snapshots (n = %d DOFs), sigma_r/sigma_1 = "
              "%.2e\n", r, static_cast<int>(model.singularValues().size()),
              static_cast<int>(v.rows()), model.singularValues()[r - 1] / model.singularValues()[0]);
  const SparseMatrixD m_ref = model.mass().at(2600.0 * 1.25e-3);  // box centre
  EXPECT_LT((v.transpose() * (m_ref * v) - Eigen::MatrixXd::Identity(r, r)).cwiseAbs().maxCoeff(),
            1e-10);
  const Eigen::MatrixXd gv = model.constraintJacobian() * v;
  const double g_rel =
      gv.cwiseAbs().maxCoeff() / (maxAbs(model.constraintJacobian()) * v.cwiseAbs().maxCoeff());
  std::printf("[ measured ] max|GV| / (max|G| max|V|) = %.1e\n", g_rel);
  EXPECT_LT(g_rel, 1e-13);
}

TEST(AffineModel, EvaluateIsTheGalerkinSolveWithTheExtractionFormulas) {
  // At random (h, E, ρ) in the box: a direct linearisation there, projected on V, has the same
  // eigenvalues as evaluate() (1e-8 relative; measured ~1e-13), and extractModalModel run on the
  // full matrices with the modes Φ = VY gives the same modal model. Against a full modal solve
  // (no basis) the truncation error of the lowest 10 frequencies and of the ROM deployment are
  // reported and bounded.
  const AffineModalModel& model = affineModel();
  const Eigen::MatrixXd& v = model.basis();
  std::mt19937 gen(20240117);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  double worst_galerkin = 0, worst_extraction = 0, worst_trunc = 0, worst_trunc6 = 0,
         worst_nrmse = 0, worst_metric = 0;
  for (int trial = 0; trial < 4; ++trial) {
    const double h = 0.5e-3 + 1.5e-3 * u01(gen), e = 50e9 + 40e9 * u01(gen);
    const double rho = 2000.0 + 1200.0 * u01(gen);
    const ModalModel m = model.evaluate(h, e, rho);
    const AffineSolution sol = model.solve(h, e, rho);

    // Galerkin projection of the direct linearisation.
    const testing::DirectSolve direct = directModalSolve(configAt(h, e, rho), 10);
    const Eigen::MatrixXd kr = v.transpose() * (direct.lin.problem.stiffness * v);
    const Eigen::MatrixXd mr = v.transpose() * (direct.lin.problem.mass * v);
    EXPECT_LT((model.reducedStiffness(h, e) - kr).norm(), 1e-11 * kr.norm());
    EXPECT_LT((model.reducedMass(h, rho) - mr).norm(), 1e-12 * mr.norm());
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(
        0.5 * (kr + kr.transpose()), 0.5 * (mr + mr.transpose()), Eigen::EigenvaluesOnly);
    const Eigen::VectorXd galerkin = ges.eigenvalues().head(10);
    const double g_err =
        (sol.omega_squared - galerkin).cwiseQuotient(galerkin).cwiseAbs().maxCoeff();
    worst_galerkin = std::max(worst_galerkin, g_err);
    EXPECT_LT(g_err, 1e-8);

    // The same extraction code on the full matrices and Φ = VY.
    LinearizedModes lm;
    lm.q_reference = direct.lin.q;
    lm.mass = direct.lin.problem.mass;
    lm.damping = direct.lin.damping;
    lm.omega_squared = sol.omega_squared;
    lm.modes = v * sol.coefficients;
    const ModalModel x = extractModalModel(direct.model, lm);
    auto rel = [](const auto& a, const auto& b) { return (a - b).norm() / b.norm(); };
    const double x_err = std::max(
        {rel(m.omega_rad_s, x.omega_rad_s), rel(m.damping_ratio, x.damping_ratio),
         rel(m.rotation_participation, x.rotation_participation),
         rel(m.centrifugal_participation, x.centrifugal_participation),
         rel(m.end_rotation, x.end_rotation), rel(m.end_translation, x.end_translation),
         rel(m.momentum_participation, x.momentum_participation), rel(m.coriolis, x.coriolis),
         std::abs(m.inertia_z_kg_m2 / x.inertia_z_kg_m2 - 1),
         std::abs(m.total_mass_kg / x.total_mass_kg - 1), rel(m.centroid_m, x.centroid_m),
         rel(m.end_position_m, x.end_position_m)});
    worst_extraction = std::max(worst_extraction, x_err);
    EXPECT_LT(x_err, 1e-9);

    // Truncation to span V against the full modal solve.
    const double t_err = frequencyError(direct.modal, m, 10);
    const double t_err6 = frequencyError(direct.modal, m, 6);
    const DeploymentComparison cmp = compareRoms(direct.modal, m, configAt(h, e, rho));
    std::printf("[ measured ] h = %.4g mm, E = %.4g GPa, rho = %.5g: Galerkin %.1e, extraction "
                "%.1e, truncation: freq (10) %.1e (6) %.1e, NRMSE %.2e, worst metric %.2e\n",
                h * 1e3, e * 1e-9, rho, g_err, x_err, t_err, t_err6,
                cmp.nrmse_relative_acceleration, cmp.worst());
    worst_trunc = std::max(worst_trunc, t_err);
    worst_trunc6 = std::max(worst_trunc6, t_err6);
    worst_nrmse = std::max(worst_nrmse, cmp.nrmse_relative_acceleration);
    worst_metric = std::max({worst_metric, cmp.peak_abs_error, cmp.peak_rel_error,
                             cmp.rms_rel_error, cmp.peak_force_error, cmp.peak_torque_error});
  }
  std::printf("[ measured ] affine model, max over 4 random points: Galerkin %.1e, extraction %.1e, "
              "truncation freq (10) %.1e (6) %.1e, NRMSE %.2e, metrics %.2e\n",
              worst_galerkin, worst_extraction, worst_trunc, worst_trunc6, worst_nrmse,
              worst_metric);
  EXPECT_LT(worst_trunc6, 1e-4);
  EXPECT_LT(worst_trunc, 1e-3);
  EXPECT_LT(worst_nrmse, 0.01);
  EXPECT_LT(worst_metric, 0.01);
}

TEST(AffineModel, ReproducesAFullSolveExactlyAtASnapshot) {
  // At a snapshot point span V contains the exact modes, so the truncation error vanishes there.
  const AffineModalModel& model = affineModel();
  const double h = 1.25e-3, rho = 2000.0, e = 77e9;  // (h, ρ) on the snapshot grid, any E
  const ModalModel m = model.evaluate(h, e, rho);
  const ModalModel direct = directModalSolve(configAt(h, e, rho), 10).modal;
  const double err = frequencyError(direct, m, 10);
  std::printf("[ measured ] at a snapshot point: max relative frequency error %.1e\n", err);
  EXPECT_LT(err, 1e-8);
}

TEST(AffineModel, TruncationErrorFallsWithTheBasisSize) {
  // The POD cut-off trades basis size for truncation error. At three points in the box (not on the
  // snapshot grid): basis size and max relative error of the lowest 10 frequencies vs full solves.
  // Measured (108 snapshots, n = 240, 110 constrained DOFs): cut-off 1e-2 → 14 vectors, 3.0e-4;
  // 1e-3 → 22, 8.5e-6; 1e-5 → 32, 1.1e-8; 1e-8 (default) → 47, 2.4e-11.
  const double points[3][3] = {{0.7e-3, 60e9, 3000.0}, {1.6e-3, 85e9, 2300.0},
                               {1.0e-3, 70e9, 2700.0}};
  std::vector<testing::DirectSolve> truth;
  for (const auto& p : points) truth.push_back(directModalSolve(configAt(p[0], p[1], p[2]), 10));
  double previous = 1.0;
  for (double tol : {1e-2, 1e-3, 1e-5, 1e-8}) {
    AffineModelOptions o = boxOptions();
    o.basis_tolerance = tol;
    const AffineModalModel model =
        AffineModalModel::build(fullorder::mastParametersFromConfig(scheme1Config(10)), o);
    double err = 0.0;
    for (int i = 0; i < 3; ++i)
      err = std::max(err, frequencyError(truth[static_cast<std::size_t>(i)].modal,
                                         model.evaluate(points[i][0], points[i][1], points[i][2]),
                                         10));
    std::printf("[ measured ] POD cut-off %.0e: basis %d vectors, truncation error of the lowest "
                "10 frequencies %.1e\n", tol, model.basisSize(), err);
    EXPECT_LE(err, previous * 1.01 + 1e-12);
    previous = err;
  }
  EXPECT_LT(previous, 1e-9);
}

TEST(AffineModel, RefusesGravityAndPointsOutsideTheBox) {
  fullorder::MastParameters p = fullorder::mastParametersFromConfig(scheme1Config(10));
  p.gravity_m_s2 = Eigen::Vector3d(0.0, -9.81, 0.0);
  EXPECT_THROW(AffineModalModel::build(p, boxOptions()), InputError);
  const AffineModalModel& model = affineModel();
  EXPECT_THROW(model.evaluate(2.5e-3, 70e9, 2700.0), InputError);
  EXPECT_THROW(model.evaluate(1e-3, 100e9, 2700.0), InputError);
  EXPECT_THROW(model.evaluate(1e-3, 70e9, std::nan("")), InputError);
  AffineModelOptions o = boxOptions();
  o.modes = 1000;  // more than the basis holds
  EXPECT_THROW(AffineModalModel::build(fullorder::mastParametersFromConfig(scheme1Config(10)), o),
               InputError);
}

}  // namespace
}  // namespace mastrom::rom
