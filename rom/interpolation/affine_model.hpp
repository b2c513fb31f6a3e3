// Interpolation-free parametric ROM for wall thickness h, Young's modulus E and density ρ at a
// FIXED mid-surface radius (docs/theory.md §4.4 "exact where possible").
//
// At the stress-free reference (no gravity, λ* = 0) the tangent stiffness is the shell's material
// stiffness, and the shell energy U = ∫ h/2 ε_mᵀDε_m + h³/24 κᵀDκ dA with D ∝ E (docs/theory.md
// §2.2) gives
//     K(h, E) = E (h K_m + h³ K_b),       M(h, ρ) = M_rigid + ρh M_shell,       C = μ K,
// exactly; the constraint Jacobian G and the reference state q̄ depend on neither h, E nor ρ (the
// mid-surface does not move). So:
//  * K_m, K_b come from two linearisations at thicknesses h₁ ≠ h₂ (same E): per entry the 2×2
//    system [h₁ h₁³; h₂ h₂³][E K_m; E K_b] = [K(h₁); K(h₂)]; M_rigid, M_shell likewise from the
//    same two linearisations (ρh₁ ≠ ρh₂) — M is affine in the single product ρh;
//  * a global basis V (n × r) from the modes of a few snapshots over the (h, ρ) box — E only scales
//    K, it does not change a mode shape — compressed by POD (SVD in the mass inner product of the
//    box centre, M_ref = LLᵀ: V = L⁻ᵀU_r, VᵀM_ref V = I). GV = 0 because every snapshot satisfies
//    it and V is a combination of snapshots (the round-off of the weakest POD directions is
//    projected out and V re-orthonormalised, so it holds to ~1e-15);
//  * the reduced matrices VᵀK_mV, VᵀK_bV, VᵀM_rigidV, VᵀM_shellV (r × r) and every output operator
//    of the modal model (rom/model/modal_extraction.hpp) on the columns of V: those built from M
//    (Γ, Γ_c, L, ΦᵀMΩΦ, J, m, first moment) are affine in ρh too and are split the same way; the end
//    rotation/translation per unit coordinate (3 × r) and p̄ are geometric and fixed. They are
//    obtained by running extractModalModel itself on V at the two linearisations, so the formulas
//    are the same code as for a direct modal solve.
// Online, evaluate(h, E, ρ): K_r = E(h K_m,r + h³ K_b,r), M_r = M_rigid,r + ρh M_shell,r, the dense
// generalized eigenproblem K_r y = ω² M_r y (r × r; YᵀM_rY = I), and with Φ = VY:
//     Γ = Yᵀ(Γ_V,rigid + ρh Γ_V,shell), …, ψ = ψ_V Y, …, ζ_k = μ ω_k / 2 (Kelvin–Voigt, C = μK).
// The frequencies are those of the Galerkin projection of the full model onto span V — exact to
// round-off for that subspace at any (h, E, ρ); the truncation to span V is the only approximation.
//
// Validity: no gravity (a preload adds the geometric stiffness (Φ_qᵀλ*)_q, which depends on h, E
// and ρ non-affinely — build() refuses), fixed radius (when the user's parameter is the inner
// diameter, R = (D_in + h)/2 moves with h: vary E and ρ only, or use an interpolated database),
// fixed ν, μ, mesh and module data.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "common/kinds.hpp"
#include "fullorder/mast_model.hpp"
#include "rom/database/affine_reduced.hpp"
#include "rom/model/modal_model.hpp"

namespace mastrom::rom {

using SparseMatrixD = Eigen::SparseMatrix<double>;

/// K(h, E) = E (h·membrane + h³·bending).
struct AffineStiffness {
  SparseMatrixD membrane;  ///< K_m [N/m per Pa per m]
  SparseMatrixD bending;   ///< K_b [N/m per Pa per m³]
  SparseMatrixD at(double thickness_m, double youngs_modulus_pa) const;
};

/// M(ρh) = rigid + ρh·shell.
struct AffineMass {
  SparseMatrixD rigid;  ///< the modules' mass matrix (zero on shell DOFs)
  SparseMatrixD shell;  ///< ∫SᵀS dA per unit areal density [m²]
  SparseMatrixD at(double areal_density_kg_m2) const;
};

/// Split stiffness matrices assembled at thicknesses h1 ≠ h2 with the same modulus E into the
/// membrane and bending terms (per entry the 2×2 system of the header). Throws InputError when the
/// sizes differ, h1 = h2, or a value is not finite and > 0.
AffineStiffness separateStiffness(const SparseMatrixD& k1, double h1, const SparseMatrixD& k2,
                                  double h2, double youngs_modulus_pa);

/// Split mass matrices at areal densities ρh₁ ≠ ρh₂ into the rigid and the shell terms.
AffineMass separateMass(const SparseMatrixD& m1, double rho_h1, const SparseMatrixD& m2,
                        double rho_h2);

/// The parameter box the model is built for (bounds inclusive; min = max fixes a parameter).
struct AffineParameterBox {
  double thickness_min_m = 0.5e-3, thickness_max_m = 2.0e-3;
  double youngs_modulus_min_pa = 70e9, youngs_modulus_max_pa = 70e9;
  double density_min_kg_m3 = 2700.0, density_max_kg_m3 = 2700.0;
  /// Throws InputError naming the bound when one is not finite and > 0 or min > max.
  void validate() const;
};

struct AffineModelOptions {
  AffineParameterBox box;
  double lock_angle_rad = 0.0;  ///< θ₀ of the linearisation (only rotates the modes rigidly)
  int snapshot_points = 3;      ///< snapshot grid points per varying axis (h, ρ), ≥ 1
  int snapshot_modes = 12;      ///< modes per snapshot, ≥ 1
  /// POD cut-off: singular values σ_i < tolerance · σ_1 (mass inner product) are dropped.
  double basis_tolerance = 1e-8;
  int modes = 10;  ///< modes of the evaluated ModalModel, 1 ≤ modes ≤ basis size
  /// Backend of the snapshot solves (each on MPI_COMM_SELF; SLEPc needs an initialised
  /// SlepcSession, modes/slepc_session.hpp).
  EigenBackendKind backend = EigenBackendKind::Dense;
  /// Also store the interfaces' stress rows of the basis (AffineReducedModel::stress_rows), so that
  /// stressModes gives the modal stresses exactly.
  bool stresses = false;
  /// Throws InputError naming the option, its value and the allowed range.
  void validate() const;
};

/// The reduced eigensolution at one point: ω² ascending and the coefficients Y (r × modes) of the
/// modes in the basis, Φ = V Y, YᵀM_rY = I.
struct AffineSolution {
  Eigen::VectorXd omega_squared;
  Eigen::MatrixXd coefficients;
};

class AffineModalModel {
public:
  /// Linearise `base` (its h, E, ρ replaced as described in the header; any lock replaced by
  /// options.lock_angle_rad), separate the affine terms, build the basis and the reduced operators.
  /// Throws InputError for bad options, gravity ≠ 0, or a base that is not stress-free at the
  /// reference; NumericalError when a snapshot's modal solve fails.
  static AffineModalModel build(const fullorder::MastParameters& base,
                                const AffineModelOptions& options);

  /// The online part (what a ROM database stores), and a model made of it alone: evaluate, solve,
  /// reducedStiffness/Mass, box and modeCount work as for the built model; the full-order terms
  /// (basis, stiffness, mass, constraintJacobian, singularValues) are empty. fromReduced throws
  /// InputError when the reduced model is invalid.
  AffineReducedModel reduced() const;
  static AffineModalModel fromReduced(const AffineReducedModel& reduced);

  /// The modal model at (h, E, ρ). Throws InputError when a value is not finite or lies outside
  /// the box (relative tolerance 1e-9 of the bound), naming it and the box.
  ModalModel evaluate(double thickness_m, double youngs_modulus_pa, double density_kg_m3) const;
  /// The same, handing out the reduced eigensolution behind it (for stressModes).
  ModalModel evaluate(double thickness_m, double youngs_modulus_pa, double density_kg_m3,
                      AffineSolution& solution) const;
  /// True when the model carries the stress rows of its basis (built with options.stresses).
  bool hasStresses() const { return online_.stress_rows.size() > 0; }
  /// The linearised stress per unit modal coordinate, S (6P × modes, rom/model/modal_stress.hpp),
  /// of the modes Φ = V·coefficients at (h, E): membrane rows × E, bending rows × E·h, times the
  /// coefficients — exact, like the frequencies (docs/theory.md §6.5). Throws InputError when
  /// !hasStresses().
  Eigen::MatrixXd stressModes(double thickness_m, double youngs_modulus_pa,
                              const Eigen::MatrixXd& coefficients) const;
  /// The reduced eigensolution behind evaluate (same checks).
  AffineSolution solve(double thickness_m, double youngs_modulus_pa, double density_kg_m3) const;

  /// V^T K(h, E) V and V^T M(h, ρ) V (r × r).
  Eigen::MatrixXd reducedStiffness(double thickness_m, double youngs_modulus_pa) const;
  Eigen::MatrixXd reducedMass(double thickness_m, double density_kg_m3) const;

  int basisSize() const { return static_cast<int>(basis_.cols()); }
  int modeCount() const { return online_.modes; }
  const Eigen::MatrixXd& basis() const { return basis_; }  ///< V (n × r), VᵀM_refV = I
  const Eigen::VectorXd& singularValues() const { return singular_values_; }  ///< POD, all kept+dropped
  const AffineStiffness& stiffness() const { return stiffness_; }  ///< full-order terms
  const AffineMass& mass() const { return mass_; }                 ///< full-order terms
  const SparseMatrixD& constraintJacobian() const { return constraint_jacobian_; }
  AffineParameterBox box() const;

private:
  AffineModalModel() = default;
  void requireInBox(double h, double e, double rho) const;

  /// What an evaluation needs: the box, the reduced terms and the output operators (the part a
  /// database stores).
  AffineReducedModel online_;
  // The full-order terms of a built model (empty for one made fromReduced).
  AffineStiffness stiffness_;
  AffineMass mass_;
  SparseMatrixD constraint_jacobian_;
  Eigen::VectorXd q_reference_;
  Eigen::MatrixXd basis_;
  Eigen::VectorXd singular_values_;
};

}  // namespace mastrom::rom
