// Modal analysis of a linearised multibody system (docs/theory.md §3) and the per-mode quantities
// the modal ROM of §4.1 needs.
//
// With mass-normalised constrained modes Φ (ΦᵀMΦ = I, GΦ = 0) of the linearisation at q₀ = q*
// (global frame, joint locked at θ0), and the rigid rotation field about the joint axis
// Ω q₀ = Z × (every 3-block of q₀) — positions, slopes and NCF direction vectors alike:
//   frequency          f_k = ω_k / 2π                                               [Hz]
//   damping ratio      ζ_k = φ_kᵀ C φ_k / (2 ω_k), C the assembled Kelvin–Voigt damping
//                      matrix (= μ ω_k / 2 exactly for a stress-free state)          [1]
//   participation      Γ_k = φ_kᵀ M Ω q₀          (the forcing of mode k by θ̈)       [√kg·m]
//   effective mass     Γ_k² / J,  J = (Ω q₀)ᵀ M (Ω q₀) the rigid moment of inertia about Z
//   centrifugal part.  Γc_k = φ_kᵀ M Ω² q₀        (the forcing by θ̇²)               [√kg·m]
//   translation part.  T_kj = φ_kᵀ M u_j, u_j the uniform unit field along global axis j
//                      (modal gravity forcing Φᵀ M q_g = T g, and the joint force)     [√kg]
//   Coriolis matrix    ΦᵀMΩΦ (k × k, skew)                                            [1]
//   end rotation       ψ_k = ½ Σ_c c × δc over the end module's NCF frame columns c = x̂, u, v
//                      with δ = φ_k (rotation per unit modal coordinate, global)    [rad/(√kg·m)]
//   end displacement   δr_i of the end module's centroid per unit modal coordinate  [1/√kg]
//   label              modes/mode_labels.hpp
//
// Degenerate clusters (the exact bending pairs and shell pairs of a symmetric mast or cylinder,
// relative gap of ω² below cluster_tolerance) have no unique eigenvectors; each backend returns an
// arbitrary orthonormal basis of the cluster. They are rotated into a canonical basis here, so that
// results do not depend on backend, rank count or round-off: within a cluster, successively the
// direction that takes all of a probe load's modal force, then the orthogonal rest, with the probes
// (in order) M Ωq₀ (rotation about Z), the uniform fields along Z, the in-plane lateral and the
// axial direction of the mast at θ0, the rotations about the lateral and the axial direction
// through the origin, then fixed pseudo-random fields. So a y/z bending pair splits into one mode
// that the drive excites (in-plane, bending-y) and one it does not (bending-z, Γ = 0).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fullorder/mast_model.hpp"
#include "fullorder/multibody_system.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"
#include "modes/mode_basis.hpp"

namespace mastrom::modes {

/// Extra pairs runModalAnalysis asks for beyond the requested count, so that a degenerate cluster
/// (a pair) cut by the count is canonicalised as a whole before the extra pairs are dropped.
constexpr int kClusterMargin = 2;

struct ModalAnalysisOptions {
  EigenSolverOptions solver;
  int end_body = -1;                ///< body whose rotation is reported (−1: none; zeros)
  double frame_angle_rad = 0.0;     ///< θ0: orients the probes and the labels (see header)
  double cluster_tolerance = kClusterTolerance;  ///< relative ω² gap of a cluster (mode_basis.hpp)
};

/// The modes and every per-mode quantity of the header comment (k = eigen.converged rows/entries).
struct ModalAnalysis {
  EigenResult eigen;  ///< status, ω² ascending, f [Hz], Φ (canonical in degenerate clusters)
  Eigen::VectorXd damping_ratio;              ///< ζ [1]
  Eigen::VectorXd participation;              ///< Γ [√kg·m]
  Eigen::VectorXd effective_mass_fraction;    ///< Γ² / J [1]
  Eigen::VectorXd centrifugal_participation;  ///< Γc [√kg·m]
  Eigen::MatrixXd translation_participation;  ///< k × 3 [√kg]
  Eigen::MatrixXd coriolis;                   ///< k × k, ΦᵀMΩΦ [1]
  Eigen::MatrixXd end_rotation;               ///< k × 3 [rad/(√kg·m)]
  Eigen::MatrixXd end_displacement;           ///< k × 3 [1/√kg]
  double rotational_inertia_kg_m2 = 0.0;      ///< J
  std::vector<std::string> labels;
  Eigen::VectorXd residuals;  ///< projected residuals (eigen_solver.hpp) of the returned pairs
};

/// Per-mode quantities of an already solved eigenproblem of `linearization`: the modes of `eigen`
/// are canonicalised in degenerate clusters first, then only the options.solver.count pairs nearest
/// the target are kept (a solve for more pairs that delivered that many counts as converged).
/// `system` is the one that was linearised.
ModalAnalysis computeModalQuantities(const fullorder::MultibodySystem& system,
                                     const Linearization& linearization, EigenResult eigen,
                                     const ModalAnalysisOptions& options);

/// Solve the constrained eigenproblem of `linearization` with options.solver (for kClusterMargin
/// more pairs than requested, when the model has them), then computeModalQuantities. A failed or
/// partial solve is reported in result.eigen.status with the pairs that did converge (none when
/// Failed); only misuse throws (InputError).
ModalAnalysis runModalAnalysis(const fullorder::MultibodySystem& system,
                               const Linearization& linearization,
                               const ModalAnalysisOptions& options);

/// The same for a locked mast: end_body = the end module, frame angle = the lock angle.
ModalAnalysis analyzeMast(const fullorder::MastModel& model, const Linearization& linearization,
                          const EigenSolverOptions& solver);

/// Rotate the modes of every degenerate cluster of `result` into the canonical basis defined by
/// `probes` (n × p displacement fields; the modal force of probe j on mode k is φ_kᵀ M probe_j),
/// then fixed pseudo-random fields; re-applies the sign rule of EigenResult. Exposed for tests.
void canonicalizeDegenerateModes(EigenResult& result, const SparseMatrix& mass,
                                 const Eigen::Ref<const Eigen::MatrixXd>& probes,
                                 double cluster_tolerance);

}  // namespace mastrom::modes
