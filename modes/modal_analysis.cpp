// Modal analysis and per-mode quantities (see modal_analysis.hpp).
#include "modes/modal_analysis.hpp"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.hpp"
#include "modes/mode_labels.hpp"

namespace mastrom::modes {
namespace {

/// The sign rule of EigenResult: the first entry within 1e-6 of the largest magnitude is positive.
void normaliseSign(Eigen::Ref<Eigen::VectorXd> phi) {
  const double largest = phi.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < phi.size(); ++i) {
    if (std::abs(phi(i)) >= (1.0 - 1e-6) * largest) {
      if (phi(i) < 0.0) phi *= -1.0;
      return;
    }
  }
}

/// Field of the rotation about the unit axis `axis` through the origin: axis × every 3-block.
Eigen::VectorXd rotationFieldAbout(const Eigen::VectorXd& q, const Eigen::Vector3d& axis) {
  Eigen::VectorXd out(q.size());
  for (Eigen::Index k = 0; k < q.size(); k += 3)
    out.segment<3>(k) = axis.cross(Eigen::Vector3d(q.segment<3>(k)));
  return out;
}

/// Deterministic pseudo-random field (the same on every backend, rank and run).
Eigen::VectorXd pseudoRandomField(Eigen::Index n, int seed) {
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i)
    v(i) = std::sin(0.7548776662 * double(i + 1) * double(seed + 1) + 0.5698402910 * seed);
  return v;
}

/// Keep the `count` pairs nearest σ (ascending order preserved); a solve for more pairs that
/// delivered at least `count` counts as converged.
void keepNearestTarget(EigenResult& eigen, int count, double sigma) {
  const Eigen::Index k = eigen.modes.cols();
  if (k > count) {
    std::vector<Eigen::Index> order(static_cast<std::size_t>(k));
    for (Eigen::Index j = 0; j < k; ++j) order[static_cast<std::size_t>(j)] = j;
    std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
      return std::abs(eigen.eigenvalues_rad2_s2(a) - sigma) <
             std::abs(eigen.eigenvalues_rad2_s2(b) - sigma);
    });
    order.resize(static_cast<std::size_t>(count));
    std::sort(order.begin(), order.end());
    Eigen::MatrixXd modes(eigen.modes.rows(), count);
    Eigen::VectorXd values(count), frequencies(count);
    for (int j = 0; j < count; ++j) {
      const Eigen::Index src = order[static_cast<std::size_t>(j)];
      modes.col(j) = eigen.modes.col(src);
      values(j) = eigen.eigenvalues_rad2_s2(src);
      frequencies(j) = eigen.frequencies_hz(src);
    }
    eigen.modes = std::move(modes);
    eigen.eigenvalues_rad2_s2 = values;
    eigen.frequencies_hz = frequencies;
    eigen.converged = count;
  }
  if (eigen.status == EigenStatus::NotConverged && eigen.converged >= count) {
    eigen.status = EigenStatus::Converged;
    eigen.message += " (the requested pairs converged)";
  }
  eigen.requested = count;
}

}  // namespace

void canonicalizeDegenerateModes(EigenResult& result, const SparseMatrix& mass,
                                 const Eigen::Ref<const Eigen::MatrixXd>& probes,
                                 double cluster_tolerance) {
  const Eigen::Index k = result.modes.cols();
  const Eigen::Index n = result.modes.rows();
  if (k < 2) return;
  MASTROM_REQUIRE(probes.rows() == n && mass.rows() == n, InputError,
                  "canonicalizeDegenerateModes: sizes do not match");
  // Modal forces of the probes on every mode, and of a few fixed pseudo-random fields.
  constexpr int kRandomProbes = 4;
  Eigen::MatrixXd fields(n, probes.cols() + kRandomProbes);
  fields.leftCols(probes.cols()) = probes;
  for (int r = 0; r < kRandomProbes; ++r) fields.col(probes.cols() + r) = pseudoRandomField(n, r);
  Eigen::MatrixXd loads(n, fields.cols());
  loads.noalias() = mass * fields;
  const Eigen::VectorXd& values = result.eigenvalues_rad2_s2;

  Eigen::Index begin = 0;
  while (begin < k) {
    Eigen::Index end = begin + 1;
    while (end < k && std::abs(values(end) - values(end - 1)) <=
                          cluster_tolerance * std::max(std::abs(values(end)), 1e-300))
      ++end;
    const Eigen::Index c = end - begin;
    if (c >= 2) {
      const Eigen::MatrixXd cluster = result.modes.middleCols(begin, c);
      Eigen::MatrixXd forces(c, loads.cols());  // modal force of every probe on every mode
      forces.noalias() = cluster.transpose() * loads;
      Eigen::MatrixXd basis = Eigen::MatrixXd::Identity(c, c);  // coefficients of what is left
      Eigen::MatrixXd chosen(c, 0);
      for (Eigen::Index p = 0; p < forces.cols() && basis.cols() > 1; ++p) {
        // Significance against the probe's modal force on all returned modes.
        Eigen::VectorXd all_forces(k);
        all_forces.noalias() = result.modes.transpose() * loads.col(p);
        const double scale = all_forces.cwiseAbs().maxCoeff();
        const Eigen::VectorXd a = basis.transpose() * forces.col(p);
        if (!(scale > 0.0) || a.norm() <= 1e-6 * scale) continue;
        const Eigen::VectorXd y = a / a.norm();
        chosen.conservativeResize(c, chosen.cols() + 1);
        chosen.rightCols(1) = basis * y;
        // Orthonormal complement of y within the remaining space (Householder of y).
        const Eigen::HouseholderQR<Eigen::MatrixXd> qr(y);
        const Eigen::MatrixXd q = qr.householderQ();
        basis = (basis * q.rightCols(basis.cols() - 1)).eval();
      }
      Eigen::MatrixXd rotation(c, c);
      rotation << chosen, basis;
      result.modes.middleCols(begin, c) = cluster * rotation;
      for (Eigen::Index j = begin; j < end; ++j) normaliseSign(result.modes.col(j));
    }
    begin = end;
  }
}

ModalAnalysis computeModalQuantities(const fullorder::MultibodySystem& system,
                                     const Linearization& lin, EigenResult eigen,
                                     const ModalAnalysisOptions& options) {
  const Eigen::Index n = lin.problem.dofs();
  MASTROM_REQUIRE(system.dofCount() == n && lin.q.size() == n, InputError,
                  "modal analysis: the system (", system.dofCount(),
                  " DOFs) and the linearisation (", n, ") do not match");
  MASTROM_REQUIRE(eigen.modes.rows() == n || eigen.modes.cols() == 0, InputError,
                  "modal analysis: the modes have ", eigen.modes.rows(), " rows for ", n, " DOFs");
  MASTROM_REQUIRE(options.end_body >= -1 && options.end_body < system.bodyCount(), InputError,
                  "modal analysis: end_body = ", options.end_body, " is out of range (−1 or 0..",
                  system.bodyCount() - 1, ")");
  const SparseMatrix& mass = lin.problem.mass;
  const double theta = options.frame_angle_rad;
  const Eigen::Vector3d axial(std::cos(theta), std::sin(theta), 0.0);
  const Eigen::Vector3d lateral(-std::sin(theta), std::cos(theta), 0.0);

  const Eigen::VectorXd omega_q = rotationField(lin.q);
  if (eigen.modes.cols() > 1) {
    Eigen::MatrixXd probes(n, 6);
    probes.col(0) = omega_q;
    probes.col(1) = system.uniformField(Eigen::Vector3d::UnitZ());
    probes.col(2) = system.uniformField(lateral);
    probes.col(3) = system.uniformField(axial);
    probes.col(4) = rotationFieldAbout(lin.q, lateral);
    probes.col(5) = rotationFieldAbout(lin.q, axial);
    canonicalizeDegenerateModes(eigen, mass, probes, options.cluster_tolerance);
  }

  keepNearestTarget(eigen, options.solver.count, options.solver.target_rad2_s2);

  ModalAnalysis out;
  const Eigen::Index k = eigen.modes.cols();
  const Eigen::MatrixXd& phi = eigen.modes;
  Eigen::MatrixXd m_phi(n, k);
  m_phi.noalias() = mass * phi;

  const Eigen::VectorXd m_omega_q = mass * omega_q;
  out.rotational_inertia_kg_m2 = omega_q.dot(m_omega_q);
  out.participation.noalias() = phi.transpose() * m_omega_q;
  out.effective_mass_fraction =
      out.rotational_inertia_kg_m2 > 0.0
          ? Eigen::VectorXd(out.participation.array().square() / out.rotational_inertia_kg_m2)
          : Eigen::VectorXd::Zero(k);
  const Eigen::VectorXd omega2_q = rotationField(omega_q);
  out.centrifugal_participation.noalias() = m_phi.transpose() * omega2_q;
  out.translation_participation.resize(k, 3);
  for (int j = 0; j < 3; ++j)
    out.translation_participation.col(j).noalias() =
        m_phi.transpose() * system.uniformField(Eigen::Vector3d::Unit(j));
  Eigen::MatrixXd omega_phi(n, k);
  for (Eigen::Index j = 0; j < k; ++j) omega_phi.col(j) = rotationField(phi.col(j));
  out.coriolis.noalias() = m_phi.transpose() * omega_phi;

  out.damping_ratio.resize(k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const double c = phi.col(j).dot(lin.damping * phi.col(j));
    const double omega = std::sqrt(std::abs(eigen.eigenvalues_rad2_s2(j)));
    out.damping_ratio(j) = omega > 0.0 ? c / (2.0 * omega) : 0.0;
  }

  out.end_rotation = Eigen::MatrixXd::Zero(k, 3);
  out.end_displacement = Eigen::MatrixXd::Zero(k, 3);
  if (options.end_body >= 0) {
    const fullorder::RigidModule& body = system.body(options.end_body);
    const int offset = system.bodyDofOffset(options.end_body);
    const fullorder::Vec12 q_body = lin.q.segment<12>(offset);
    for (Eigen::Index j = 0; j < k; ++j) {
      const fullorder::Vec12 d_body = phi.col(j).segment<12>(offset);
      out.end_rotation.row(j) = body.angularVelocity(q_body, d_body).transpose();
      // The centroid's displacement (r_c = A_c q: the offset from r_i included).
      out.end_displacement.row(j) = (body.centroidMap() * d_body).transpose();
    }
  }

  out.labels = labelModes(system, phi, theta);
  out.residuals = k > 0 ? projectedResiduals(lin.problem, eigen) : Eigen::VectorXd();
  out.eigen = std::move(eigen);
  return out;
}

ModalAnalysis runModalAnalysis(const fullorder::MultibodySystem& system, const Linearization& lin,
                               const ModalAnalysisOptions& options) {
  // A few pairs beyond the request, so that a degenerate cluster cut by the requested count is
  // still canonicalised as a whole (computeModalQuantities keeps options.solver.count pairs).
  EigenSolverOptions solver = options.solver;
  const Eigen::Index free_dofs = lin.problem.dofs() - lin.problem.constraints();
  MASTROM_REQUIRE(options.solver.count >= 1 && options.solver.count <= free_dofs, InputError,
                  "modal analysis: count = ", options.solver.count, " is out of range (1 … ",
                  free_dofs, ", the unconstrained DOFs n − m of the model)");
  solver.count =
      static_cast<int>(std::min<Eigen::Index>(options.solver.count + kClusterMargin, free_dofs));
  if (solver.subspace_dimension != 0 && solver.subspace_dimension <= solver.count)
    solver.subspace_dimension = solver.count + 1;
  EigenResult eigen = solveConstrainedEigenproblem(lin.problem, solver);
  return computeModalQuantities(system, lin, std::move(eigen), options);
}

ModalAnalysis analyzeMast(const fullorder::MastModel& model, const Linearization& lin,
                          const EigenSolverOptions& solver) {
  ModalAnalysisOptions options;
  options.solver = solver;
  options.end_body = model.endModule();
  options.frame_angle_rad = model.parameters().lock_angle_rad.value_or(0.0);
  return runModalAnalysis(model.system(), lin, options);
}

}  // namespace mastrom::modes
