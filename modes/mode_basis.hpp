// The conventions that make a set of eigenvectors unique enough to compare between backends, ranks,
// runs and database samples (docs/theory.md §3.3): the sign of every vector, and which eigenvalues
// form one degenerate cluster (an invariant subspace whose basis the solver picks arbitrarily).
// The one definition of each for the modal analysis and the ROM.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

namespace mastrom::modes {

/// Relative gap of ω² below which neighbouring eigenvalues form one cluster. The bending pairs of
/// an axisymmetric mast are split only by the solver's round-off (≲ 1e-10 relative); distinct modes
/// of the mast are ≥ 1e-3 apart. 1e-6 separates the two cases with margin on both sides, and
/// mixing two genuinely distinct modes that close would only perturb their Rayleigh quotients by
/// about the gap.
constexpr double kClusterTolerance = 1e-6;

/// Flip each column so that its first entry whose magnitude is within 1e-6 relative of the
/// column's largest is positive (the tolerance keeps round-off from choosing different entries in
/// different backends).
void normaliseColumnSigns(Eigen::Ref<Eigen::MatrixXd> columns);

/// [begin, end) index ranges of ≥ 2 neighbouring eigenvalues of `omega_squared` (ascending) whose
/// relative gaps are ≤ tolerance: |ω²_j − ω²_{j−1}| ≤ tolerance · max(|ω²_j|, 1e-12 max|ω²|)
/// (the floor keeps rigid-body zeros from being compared relatively to round-off).
std::vector<std::pair<int, int>> degenerateClusters(const Eigen::VectorXd& omega_squared,
                                                    double tolerance = kClusterTolerance);

/// The smallest count ≥ `wanted` that does not cut a cluster of `omega_squared` in two (at most
/// omega_squared.size(); the last cluster may still be cut there).
int countWithWholeClusters(const Eigen::VectorXd& omega_squared, int wanted,
                           double tolerance = kClusterTolerance);

}  // namespace mastrom::modes
