// Quantities derived from mode sets (docs/theory.md §3). So far: the modal assurance criterion
// (MAC) used to track and compare modes between angles, parameters and meshes.
#pragma once

#include <Eigen/Core>

#include "modes/eigen_solver.hpp"

namespace mastrom::modes {

/// MAC matrix between mode sets Φ (n × p) and Ψ (n × q), (p × q):
///     MAC_ij = (φ_iᵀ M ψ_j)² / ((φ_iᵀ M φ_i)(ψ_jᵀ M ψ_j)),
/// in [0, 1], invariant to the sign and scale of every mode; 1 = same shape, 0 = M-orthogonal.
/// Throws InputError on a row-count mismatch or a zero-norm mode.
Eigen::MatrixXd modalAssuranceCriterion(const Eigen::Ref<const Eigen::MatrixXd>& phi,
                                        const Eigen::Ref<const Eigen::MatrixXd>& psi,
                                        const SparseMatrix& mass);
/// The same with M = I (the classical, unweighted MAC).
Eigen::MatrixXd modalAssuranceCriterion(const Eigen::Ref<const Eigen::MatrixXd>& phi,
                                        const Eigen::Ref<const Eigen::MatrixXd>& psi);

}  // namespace mastrom::modes
