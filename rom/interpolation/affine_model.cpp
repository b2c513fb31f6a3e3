#include "rom/interpolation/affine_model.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"
#include "modes/mode_basis.hpp"
#include "rom/interpolation/spd_math.hpp"
#include "rom/model/modal_extraction.hpp"
#include "rom/model/modal_stress_extraction.hpp"

namespace mastrom::rom {
namespace {

double maxAbs(const SparseMatrixD& a) {
  double m = 0.0;
  for (Eigen::Index k = 0; k < a.outerSize(); ++k)
    for (SparseMatrixD::InnerIterator it(a, k); it; ++it) m = std::max(m, std::abs(it.value()));
  return m;
}

Eigen::MatrixXd project(const SparseMatrixD& a, const Eigen::MatrixXd& v) {
  const Eigen::MatrixXd av = a * v;
  Eigen::MatrixXd out;
  out.noalias() = v.transpose() * av;
  return 0.5 * (out + out.transpose());
}

void requirePositive(double value, const char* name) {
  MASTROM_REQUIRE(std::isfinite(value) && value > 0, InputError, "affine model: ", name, " = ",
                  value, " must be finite and > 0");
}

/// A locked mast at thickness h, linearised at its stress-free reference.
struct Linearized {
  fullorder::MastModel model;
  modes::Linearization lin;
};

Linearized linearizeAt(fullorder::MastParameters params, double thickness_m, double angle_rad) {
  params.interface_thickness_m = thickness_m;
  fullorder::MastModel model = modes::buildLockedMast(std::move(params), angle_rad);
  modes::Linearization lin = modes::linearizeMast(model);
  MASTROM_REQUIRE(!lin.equilibrium_solved, InputError, "affine model: the mast with h = ",
                  thickness_m, " m is not force-free at its reference state; the affine "
                  "decomposition holds only at the stress-free reference (no gravity, no load)");
  return {std::move(model), std::move(lin)};
}

std::vector<double> axisPoints(double lo, double hi, int n) {
  if (!(hi > lo) || n <= 1) return {0.5 * (lo + hi)};
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = lo + (hi - lo) * i / (n - 1);
  v.back() = hi;
  return v;
}

bool inRange(double x, double lo, double hi) {
  const double tol = 1e-9 * std::max(std::abs(lo), std::abs(hi));
  return x >= lo - tol && x <= hi + tol;
}

/// The stress rows of the basis columns per unit E (membrane) and E·h (bending), from the
/// linearisations at h1 and h2 (AffineReducedModel::stress_rows).
Eigen::MatrixXd basisStressRows(const Linearized& a, double h1, const Linearized& b, double h2,
                                double e0, const Eigen::MatrixXd& basis) {
  // σ_m = E D̂ ε and σ_b = (E h/2) D̂ κ (fullorder/shell_material.hpp, shell_stress.cpp): the rows at
  // h1 per unit E resp. E·h1, checked against those at h2 — the scaling the online part relies on.
  Eigen::MatrixXd rows = linearizedStressRows(a.model, a.lin.q, basis);
  const Eigen::MatrixXd at_h2 = linearizedStressRows(b.model, b.lin.q, basis);
  const Eigen::Index points = rows.rows() / kStressRowsPerPoint;
  Eigen::MatrixXd predicted(rows.rows(), rows.cols());
  for (Eigen::Index p = 0; p < points; ++p) {
    const Eigen::Index m = kStressRowsPerPoint * p, bend = m + 3;
    rows.middleRows(m, 3) /= e0;
    rows.middleRows(bend, 3) /= e0 * h1;
    predicted.middleRows(m, 3) = e0 * rows.middleRows(m, 3);
    predicted.middleRows(bend, 3) = (e0 * h2) * rows.middleRows(bend, 3);
  }
  const double scale = at_h2.cwiseAbs().maxCoeff();
  const double gap = (predicted - at_h2).cwiseAbs().maxCoeff();
  MASTROM_REQUIRE(gap <= 1e-10 * scale, NumericalError,
                  "affine model: the interface stresses do not scale as E and E*h between h = ", h1,
                  " m and ", h2, " m (largest gap ", gap, " of ", scale, ")");
  return rows;
}

}  // namespace

SparseMatrixD AffineStiffness::at(double thickness_m, double youngs_modulus_pa) const {
  const double h = thickness_m;
  return youngs_modulus_pa * (h * membrane + (h * h * h) * bending);
}

SparseMatrixD AffineMass::at(double areal_density_kg_m2) const {
  return rigid + areal_density_kg_m2 * shell;
}

AffineStiffness separateStiffness(const SparseMatrixD& k1, double h1, const SparseMatrixD& k2,
                                  double h2, double youngs_modulus_pa) {
  requirePositive(h1, "h1");
  requirePositive(h2, "h2");
  requirePositive(youngs_modulus_pa, "E");
  MASTROM_REQUIRE(h1 != h2, InputError, "affine model: the two thicknesses must differ (h = ", h1,
                  " m)");
  MASTROM_REQUIRE(k1.rows() == k2.rows() && k1.cols() == k2.cols(), InputError,
                  "affine model: stiffness matrices of different sizes");
  // [h₁ h₁³; h₂ h₂³][E K_m; E K_b] = [K₁; K₂], by Cramer's rule per entry.
  const double det = h1 * h2 * (h2 * h2 - h1 * h1);
  const double scale = 1.0 / (det * youngs_modulus_pa);
  AffineStiffness out;
  out.membrane = (h2 * h2 * h2 * scale) * k1 - (h1 * h1 * h1 * scale) * k2;
  out.bending = (h1 * scale) * k2 - (h2 * scale) * k1;
  return out;
}

AffineMass separateMass(const SparseMatrixD& m1, double rho_h1, const SparseMatrixD& m2,
                        double rho_h2) {
  requirePositive(rho_h1, "rho h1");
  requirePositive(rho_h2, "rho h2");
  MASTROM_REQUIRE(rho_h1 != rho_h2, InputError,
                  "affine model: the two areal densities must differ (rho h = ", rho_h1, ")");
  MASTROM_REQUIRE(m1.rows() == m2.rows() && m1.cols() == m2.cols(), InputError,
                  "affine model: mass matrices of different sizes");
  AffineMass out;
  out.shell = (1.0 / (rho_h2 - rho_h1)) * (m2 - m1);
  out.rigid = (rho_h2 / (rho_h2 - rho_h1)) * m1 - (rho_h1 / (rho_h2 - rho_h1)) * m2;
  return out;
}

void AffineParameterBox::validate() const {
  const std::pair<double, double> ranges[3] = {{thickness_min_m, thickness_max_m},
                                               {youngs_modulus_min_pa, youngs_modulus_max_pa},
                                               {density_min_kg_m3, density_max_kg_m3}};
  const char* names[3] = {"thickness [m]", "Young's modulus [Pa]", "density [kg/m^3]"};
  for (int i = 0; i < 3; ++i) {
    const auto [lo, hi] = ranges[i];
    MASTROM_REQUIRE(std::isfinite(lo) && std::isfinite(hi) && lo > 0 && hi >= lo, InputError,
                    "affine model: the ", names[i], " range [", lo, ", ", hi,
                    "] must be finite with 0 < min <= max");
  }
}

void AffineModelOptions::validate() const {
  box.validate();
  MASTROM_REQUIRE(std::isfinite(lock_angle_rad), InputError, "affine model: lock angle = ",
                  lock_angle_rad, " rad is not finite");
  MASTROM_REQUIRE(snapshot_points >= 1 && snapshot_points <= 50, InputError,
                  "affine model: snapshot_points = ", snapshot_points, " must be in [1, 50]");
  MASTROM_REQUIRE(snapshot_modes >= 1, InputError, "affine model: snapshot_modes = ",
                  snapshot_modes, " must be >= 1");
  MASTROM_REQUIRE(basis_tolerance > 0 && basis_tolerance < 1, InputError,
                  "affine model: basis_tolerance = ", basis_tolerance, " must be in (0, 1)");
  MASTROM_REQUIRE(modes >= 1, InputError, "affine model: modes = ", modes, " must be >= 1");
}

AffineModalModel AffineModalModel::build(const fullorder::MastParameters& base,
                                         const AffineModelOptions& options) {
  options.validate();
  MASTROM_REQUIRE(base.gravity_m_s2.isZero(), InputError,
                  "affine model: valid only without gravity (gravity = (", base.gravity_m_s2.x(),
                  ", ", base.gravity_m_s2.y(), ", ", base.gravity_m_s2.z(),
                  ") m/s^2): the preload's geometric stiffness is not affine in h, E and rho; "
                  "use an interpolated database instead");
  const AffineParameterBox& box = options.box;
  AffineModalModel out;
  out.online_.thickness_min_m = box.thickness_min_m;
  out.online_.thickness_max_m = box.thickness_max_m;
  out.online_.youngs_modulus_min_pa = box.youngs_modulus_min_pa;
  out.online_.youngs_modulus_max_pa = box.youngs_modulus_max_pa;
  out.online_.density_min_kg_m3 = box.density_min_kg_m3;
  out.online_.density_max_kg_m3 = box.density_max_kg_m3;
  out.online_.modes = options.modes;
  out.online_.damping_s = base.damping_s;
  out.online_.reference_angle_rad = options.lock_angle_rad;

  // Two linearisations at the ends of the thickness range (same E, ρ: those of `base`).
  const double e0 = base.youngs_modulus_pa, rho0 = base.density_kg_m3;
  const double h1 = box.thickness_min_m;
  const double h2 = box.thickness_max_m > h1 ? box.thickness_max_m : 1.5 * h1;
  const Linearized a = linearizeAt(base, h1, options.lock_angle_rad);
  const Linearized b = linearizeAt(base, h2, options.lock_angle_rad);
  // What the decomposition assumes: the reference state and the constraints do not depend on h.
  const double q_scale = std::max(1.0, a.lin.q.cwiseAbs().maxCoeff());
  MASTROM_REQUIRE((a.lin.q - b.lin.q).cwiseAbs().maxCoeff() <= 1e-14 * q_scale, NumericalError,
                  "affine model: the reference state changes with the thickness (is the radius "
                  "derived from an inner diameter?)");
  const double g_diff = maxAbs(SparseMatrixD(a.lin.problem.constraint_jacobian -
                                             b.lin.problem.constraint_jacobian));
  MASTROM_REQUIRE(g_diff <= 1e-12 * maxAbs(a.lin.problem.constraint_jacobian), NumericalError,
                  "affine model: the constraint Jacobian changes with the thickness (max diff ",
                  g_diff, ")");
  out.stiffness_ = separateStiffness(a.lin.problem.stiffness, h1, b.lin.problem.stiffness, h2, e0);
  out.mass_ = separateMass(a.lin.problem.mass, rho0 * h1, b.lin.problem.mass, rho0 * h2);
  out.constraint_jacobian_ = a.lin.problem.constraint_jacobian;
  out.q_reference_ = a.lin.q;

  // Snapshots over the (h, ρ) box — E scales K and changes no mode shape — from the affine terms
  // (exactly the matrices a linearisation at that point would assemble).
  const std::vector<double> hs =
      axisPoints(box.thickness_min_m, box.thickness_max_m, options.snapshot_points);
  const std::vector<double> rhos =
      axisPoints(box.density_min_kg_m3, box.density_max_kg_m3, options.snapshot_points);
  const Eigen::Index n = out.q_reference_.size();
  Eigen::MatrixXd snapshots(n, static_cast<Eigen::Index>(hs.size() * rhos.size()) *
                                   options.snapshot_modes);
  Eigen::Index col = 0;
  for (double rho : rhos) {
    for (double h : hs) {
      modes::ConstrainedEigenproblem problem;
      problem.stiffness = out.stiffness_.at(h, e0);
      problem.mass = out.mass_.at(rho * h);
      problem.constraint_jacobian = out.constraint_jacobian_;
      modes::EigenSolverOptions eo;
      eo.count = options.snapshot_modes;
      eo.backend = options.backend;
      eo.communicator = MPI_COMM_SELF;
      const modes::EigenResult res = modes::solveConstrainedEigenproblem(problem, eo);
      MASTROM_REQUIRE(res.ok(), NumericalError, "affine model: snapshot modal solve at h = ", h,
                      " m, rho = ", rho, " kg/m^3: ", modes::toString(res.status), ": ",
                      res.message);
      snapshots.middleCols(col, options.snapshot_modes) = res.modes;
      col += options.snapshot_modes;
    }
  }

  // POD in the mass inner product of the box centre: M_ref = Pᵀ L Lᵀ P, ‖x‖²_M = ‖Lᵀ P x‖², so
  // the SVD Lᵀ P S = U Σ Wᵀ gives the M_ref-orthonormal basis V = Pᵀ L⁻ᵀ U_r.
  const double h_c = 0.5 * (box.thickness_min_m + box.thickness_max_m);
  const double rho_c = 0.5 * (box.density_min_kg_m3 + box.density_max_kg_m3);
  const SparseMatrixD m_ref = out.mass_.at(rho_c * h_c);
  const Eigen::SimplicialLLT<SparseMatrixD> llt(m_ref);
  MASTROM_REQUIRE(llt.info() == Eigen::Success, NumericalError,
                  "affine model: the reference mass matrix is not positive definite");
  const Eigen::MatrixXd permuted = llt.permutationP() * snapshots;
  const Eigen::MatrixXd whitened = llt.matrixU() * permuted;  // Lᵀ P S
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(whitened, Eigen::ComputeThinU);
  out.singular_values_ = svd.singularValues();
  const double cutoff = options.basis_tolerance * out.singular_values_[0];
  const Eigen::Index r = (out.singular_values_.array() > cutoff).count();
  MASTROM_REQUIRE(options.modes <= r, InputError, "affine model: modes = ", options.modes,
                  " exceeds the basis size ", r, " (raise snapshot_modes or snapshot_points)");
  const Eigen::MatrixXd coeffs = llt.matrixU().solve(svd.matrixU().leftCols(r));
  Eigen::MatrixXd v = llt.permutationPinv() * coeffs;
  // The weakest kept directions carry round-off amplified by σ_1/σ_r (up to 1/tolerance), which
  // shows as GV ~ 1e-8: project onto null(G) with the Euclidean projector I − Gᵀ(GGᵀ)⁻¹G and
  // restore VᵀM_refV = I (a Cholesky of the Gram matrix), so GV = 0 to round-off.
  const SparseMatrixD& g = out.constraint_jacobian_;
  if (g.rows() > 0) {
    const Eigen::SimplicialLDLT<SparseMatrixD> ggt(SparseMatrixD(g * g.transpose()));
    MASTROM_REQUIRE(ggt.info() == Eigen::Success, NumericalError,
                    "affine model: the constraint Jacobian does not have full row rank");
    const Eigen::MatrixXd gv = g * v;
    v -= g.transpose() * ggt.solve(gv);
  }
  const Eigen::MatrixXd gram = v.transpose() * (m_ref * v);
  const Eigen::LLT<Eigen::MatrixXd> gram_llt(0.5 * (gram + gram.transpose()));
  MASTROM_REQUIRE(gram_llt.info() == Eigen::Success, NumericalError,
                  "affine model: the basis lost rank in its projection onto the constraints");
  out.basis_ = gram_llt.matrixL().solve(v.transpose()).transpose();  // V L⁻ᵀ

  out.online_.k_membrane = project(out.stiffness_.membrane, out.basis_);
  out.online_.k_bending = project(out.stiffness_.bending, out.basis_);
  out.online_.m_rigid = project(out.mass_.rigid, out.basis_);
  out.online_.m_shell = project(out.mass_.shell, out.basis_);

  // Output operators on the basis columns: extractModalModel itself, run at the two
  // linearisations (masses M(ρ₀h₁), M(ρ₀h₂)), then split like the mass.
  LinearizedModes lm;
  lm.q_reference = a.lin.q;
  lm.reference_angle_rad = options.lock_angle_rad;
  lm.omega_squared = Eigen::VectorXd::Ones(r);  // unused by the operators
  lm.modes = out.basis_;
  lm.mass = a.lin.problem.mass;
  const ModalModel xa = extractModalModel(a.model, lm);
  lm.mass = b.lin.problem.mass;
  const ModalModel xb = extractModalModel(b.model, lm);
  const double sa = rho0 * h1, sb = rho0 * h2;
  const double cs = 1.0 / (sb - sa);
  auto split = [&](const auto& va, const auto& vb, auto& rigid, auto& shell) {
    shell = cs * (vb - va);
    rigid = va - sa * shell;
  };
  split(xa.rotation_participation, xb.rotation_participation, out.online_.gamma_rigid, out.online_.gamma_shell);
  split(xa.centrifugal_participation, xb.centrifugal_participation, out.online_.gamma_c_rigid,
        out.online_.gamma_c_shell);
  split(xa.momentum_participation, xb.momentum_participation, out.online_.momentum_rigid,
        out.online_.momentum_shell);
  split(xa.coriolis, xb.coriolis, out.online_.coriolis_rigid, out.online_.coriolis_shell);
  split(xa.inertia_z_kg_m2, xb.inertia_z_kg_m2, out.online_.inertia_rigid, out.online_.inertia_shell);
  split(xa.total_mass_kg, xb.total_mass_kg, out.online_.mass_rigid, out.online_.mass_shell);
  const Eigen::Vector3d fa = xa.centroid_m * xa.total_mass_kg;
  const Eigen::Vector3d fb = xb.centroid_m * xb.total_mass_kg;
  split(fa, fb, out.online_.first_moment_rigid, out.online_.first_moment_shell);
  out.online_.end_rotation = xa.end_rotation;
  out.online_.end_translation = xa.end_translation;
  out.online_.end_position = xa.end_position_m;
  MASTROM_ASSERT((xa.end_rotation - xb.end_rotation).norm() <= 1e-12 * xa.end_rotation.norm());
  if (options.stresses && a.model.interfaceCount() > 0)
    out.online_.stress_rows = basisStressRows(a, h1, b, h2, e0, out.basis_);
  return out;
}

AffineReducedModel AffineModalModel::reduced() const { return online_; }

AffineParameterBox AffineModalModel::box() const {
  AffineParameterBox b;
  b.thickness_min_m = online_.thickness_min_m;
  b.thickness_max_m = online_.thickness_max_m;
  b.youngs_modulus_min_pa = online_.youngs_modulus_min_pa;
  b.youngs_modulus_max_pa = online_.youngs_modulus_max_pa;
  b.density_min_kg_m3 = online_.density_min_kg_m3;
  b.density_max_kg_m3 = online_.density_max_kg_m3;
  return b;
}

AffineModalModel AffineModalModel::fromReduced(const AffineReducedModel& r) {
  r.validate();
  AffineModalModel out;
  out.online_ = r;
  out.box().validate();
  return out;
}

void AffineModalModel::requireInBox(double h, double e, double rho) const {
  const double values[3] = {h, e, rho};
  const double lo[3] = {online_.thickness_min_m, online_.youngs_modulus_min_pa, online_.density_min_kg_m3};
  const double hi[3] = {online_.thickness_max_m, online_.youngs_modulus_max_pa, online_.density_max_kg_m3};
  const char* names[3] = {"thickness [m]", "Young's modulus [Pa]", "density [kg/m^3]"};
  for (int i = 0; i < 3; ++i)
    MASTROM_REQUIRE(std::isfinite(values[i]) && inRange(values[i], lo[i], hi[i]), InputError,
                    "affine model: ", names[i], " = ", values[i],
                    " outside the model's box [", lo[i], ", ", hi[i], "]");
}

Eigen::MatrixXd AffineModalModel::reducedStiffness(double thickness_m,
                                                   double youngs_modulus_pa) const {
  const double h = thickness_m;
  return youngs_modulus_pa * (h * online_.k_membrane + (h * h * h) * online_.k_bending);
}

Eigen::MatrixXd AffineModalModel::reducedMass(double thickness_m, double density_kg_m3) const {
  return online_.m_rigid + (density_kg_m3 * thickness_m) * online_.m_shell;
}

AffineSolution AffineModalModel::solve(double thickness_m, double youngs_modulus_pa,
                                       double density_kg_m3) const {
  requireInBox(thickness_m, youngs_modulus_pa, density_kg_m3);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(
      reducedStiffness(thickness_m, youngs_modulus_pa), reducedMass(thickness_m, density_kg_m3),
      Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  MASTROM_REQUIRE(ges.info() == Eigen::Success, NumericalError,
                  "affine model: the reduced eigenproblem failed at h = ", thickness_m,
                  " m, E = ", youngs_modulus_pa, " Pa, rho = ", density_kg_m3, " kg/m^3");
  AffineSolution sol;
  sol.omega_squared = ges.eigenvalues().head(online_.modes);
  sol.coefficients = ges.eigenvectors().leftCols(online_.modes);  // YᵀM_rY = I
  modes::normaliseColumnSigns(sol.coefficients);
  return sol;
}

ModalModel AffineModalModel::evaluate(double thickness_m, double youngs_modulus_pa,
                                      double density_kg_m3) const {
  AffineSolution sol;
  return evaluate(thickness_m, youngs_modulus_pa, density_kg_m3, sol);
}

Eigen::MatrixXd AffineModalModel::stressModes(double thickness_m, double youngs_modulus_pa,
                                              const Eigen::MatrixXd& coefficients) const {
  MASTROM_REQUIRE(hasStresses(), InputError,
                  "affine model: built without the stress rows of its basis");
  Eigen::MatrixXd rows = online_.stress_rows;  // per unit E (membrane), per unit E·h (bending)
  const Eigen::Index points = rows.rows() / kStressRowsPerPoint;
  for (Eigen::Index p = 0; p < points; ++p) {
    rows.middleRows(kStressRowsPerPoint * p, 3) *= youngs_modulus_pa;
    rows.middleRows(kStressRowsPerPoint * p + 3, 3) *= youngs_modulus_pa * thickness_m;
  }
  return rows * coefficients;
}

ModalModel AffineModalModel::evaluate(double thickness_m, double youngs_modulus_pa,
                                      double density_kg_m3, AffineSolution& solution) const {
  solution = solve(thickness_m, youngs_modulus_pa, density_kg_m3);
  const AffineSolution& sol = solution;
  const Eigen::MatrixXd& y = sol.coefficients;
  const double s = density_kg_m3 * thickness_m;  // ρh
  ModalModel m;
  m.omega_rad_s = sol.omega_squared.cwiseMax(0.0).cwiseSqrt();
  m.damping_ratio = (0.5 * online_.damping_s) * m.omega_rad_s;  // C = μK: φᵀCφ/(2ω) = μω/2
  m.rotation_participation.noalias() = y.transpose() * (online_.gamma_rigid + s * online_.gamma_shell);
  m.centrifugal_participation.noalias() = y.transpose() * (online_.gamma_c_rigid + s * online_.gamma_c_shell);
  m.momentum_participation.noalias() = (online_.momentum_rigid + s * online_.momentum_shell) * y;
  const Eigen::MatrixXd coriolis = online_.coriolis_rigid + s * online_.coriolis_shell;
  m.coriolis.noalias() = y.transpose() * coriolis * y;
  m.end_rotation.noalias() = online_.end_rotation * y;
  m.end_translation.noalias() = online_.end_translation * y;
  m.inertia_z_kg_m2 = online_.inertia_rigid + s * online_.inertia_shell;
  m.total_mass_kg = online_.mass_rigid + s * online_.mass_shell;
  m.centroid_m = (online_.first_moment_rigid + s * online_.first_moment_shell) / m.total_mass_kg;
  m.end_position_m = online_.end_position;
  m.reference_angle_rad = online_.reference_angle_rad;
  m.gravity_m_s2 = Eigen::Vector3d::Zero();
  m.validate();
  return m;
}

}  // namespace mastrom::rom
