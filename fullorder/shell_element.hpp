// Gradient-deficient ANCF thin-shell element: mass, elastic and Kelvin–Voigt damping forces and their
// exact tangents (docs/theory.md §2.2; [LW24] eqs. 8–38; Dmitrochenko & Pogorelov 2003).
//
// Kinematics at a point: g_x = r_,x, g_y = r_,y, r_,ab second derivatives, unit normal
// n = g_x × g_y / |g_x × g_y|. Strains are measured against the *interpolated* reference field e₀, so
// the reference state is exactly stress-free:
//   membrane (Green–Lagrange, parameter coordinates, Voigt)  E = [½(g_x·g_x − G_x·G_x),
//                                                                ½(g_y·g_y − G_y·G_y),
//                                                                g_x·g_y − G_x·G_y]
//   bending (Kirchhoff–Love)                                 k = [κ_xx, κ_yy, 2κ_xy],
//                                                                κ_ab = r_,ab·n − R_,ab·N
// Both are covariant tensors, mapped to a local orthonormal frame of the reference surface by a
// constant 3×3 matrix T per quadrature point ([LW24] eq. 16). Energy ([LW24] eq. 31):
//   U = Σ_q w_q [ h/2 · Eᵀ T ᵀD T E + h³/24 · kᵀ Tᵀ D T k ],   D = plane-stress matrix.
// Damping (Kelvin–Voigt, stress = D(ε + μ ε̇)): F_d = Σ_q w_q [h Bᵀ D μ Ė + h³/12 B_κᵀ D μ k̇].
// The material law is fullorder/shell_material.hpp and the point algebra of every force here (and of
// the batched kernel, shell_force_batch.hpp) is fullorder/shell_point_force.hpp.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "fullorder/shell_material.hpp"
#include "fullorder/shell_point_force.hpp"
#include "fullorder/shell_shape.hpp"

namespace mastrom::fullorder {

using Vec36 = Eigen::Matrix<double, 36, 1>;
using Mat36 = Eigen::Matrix<double, 36, 36>;

/// One element with its reference geometry and precomputed quadrature data.
class ShellElement {
public:
  static constexpr int kDofs = 36;

  /// @param a_m, b_m    side lengths of the parameter rectangle [m] (x along a, y along b)
  /// @param e0          reference nodal coordinates (stress-free state)
  /// @param gauss_order Gauss points per direction (5 default; see docs/theory.md §2.2)
  ShellElement(double a_m, double b_m, const Vec36& e0, const ShellSection& section,
               int gauss_order = 5);
  /// Same with a shape table shared by congruent elements (sides and rule from the table).
  ShellElement(std::shared_ptr<const ShellShapeTable> table, const Vec36& e0,
               const ShellSection& section);

  /// Consistent mass matrix M = ρh ∫ SᵀS dA (constant).
  void mass(Mat36& m) const;

  /// Strain energy U(e) [J].
  double strainEnergy(const Vec36& e) const;

  /// Elastic force F = ∂U/∂e.
  void elasticForce(const Vec36& e, Vec36& f) const;

  /// Elastic force and its exact tangent K = ∂F/∂e (symmetric).
  void elasticForceAndTangent(const Vec36& e, Vec36& f, Mat36& k) const;

  /// Kelvin–Voigt damping force F_d(e, ė) (zero when damping_s = 0 or under rigid motion).
  void dampingForce(const Vec36& e, const Vec36& edot, Vec36& f) const;

  /// Damping force and its tangents C = ∂F_d/∂ė (symmetric) and K_d = ∂F_d/∂e (not symmetric).
  void dampingForceAndTangents(const Vec36& e, const Vec36& edot, Vec36& f, Mat36& c,
                               Mat36& k_d) const;

  /// The element's block of an iteration matrix, stiffness · (K + K_d) + damping · C, in one pass
  /// over the points: what elasticForceAndTangent and dampingForceAndTangents give combined, to
  /// round-off, at about half their cost (the Kelvin–Voigt law is μ times the elastic one, so C
  /// shares K's material product, and the geometric terms are linear in the resultants).
  void iterationTangent(const Vec36& e, const Vec36& edot, double stiffness, double damping,
                        Mat36& block) const;

  const Vec36& referenceCoordinates() const { return e0_; }
  const ShellSection& section() const { return section_; }
  double sideA() const { return table_->a_m; }
  double sideB() const { return table_->b_m; }
  const std::shared_ptr<const ShellShapeTable>& shapeTable() const { return table_; }
  /// Reference mid-surface area ∫ dA [m²] (by the same quadrature).
  double referenceArea() const;

  /// Reference-state data of one quadrature point (the shape values live in the shape table).
  struct QuadPoint {
    ShellPointReference reference;  ///< D = w·dA·TᵀD̂T (D̂ of unit modulus), metric0, curv0
    double mass_weight = 0.0;       ///< w·dA (no ρh)
  };
  /// Point p of the shape table's rule (for ShellForceBatch, which evaluates many elements at once).
  const QuadPoint& quadPoint(std::size_t p) const { return qp_[p]; }

private:
  const ShellShapeValues& shape(std::size_t point) const { return table_->values[point]; }
  /// f = Σ_p Bᵀ[σ; m] by shellPointForce with the part kPart of the law (ė read unless kElastic);
  /// at_point(p, fields, state) is called at every point after the point's force is added.
  template <ShellStressPart kPart, class AtPoint>
  void pointForces(const Vec36& e, const Vec36* edot, const ShellSectionScales& c, Vec36& f,
                   AtPoint&& at_point) const;

  std::shared_ptr<const ShellShapeTable> table_;
  Vec36 e0_;
  ShellSection section_;
  std::vector<QuadPoint> qp_;
};

}  // namespace mastrom::fullorder
