// Interpolation method (b) of docs/theory.md §4.4: aligned reduced matrices interpolated on the
// manifold of SPD matrices, then a small symmetric eigenproblem (Amsallem & Farhat 2008, 2011; the
// habits of libROM's manifold_interp: Procrustes-aligned bases, congruence-transformed reduced
// matrices, SPD interpolation through the log map at a reference point).
//
// Offline, per sample s with its k_s modes and the database's alignment Q_s (k_s × k, orthonormal
// columns; Φ_s Q_s ≈ Φ_ref in the mass inner product, rom/offline/mode_tracking.hpp), every modal quantity
// is rewritten in the aligned coordinates η = Q_s η̃ — the coordinates of the basis Φ̃_s = Φ_s Q_s,
// which is (nearly) the same basis at every sample:
//     K̃_s = Q_sᵀ diag(ω_s²) Q_s     (SPD when every ω > 0)     C̃_s = Q_sᵀ diag(2ζ_s ω_s) Q_s
//     Γ̃ = Q_sᵀ Γ,  Γ̃_c = Q_sᵀ Γ_c,  ψ̃ = ψ Q_s,  T̃ = T Q_s,  L̃ = L Q_s,  (ΦᵀMΩΦ)~ = Q_sᵀ (ΦᵀMΩΦ) Q_s
// (mass-normalised modes: M̃ = Q_sᵀ I Q_s = I). With k_s = k (what rom/offline/database_build.hpp stores)
// this is an exact change of coordinates: sample s's modal model is represented without loss.
//
// Online at p, with the multilinear (tensor-product hat) weights w_s(p) of the grid cell around p
// (in log p by default, see ManifoldInterpolationOptions):
//     K̃(p) = exp( Σ_s w_s log K̃_s )                              (log-Euclidean, the default)
//     C̃(p), Γ̃(p), …, J, m, c̄, p̄, θ₀ = Σ_s w_s (·)_s           (linear)
//     K̃(p) = Y diag(ω²) Yᵀ  →  ω,  Γ = YᵀΓ̃,  Γ_c = YᵀΓ̃_c,  ψ = ψ̃Y,  T = T̃Y,  L = L̃Y,
//                               ΦᵀMΩΦ = Yᵀ(·)~Y,  ζ_k = (YᵀC̃Y)_kk / (2ω_k).
// Nothing is tracked: the eigensolve sorts the frequencies, so modes that cross between samples
// (thin-wall shell modes passing a bending pair) and degenerate pairs (whose basis the eigensolver
// picks arbitrarily at each sample) come out right as long as the aligned subspaces agree.
//
// Why log-Euclidean rather than the affine-invariant map at the reference sample,
// K̃(p) = Exp_P(Σ w_s Log_P K̃_s), P = K̃_ref (Amsallem & Farhat; still available, SpdMetric):
// the Procrustes alignment mixes a sample's low modes slightly with its high ones (the modes
// change shape over the box): K̃_s = Q_sᵀ Λ_s Q_s with Q_s = I + O(ε) off the diagonal. The
// interpolation error of an eigenvalue then carries that mixing with the weight the metric gives
// it: in the whitened coordinates of the affine-invariant map an entry between modes i and j is
// ε (λ_j − λ_i)/√(λ_iλ_j) ~ ε √(λ_j/λ_i) — the frequency ratio, ≈ 20 between the first bending
// pair and the 10th mode of Scheme 3 — while in log K̃_s it is ε (log λ_j − log λ_i), a log of
// the ratio. Measured on Scheme 3, h ∈ [0.5, 2] mm × D_in ∈ [80, 100] mm in 5 × 5 samples, six
// cell midpoints against direct modal solves (ROM-vs-ROM NRMSE of the relative end angular
// acceleration, 1 s horizon): affine-invariant up to 3.9 % with the excited member of the bending
// pair 0.05 % too stiff (its out-of-plane partner, which the drive does not excite and whose
// block mixes less, within 0.005 %); log-Euclidean up to 2.6 %, the pair split ≤ 0.002 %. The
// aligned coordinates are orthonormal at every sample (mass-normalised modes, M̃ = I), so the
// only changes of coordinates are orthogonal, under which log-Euclidean is invariant too; for
// commuting (diagonal) data both metrics reduce to geometric interpolation of every ω² — exact
// for a power law ω² ∝ p^a along the logarithmic weights. Damping is interpolated linearly: C̃ is
// only semi-definite in general (ζ = 0 allowed), and the non-negative weights of a point inside
// the box keep it so.
//
// θ₀ as a parameter (gravity on): as in rom/interpolation/tracked_interpolation.hpp, ψ̃, T̃, L̃, c̄, p̄ are rotated
// back to the stowed frame before interpolation and forward to the interpolated θ₀ after.
// Outside the box the boundary cell's weights extrapolate linearly (K̃ stays SPD; ζ is clipped at
// 0, J and m kept > 0); whether that is allowed is the caller's decision (rom/database/parameter_space.hpp).
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "rom/interpolation/interpolator.hpp"
#include "rom/interpolation/grid_weights.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/interpolation/spd_math.hpp"

namespace mastrom::rom {

/// Where the logarithms of the aligned stiffness matrices are taken (both are metrics of the SPD
/// manifold; see the header for the choice).
enum class SpdMetric {
  LogEuclidean,     ///< K̃(p) = exp(Σ w_s log K̃_s)
  AffineInvariant   ///< K̃(p) = Exp_P(Σ w_s Log_P K̃_s), P = K̃_ref
};

struct ManifoldInterpolationOptions {
  /// Logarithmic by default: the tangent space holds log ω² (relative to the reference), and with
  /// weights in log p every power law ω² ∝ p^a — E (a = 1), the bending pair in h (a ≈ 1) and in R
  /// (a ≈ 3), shell modes in ρ (a = −1) — is interpolated exactly instead of with an O(Δp²) error
  /// that turns into phase drift of the response. Measured in tests/rom/test_spd_interpolation.cpp
  /// (h ∈ [0.5, 2] mm in 7 points × R ∈ [38, 44] mm in 3, cell midpoints): NRMSE of the relative
  /// end angular acceleration ≤ 1.6 % with logarithmic weights, up to 26 % with linear ones.
  AxisWeighting weighting = AxisWeighting::Logarithmic;
  /// Log-Euclidean by default (measured, see the header: the affine-invariant map amplifies the
  /// alignment's mixing of a low mode with the high ones by their frequency ratio).
  SpdMetric metric = SpdMetric::LogEuclidean;
};

class ManifoldInterpolator final : public ModalInterpolator {
public:
  /// Throws InputError when the database is inconsistent (grid size, mode counts, alignment sizes
  /// or orthonormality, gravity that differs between samples), NumericalError when a sample's
  /// aligned stiffness is not SPD (a zero or negative ω²), naming the sample.
  explicit ManifoldInterpolator(const RomDatabase& db,
                                const ManifoldInterpolationOptions& options = {});

  /// See the header. Throws InputError when the number of values is wrong or one is not finite.
  ModalModel evaluate(const std::vector<double>& parameters) const override;
  ModalModel evaluateWithStresses(const std::vector<double>& parameters) const override;

  /// K̃(p) in the reference's aligned coordinates (k × k, SPD): what `evaluate` diagonalises.
  Eigen::MatrixXd alignedStiffness(const std::vector<double>& parameters) const;

  int modeCount() const { return modes_; }

private:
  /// One sample in aligned coordinates (3-vectors in the stowed frame when rotate_).
  struct Aligned {
    Eigen::MatrixXd log_stiffness;  ///< log K̃_s, or log(P^-½ K̃_s P^-½) (affine-invariant)
    Eigen::MatrixXd damping;        ///< C̃_s
    Eigen::VectorXd gamma, gamma_c;
    Eigen::Matrix3Xd psi, translation, momentum;
    Eigen::MatrixXd coriolis;  ///< empty when the database carries none
    double inertia = 0.0, mass = 0.0, theta0 = 0.0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), end_position = Eigen::Vector3d::Zero();
    /// [S Q | S_res | σ̄] and the points, when the database carries stresses.
    Eigen::MatrixXd stress;
    Eigen::Matrix2Xd stress_points;
    double stress_damping = 0.0;
  };
  ModalModel evaluateModel(const std::vector<double>& parameters, bool stresses) const;
  Eigen::VectorXi stress_offsets_;

  std::vector<ParameterAxis> axes_;
  ManifoldInterpolationOptions options_;
  std::vector<Aligned> samples_;
  std::unique_ptr<SpdBasePoint> base_;  ///< P = K̃_ref (affine-invariant metric only)
  /// exp of an interpolated logarithm (the inverse of the chosen metric's log map).
  Eigen::MatrixXd expLog(const Eigen::MatrixXd& x) const;
  int modes_ = 0;
  bool rotate_ = false;     ///< θ₀ differs between samples
  bool coriolis_ = true;    ///< every sample carries ΦᵀMΩΦ
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
};

/// Method (b) over `db` (copies what it needs: `db` may be destroyed after). Same contract as the
/// ManifoldInterpolator constructor.
std::unique_ptr<ModalInterpolator> makeManifoldInterpolator(
    const RomDatabase& db, const ManifoldInterpolationOptions& options = {});

}  // namespace mastrom::rom
