// One database sample's offline work (see sample_solve.hpp).
#include "rom/offline/sample_solve.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <Eigen/SVD>

#include "common/error.hpp"
#include "fullorder/block_rotation.hpp"
#include "modes/mode_basis.hpp"
#include "rom/offline/locked_modal_solve.hpp"
#include "rom/model/modal_extraction.hpp"
#include "rom/database/parameter_space.hpp"

namespace mastrom::rom {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The reference sample's basis of a degenerate eigenspace is arbitrary; make it canonical: a
/// Householder reflection within the cluster puts the whole rotation participation Γ = ΦᵀMΩq̄ (or,
/// when Γ vanishes, Γ_c) into the cluster's first mode. For a pair (the bending pair) this fixes
/// the basis: the in-plane mode the drive excites and the out-of-plane one it does not.
void canonicalizeClusters(Eigen::MatrixXd& phi, const std::vector<std::pair<int, int>>& clusters,
                          const Eigen::SparseMatrix<double>& mass, const Eigen::VectorXd& q) {
  const Eigen::VectorXd omega_q = fullorder::rotationRateField(q);
  const Eigen::VectorXd m_omega_q = mass * omega_q;
  const Eigen::VectorXd m_omega2_q = mass * fullorder::rotationRateField(omega_q);
  for (const auto& [b, e] : clusters) {
    const int c = e - b;
    Eigen::VectorXd g = phi.middleCols(b, c).transpose() * m_omega_q;
    const double scale = std::sqrt(m_omega_q.dot(omega_q));  // √J: |Γ| ≤ √J
    if (g.norm() <= 1e-9 * scale) g = phi.middleCols(b, c).transpose() * m_omega2_q;
    const double norm = g.norm();
    if (norm <= 1e-9 * scale) continue;
    // H = I − 2vvᵀ/vᵀv with v = g − |g|e₁ maps g to |g|e₁ (v = g + |g|e₁ if that is closer).
    Eigen::VectorXd v = g;
    v[0] += g[0] >= 0 ? norm : -norm;
    const Eigen::MatrixXd h =
        Eigen::MatrixXd::Identity(c, c) - 2.0 * v * v.transpose() / v.squaredNorm();
    const Eigen::MatrixXd rotated = phi.middleCols(b, c) * h;
    phi.middleCols(b, c) = rotated;
  }
}

/// A sample's basis of a degenerate eigenspace, rotated to match the reference's modes: the c
/// reference modes the cluster projects onto most, then orthogonal Procrustes within the cluster
/// (mass inner product of the reference), so that MAC tracking sees the same shapes.
void alignClusters(Eigen::MatrixXd& phi, const std::vector<std::pair<int, int>>& clusters,
                   const Eigen::MatrixXd& phi_ref, const Eigen::SparseMatrix<double>& mass_ref) {
  if (clusters.empty()) return;
  const Eigen::MatrixXd m_ref = mass_ref * phi_ref;
  for (const auto& [b, e] : clusters) {
    const int c = e - b;
    const Eigen::MatrixXd x = phi.middleCols(b, c).transpose() * m_ref;  // c × k_ref
    const Eigen::VectorXd weight = x.colwise().squaredNorm().transpose();
    std::vector<int> order(static_cast<std::size_t>(weight.size()));
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(),
                     [&weight](int a, int z) { return weight[a] > weight[z]; });
    order.resize(static_cast<std::size_t>(std::min<Eigen::Index>(c, weight.size())));
    std::sort(order.begin(), order.end());
    if (static_cast<int>(order.size()) < c) continue;
    Eigen::MatrixXd y(c, c);
    for (int j = 0; j < c; ++j) y.col(j) = x.col(order[j]);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(y, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::MatrixXd r = svd.matrixU() * svd.matrixV().transpose();
    const Eigen::MatrixXd rotated = phi.middleCols(b, c) * r;
    phi.middleCols(b, c) = rotated;
  }
}

/// Solve one sample. `reference` = nullptr for the reference sample itself (its degenerate
/// eigenspaces are canonicalised); otherwise they are aligned to the reference's modes.

}  // namespace

std::string describePoint(const std::vector<ParameterAxis>& axes, const std::vector<double>& p) {
  std::string text;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    text += (a ? ", " : "") + formatOverride(axes[a].key, p[a]);
  }
  return text;
}

/// The modes rigidly rotated by `angle_rad` about Z: every 3-block of a field (positions, slopes,
/// NCF vectors) rotates alike (rom/model/modal_model.hpp). Samples locked at different angles θ₀ (a θ₀
/// axis with gravity on) are compared in the reference's frame: rotated by θ_ref − θ_s, a mode
/// differs from the reference's only by its elastic change, so MAC tracking and the Procrustes
/// alignment see the shapes, not the rigid rotation of the whole mast (which mixes every bending
/// mode with its neighbours in the global frame). M commutes with the rotation (MR = RM).
Eigen::MatrixXd rotateModes(const Eigen::MatrixXd& phi, double angle_rad) {
  if (angle_rad == 0.0) return phi;
  return fullorder::rotateEveryBlock(phi, fullorder::rotationAboutZ(angle_rad));
}

SampleSolution solveSample(const Config& base, const std::vector<ParameterAxis>& axes,
                           const std::vector<double>& point, int modes, EigenBackendKind backend,
                           int index, const SampleSolution* reference, bool stresses) {
  const std::string where =
      detail::concat("rom build: sample ", index, " (", describePoint(axes, point), ")");
  Config config;
  try {
    config = applyOverrides(base, parameterOverrides(axes, point));
  } catch (const InputError& e) {
    throw InputError(where + ": " + e.what());
  }
  const LockedModalSolve solve = solveLockedMast(config, modes, kExtraModes, backend, where);
  const modes::Linearization& lin = solve.lin;
  const modes::EigenResult& res = solve.eigen;
  const int count = static_cast<int>(res.eigenvalues_rad2_s2.size());
  SampleSolution out;
  out.assembly_s = solve.assembly_s;
  out.eigensolve_s = solve.eigensolve_s;

  const auto start = Clock::now();
  LinearizedModes lm;
  lm.q_reference = lin.q;
  lm.reference_angle_rad = config.modes.angleRad();
  lm.mass = lin.problem.mass;
  lm.damping = lin.damping;
  if (stresses) lm.problem = &lin.problem;
  Eigen::MatrixXd phi = res.modes.leftCols(count);
  const std::vector<std::pair<int, int>> clusters =
      modes::degenerateClusters(res.eigenvalues_rad2_s2.head(count));
  if (reference == nullptr) {
    canonicalizeClusters(phi, clusters, lin.problem.mass, lin.q);
  } else {
    // In the reference's frame (rotateModes), then back: the cluster rotation acts on the right,
    // the frame rotation on the left, so they commute.
    const double to_reference = reference->modal.reference_angle_rad - config.modes.angleRad();
    phi = rotateModes(phi, to_reference);
    alignClusters(phi, clusters, reference->modes, reference->mass);
    phi = rotateModes(phi, -to_reference);
  }
  lm.omega_squared = res.eigenvalues_rad2_s2.head(modes);
  lm.modes = phi.leftCols(modes);
  out.modal = extractModalModel(solve.model, lm);
  out.modes = std::move(phi);
  out.mass = std::move(lm.mass);
  out.extraction_s = secondsSince(start);
  return out;
}

}  // namespace mastrom::rom
