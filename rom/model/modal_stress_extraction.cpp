// Modal stress data of a linearised mast (see modal_stress_extraction.hpp).
#include "rom/model/modal_stress_extraction.hpp"

#include <vector>

#include "common/error.hpp"
#include "fullorder/block_rotation.hpp"
#include "fullorder/interface_stress.hpp"
#include "modes/constrained_statics.hpp"

namespace mastrom::rom {
namespace {

/// The rows of one point: σ_m = σ(ζ = 0), σ_b = σ(+h/2) − σ(0) (modal_stress.hpp).
void storePoint(const fullorder::ShellPointStress& s, Eigen::Ref<Eigen::VectorXd> rows) {
  rows.head<3>() = s.stress_pa[1];
  rows.tail<3>() = s.stress_pa[2] - s.stress_pa[1];
}

/// First point of each interface (offsets[I]) and the total (offsets[interfaces]).
Eigen::VectorXi pointOffsets(const fullorder::InterfaceStressResult& layout, int interfaces) {
  Eigen::VectorXi offsets(interfaces + 1);
  offsets[0] = 0;
  for (int i = 0; i < interfaces; ++i)
    offsets[i + 1] =
        offsets[i] + static_cast<int>(layout.point_coordinates[static_cast<std::size_t>(i)].size());
  return offsets;
}

/// Column j of `out` = the stress rows of monitor's linearisation at q along vectors.col(j).
void storeLinearizedRows(const fullorder::InterfaceStressMonitor& monitor,
                         const Eigen::VectorXi& offsets, const Eigen::VectorXd& q,
                         const Eigen::MatrixXd& vectors, Eigen::MatrixXd& out) {
  for (int i = 0; i + 1 < offsets.size(); ++i)
    for (Eigen::Index j = 0; j < vectors.cols(); ++j) {
      const std::vector<fullorder::ShellPointStress> s =
          monitor.linearizedPointStresses(i, q, vectors.col(j));
      for (std::size_t p = 0; p < s.size(); ++p)
        storePoint(s[p], out.col(j).segment(
                             kStressRowsPerPoint * (offsets[i] + static_cast<Eigen::Index>(p)),
                             kStressRowsPerPoint));
    }
}

}  // namespace

Eigen::MatrixXd linearizedStressRows(const fullorder::MastModel& model,
                                     const Eigen::VectorXd& q_reference,
                                     const Eigen::MatrixXd& vectors) {
  MASTROM_REQUIRE(
      q_reference.size() == model.system().dofCount() && vectors.rows() == q_reference.size(),
      InputError, "modal stresses: sizes disagree (", q_reference.size(), " DOFs, ", vectors.rows(),
      "-row vectors)");
  const int interfaces = model.interfaceCount();
  if (interfaces == 0) return Eigen::MatrixXd(0, vectors.cols());
  const fullorder::InterfaceStressMonitor monitor(model);
  const Eigen::VectorXi offsets = pointOffsets(monitor.result(), interfaces);
  Eigen::MatrixXd out(kStressRowsPerPoint * static_cast<Eigen::Index>(offsets[interfaces]),
                      vectors.cols());
  storeLinearizedRows(monitor, offsets, q_reference, vectors, out);
  return out;
}

ModalStress extractModalStress(const fullorder::MastModel& model,
                               const modes::ConstrainedEigenproblem& problem,
                               const Eigen::VectorXd& q_reference, const Eigen::MatrixXd& modes,
                               const Eigen::VectorXd& omega_squared) {
  const fullorder::MultibodySystem& sys = model.system();
  const Eigen::Index n = sys.dofCount(), k = modes.cols();
  MASTROM_REQUIRE(q_reference.size() == n && modes.rows() == n && omega_squared.size() == k &&
                      problem.dofs() == n && k >= 1,
                  InputError, "modal stresses: sizes disagree (", n, " DOFs, ", k, " modes)");
  MASTROM_REQUIRE((omega_squared.array() > 0.0).all(), InputError,
                  "modal stresses: the static correction needs every ω² > 0");
  ModalStress out;
  const int interfaces = model.interfaceCount();
  if (interfaces == 0) return out;
  const fullorder::InterfaceStressMonitor monitor(model);
  const fullorder::InterfaceStressResult& layout = monitor.result();

  // Load vectors of the modal forcing's scalars (modal_stress.hpp), and their static residuals.
  const Eigen::SparseMatrix<double>& mass = problem.mass;
  const Eigen::VectorXd omega_q = fullorder::rotationRateField(q_reference);
  Eigen::MatrixXd loads(n, kStressLoadCount);
  loads.col(0) = -(mass * omega_q);
  loads.col(1) = -(mass * fullorder::rotationRateField(omega_q));
  loads.col(2) = mass * sys.uniformField(Eigen::Vector3d::UnitX());
  loads.col(3) = mass * sys.uniformField(Eigen::Vector3d::UnitY());
  Eigen::MatrixXd residual = modes::solveConstrainedStatics(problem, loads);
  const Eigen::MatrixXd modal_loads = modes.transpose() * loads;  // φ_kᵀF_j
  residual.noalias() -= modes * (omega_squared.cwiseInverse().asDiagonal() * modal_loads);

  out.interface_offsets = pointOffsets(layout, interfaces);
  const int points = out.interface_offsets[interfaces];
  const Eigen::Index rows = kStressRowsPerPoint * static_cast<Eigen::Index>(points);
  out.modes.resize(rows, k);
  out.loads.resize(rows, kStressLoadCount);
  out.preload.resize(rows);
  out.points.resize(2, points);
  out.damping_s = model.parameters().damping_s;

  for (int i = 0; i < interfaces; ++i) {
    const Eigen::Index first = out.interface_offsets[i];
    const auto& coords = layout.point_coordinates[static_cast<std::size_t>(i)];
    for (std::size_t p = 0; p < coords.size(); ++p)
      out.points.col(first + static_cast<Eigen::Index>(p)) << coords[p][0], coords[p][1];
    const std::vector<fullorder::ShellPointStress> s =
        monitor.pointStresses(i, q_reference, nullptr);
    for (std::size_t p = 0; p < s.size(); ++p)
      storePoint(s[p],
                 out.preload.segment(kStressRowsPerPoint * (first + static_cast<Eigen::Index>(p)),
                                     kStressRowsPerPoint));
  }
  storeLinearizedRows(monitor, out.interface_offsets, q_reference, modes, out.modes);
  storeLinearizedRows(monitor, out.interface_offsets, q_reference, residual, out.loads);
  out.validate(static_cast<int>(k));
  return out;
}

}  // namespace mastrom::rom
