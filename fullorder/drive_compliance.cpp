// The mast's quasi-static answer to a unit drive acceleration (see the header; docs/theory.md
// §5.3a): one sparse LU of the held mast's saddle-point stiffness at the undeformed start state.
#include "fullorder/drive_compliance.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::fullorder {

DriveCompliance driveCompliance(const MastModel& model) {
  const MultibodySystem& sys = model.system();
  const int n = sys.dofCount(), m = sys.constraintCount();
  Eigen::VectorXd q, qdot;
  model.initialState(q, qdot);
  // The load of a unit θ̈: every 3-block of the coordinates (points, direction vectors, the shell
  // nodes' positions and gradients) accelerates by Z × block in the rigid turn.
  Eigen::VectorXd turn(n);
  for (int b = 0; b + 2 < n; b += 3) {
    turn[b] = -q[b + 1];
    turn[b + 1] = q[b];
    turn[b + 2] = 0.0;
  }
  const Eigen::VectorXd load = -(sys.massMatrix() * turn);

  // [K σGᵀ; σG 0] with σ the mean stiffness diagonal, as the static solver scales it; σ changes μ,
  // not u.
  SparseMatrix h = sys.iterationMatrixPattern();
  IterationCoefficients coeffs;
  coeffs.mass = 0.0;
  coeffs.damping = 0.0;
  coeffs.stiffness = 1.0;
  coeffs.constraint_scale = 1.0;
  const Eigen::VectorXd zero_n = Eigen::VectorXd::Zero(n), zero_m = Eigen::VectorXd::Zero(m);
  sys.assembleIterationMatrix(q, zero_n, zero_m, 0.0, coeffs, h);
  double diagonal = 0.0;
  for (int i = 0; i < n; ++i) diagonal += std::abs(h.coeff(i, i));
  coeffs.constraint_scale = diagonal > 0.0 ? diagonal / n : 1.0;
  sys.assembleIterationMatrix(q, zero_n, zero_m, 0.0, coeffs, h);
  Eigen::SparseLU<SparseMatrix> lu;
  lu.compute(h);
  MASTROM_REQUIRE(lu.info() == Eigen::Success, NumericalError,
                  "drive compliance: the held mast's stiffness could not be factorised (",
                  lu.lastErrorMessage(), ")");
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
  rhs.head(n) = load;
  const Eigen::VectorXd u = lu.solve(rhs).head(n);
  MASTROM_REQUIRE(u.allFinite(), NumericalError,
                  "drive compliance: non-finite deflection under a unit drive acceleration");

  DriveCompliance c;
  for (int k = 0; k < model.moduleCount(); ++k) {
    const int offset = model.moduleDofOffset(k);
    const double side = sys.body(k).axisLength();
    for (int i = 0; i < 12; ++i)  // [r_i, r_j, u, v]: points, then unit vectors (ncf_body.hpp)
      c.module_deflection_m_per_rad_s2 = std::max(
          c.module_deflection_m_per_rad_s2, (i < 6 ? 1.0 : side) * std::abs(u[offset + i]));
  }
  const double modal_mass = u.dot(sys.massMatrix() * u);
  const double work = u.dot(load);
  if (modal_mass > 0.0 && work > 0.0) c.rayleigh_frequency_rad_s = std::sqrt(work / modal_mass);
  return c;
}

}  // namespace mastrom::fullorder
