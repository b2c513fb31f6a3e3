// Modal analysis and per-mode quantities (see modal_analysis.hpp).
#include "modes/modal_analysis.hpp"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.hpp"
#include "fullorder/block_rotation.hpp"
#include "modes/modal_projections.hpp"
#include "modes/mode_basis.hpp"
#include "modes/mode_labels.hpp"

namespace mastrom::modes {
namespace {

/// Field of the rotation about the unit axis `axis` through the origin: axis × every 3-block (the
/// probes of the lateral and axial rotations; about Z it is fullorder::rotationRateField).
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

  for (const auto& [begin, end] : degenerateClusters(values, cluster_tolerance)) {
    const Eigen::Index c = end - begin;
    {
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
      normaliseColumnSigns(result.modes.middleCols(begin, c));
    }
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

  if (eigen.modes.cols() > 1) {
    Eigen::MatrixXd probes(n, 6);
    probes.col(0) = fullorder::rotationRateField(lin.q);
    probes.col(1) = system.uniformField(Eigen::Vector3d::UnitZ());
    probes.col(2) = system.uniformField(lateral);
    probes.col(3) = system.uniformField(axial);
    probes.col(4) = rotationFieldAbout(lin.q, lateral);
    probes.col(5) = rotationFieldAbout(lin.q, axial);
    canonicalizeDegenerateModes(eigen, mass, probes, options.cluster_tolerance);
  }

  keepNearestTarget(eigen, options.solver.count, options.solver.target_rad2_s2);

  const Eigen::Index k = eigen.modes.cols();
  ModalProjections p = projectModes(system, mass, lin.damping, lin.q, eigen.eigenvalues_rad2_s2,
                                    eigen.modes, options.end_body);
  ModalAnalysis out;
  out.rotational_inertia_kg_m2 = p.inertia_z_kg_m2;
  out.participation = std::move(p.rotation_participation);
  out.effective_mass_fraction =
      out.rotational_inertia_kg_m2 > 0.0
          ? Eigen::VectorXd(out.participation.array().square() / out.rotational_inertia_kg_m2)
          : Eigen::VectorXd::Zero(k);
  out.centrifugal_participation = std::move(p.centrifugal_participation);
  out.translation_participation = p.translation_participation.transpose();
  out.coriolis = std::move(p.coriolis);
  out.damping_ratio = std::move(p.damping_ratio);
  out.end_rotation = p.end_rotation.transpose();
  out.end_displacement = p.end_translation.transpose();

  const Eigen::MatrixXd& phi = eigen.modes;
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
