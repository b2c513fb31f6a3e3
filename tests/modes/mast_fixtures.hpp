// Small masts and helpers shared by the modal-analysis tests (tests/modes/test_*.cpp).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"
#include "modes/linearize.hpp"

namespace mastrom::modes::fixtures {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

/// The mast of a default configuration with `modules` modules and an N_axial × N_circ mesh.
inline fullorder::MastParameters mastParameters(int modules, int n_axial = 2, int n_circ = 8) {
  Config c;
  c.mast.modules = modules;
  c.interface.elements_axial = n_axial;
  c.interface.elements_circumferential = n_circ;
  return fullorder::mastParametersFromConfig(c);
}

/// The resin prototype of docs/theory.md §1 (E ≈ 2.5 GPa, ν ≈ 0.38, ρ ≈ 1200) with a 0.5 mm wall: a
/// soft mast on which real gravity has a clearly measurable effect on the modes.
inline fullorder::MastParameters resinMast(int modules, int n_axial, int n_circ) {
  fullorder::MastParameters p = mastParameters(modules, n_axial, n_circ);
  p.youngs_modulus_pa = 2.5e9;
  p.poisson_ratio = 0.38;
  p.density_kg_m3 = 1200.0;
  p.interface_thickness_m = 0.0005;
  return p;
}

/// Closest point to y on the constraint manifold Φ = 0 (Newton with minimum-norm corrections).
inline Eigen::VectorXd projectOnConstraints(const fullorder::MultibodySystem& system,
                                            Eigen::VectorXd y) {
  Eigen::VectorXd phi;
  SparseMatrix g;
  for (int it = 0; it < 30; ++it) {
    system.constraints(y, 0.0, phi);
    if (phi.cwiseAbs().maxCoeff() <= 1e-16) break;
    system.constraintJacobian(y, 0.0, g);
    const SparseMatrix ggt = g * SparseMatrix(g.transpose());
    const Eigen::SimplicialLDLT<SparseMatrix> ldlt(ggt);
    const Eigen::VectorXd step = g.transpose() * ldlt.solve(phi);
    y -= step;
  }
  return y;
}

/// Π(q) − Π(q₀) for the total potential Π = U − q_gᵀ M q (strain energy plus gravity).
inline double potentialChange(const fullorder::MultibodySystem& system, const Eigen::VectorXd& q0,
                              const Eigen::VectorXd& q) {
  const Eigen::VectorXd dq = q - q0;
  return system.strainEnergy(q) - system.strainEnergy(q0) - system.gravityForce().dot(dq);
}

/// Second derivative of Π along a curve on the constraint manifold through q₀ with tangent z
/// (z ∈ null(G)): central difference of Π at the projections of q₀ ± s z, with s chosen so the
/// largest coordinate moves by `amplitude`. On the manifold this equals zᵀ(K_t + (Φ_qᵀλ)_q)z at an
/// equilibrium (see modes/linearize.hpp), independently of how the curve is chosen.
inline double manifoldCurvature(const fullorder::MultibodySystem& system, const Eigen::VectorXd& q0,
                                const Eigen::VectorXd& z, double amplitude = 1e-5) {
  const double s = amplitude / z.cwiseAbs().maxCoeff();
  const double plus = potentialChange(system, q0, projectOnConstraints(system, q0 + s * z));
  const double minus = potentialChange(system, q0, projectOnConstraints(system, q0 - s * z));
  return (plus + minus) / (s * s);
}

}  // namespace mastrom::modes::fixtures
