// Internals shared by the implementation files of GeneralizedAlpha (generalized_alpha.cpp: the
// step; generalized_alpha_solvers.cpp: the factorisations; generalized_alpha_index1.cpp: the
// recovered accelerations). Not part of the library's interface.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseLU>
#include <memory>

#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mass_saddle_solver.hpp"
#include "fullorder/saddle_ldlt.hpp"
#include "fullorder/schur_complement.hpp"
#include "fullorder/supernodal_cholesky.hpp"

namespace mastrom::fullorder {

struct GeneralizedAlpha::Solver {
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
  /// For [M Φ_qᵀ; Φ_q 0] with M positive definite: the Schur-complement solver instead of `lu`.
  std::unique_ptr<MassSaddleSolver> schur;
  /// For the iteration matrix when block_ready: its symmetric part solved through the Schur
  /// complement over a supernodal Cholesky factor of its (1,1) block, or — where that costs more
  /// (large n·m: a long mast) — through the LDLᵀ factor of the whole saddle matrix (`saddle`, set
  /// then), instead of `lu` (factorizeIterationBySchur()).
  std::unique_ptr<SupernodalCholesky> block;
  SchurComplement block_schur;
  std::unique_ptr<SaddleLdlt> saddle;
  bool route_chosen = false;  ///< between block_schur and saddle, once (the pattern is fixed)
  bool block_ready = false;
  bool analysed = false;
  double angle_rad = 0.0;  ///< DaeSystem::rotationAngle at the factorised state
};

namespace generalized_alpha_detail {
inline double maxAbs(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

/// Copy into vectors already of the right size after the first call: no allocation per step.
inline void recordInputs(FactorizationInputs& f, const Eigen::VectorXd& q,
                         const Eigen::VectorXd& qdot, const Eigen::VectorXd& lambda, double t,
                         const IterationCoefficients& c, bool general_lu) {
  f.valid = true;
  f.general_lu = general_lu;
  f.time_s = t;
  f.q = q;
  f.qdot = qdot;
  f.lambda = lambda;
  f.coefficients = c;
}
}  // namespace generalized_alpha_detail

}  // namespace mastrom::fullorder
