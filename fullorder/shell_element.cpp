// Quadrature and assembly of the ANCF thin-shell element (docs/theory.md §2.2). Every force here is
// the shared point algebra (shellPointForce, shell_point_force.hpp, with the law of
// shell_material.hpp); the tangents add its derivatives from shell_kinematics.cpp.
#include "fullorder/shell_element.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "common/error.hpp"
#include "fullorder/gauss_quadrature.hpp"
#include "fullorder/shell_kinematics.hpp"

namespace mastrom::fullorder {
namespace {

using Map3x12 = Eigen::Map<const Mat3x12>;
using MutMap3x12 = Eigen::Map<Mat3x12>;
using Mat3x5 = Eigen::Matrix<double, 3, 5>;

/// The point's fields F = Ê·Dₛ (shell_point_force.hpp).
void pointFields(const Mat3x12& e_hat, const Eigen::Matrix<double, 12, 5>& derivatives,
                 ShellPointFields& f) {
  Eigen::Map<Mat3x5>(&f[0][0]).noalias() = e_hat.lazyProduct(derivatives);  // no GEMM set-up
}

void requireSurface(const ShellSurfaceInvariants& s) {
  MASTROM_REQUIRE(s.area_sq > 0.0 && s.area_sq < std::numeric_limits<double>::infinity(),
                  NumericalError, "shell element: degenerate surface (|g_x × g_y|² = ", s.area_sq,
                  ")");
}

/// The point's kinematics in the form the tangents' derivatives read (shell_kinematics.hpp).
ShellPointKinematics pointKinematics(const ShellPointFields& f, const ShellPointState& st) {
  ShellPointKinematics kin;
  kin.gx = Eigen::Map<const Eigen::Vector3d>(f[0]);
  kin.gy = Eigen::Map<const Eigen::Vector3d>(f[1]);
  kin.rxx = Eigen::Map<const Eigen::Vector3d>(f[2]);
  kin.ryy = Eigen::Map<const Eigen::Vector3d>(f[3]);
  kin.rxy = Eigen::Map<const Eigen::Vector3d>(f[4]);
  kin.n = Eigen::Map<const Eigen::Vector3d>(st.surface.n);
  kin.area_factor = std::sqrt(st.surface.area_sq);
  kin.membrane = Eigen::Map<const Eigen::Vector3d>(st.strain);
  kin.bending = Eigen::Map<const Eigen::Vector3d>(st.strain + 3);
  return kin;
}

/// At a point: B = ∂[E; k]/∂e, and db = ∂[σ; m]/∂e along the part kPart of the law (its
/// variation, shellResultantVariation, on each column of B).
template <ShellStressPart kPart>
void strainJacobianAndVariation(const ShellPointKinematics& kin, const ShellShapeValues& s,
                                const ShellPointReference& ref, const ShellSectionScales& c,
                                Mat6x36& b, Mat6x36& db) {
  shellStrainJacobian(kin, s, b);
  for (int j = 0; j < 36; ++j) {
    double delta[6], out[6];
    for (int i = 0; i < 6; ++i) delta[i] = b(i, j);
    shellResultantVariation<kPart>(ref.d, c, delta, out);
    for (int i = 0; i < 6; ++i) db(i, j) = out[i];
  }
}

/// The tangent terms the elastic and the damping force share at a point: B and db as above,
/// material += Bᵀ·db and geometric += Σ_c s_c ∂²ε_c/∂e² with s = [σ; m].
template <ShellStressPart kPart>
ShellPointKinematics addPointTangents(const ShellPointFields& fields, const ShellPointState& st,
                                      const ShellShapeValues& s, const ShellPointReference& ref,
                                      const ShellSectionScales& c, Mat6x36& b, Mat6x36& db,
                                      Mat36& material, Mat36& geometric) {
  const ShellPointKinematics kin = pointKinematics(fields, st);
  strainJacobianAndVariation<kPart>(kin, s, ref, c, b, db);
  material.noalias() += b.transpose() * db;
  const Eigen::Map<const Eigen::Vector3d> sigma(st.resultants), moment(st.resultants + 3);
  addShellGeometricTangent(kin, s, sigma, moment, geometric);
  return kin;
}

void requireSection(const ShellSection& s) {
  MASTROM_REQUIRE(std::isfinite(s.thickness_m) && s.thickness_m > 0, InputError,
                  "shell: thickness = ", s.thickness_m, " m must be > 0");
  MASTROM_REQUIRE(std::isfinite(s.youngs_modulus_pa) && s.youngs_modulus_pa > 0, InputError,
                  "shell: youngs_modulus = ", s.youngs_modulus_pa, " Pa must be > 0");
  MASTROM_REQUIRE(s.poisson_ratio > -1.0 && s.poisson_ratio < 0.5, InputError,
                  "shell: poisson_ratio = ", s.poisson_ratio, " must be in (-1, 0.5)");
  MASTROM_REQUIRE(std::isfinite(s.density_kg_m3) && s.density_kg_m3 > 0, InputError,
                  "shell: density = ", s.density_kg_m3, " kg/m^3 must be > 0");
  MASTROM_REQUIRE(std::isfinite(s.damping_s) && s.damping_s >= 0, InputError,
                  "shell: damping = ", s.damping_s, " s must be >= 0");
}

std::shared_ptr<const ShellShapeTable> checkedShapeTable(double a_m, double b_m, int gauss_order) {
  MASTROM_REQUIRE(a_m > 0 && b_m > 0, InputError, "shell: element sides a = ", a_m, " m, b = ", b_m,
                  " m must be > 0");
  return makeShellShapeTable(a_m, b_m, gauss_order);
}

}  // namespace

ShellElement::ShellElement(double a_m, double b_m, const Vec36& e0, const ShellSection& section,
                           int gauss_order)
    : ShellElement(checkedShapeTable(a_m, b_m, gauss_order), e0, section) {}

ShellElement::ShellElement(std::shared_ptr<const ShellShapeTable> table, const Vec36& e0,
                           const ShellSection& section)
    : table_(std::move(table)), e0_(e0), section_(section) {
  MASTROM_REQUIRE(table_ != nullptr && table_->a_m > 0 && table_->b_m > 0, InputError,
                  "shell: element needs a shape table with sides > 0");
  requireSection(section);
  const double a_m = table_->a_m, b_m = table_->b_m;
  const Eigen::Matrix3d d_hat = planeStressUnitModulus(section.poisson_ratio);
  const Map3x12 e0_hat(e0_.data());
  qp_.reserve(table_->values.size());
  for (std::size_t p = 0; p < table_->values.size(); ++p) {
    const ShellShapeValues& s = table_->values[p];
    QuadPoint q;
    const Eigen::Vector3d gx = e0_hat * s.nx, gy = e0_hat * s.ny;
    const double da = gx.cross(gy).norm();
    MASTROM_REQUIRE(da > 0, InputError, "shell: degenerate reference geometry");
    const double w = table_->weights[p] * 0.25 * a_m * b_m * da;
    const Eigen::Matrix3d t = voigtFrameTransform(gx, gy);
    const Eigen::Matrix3d d = w * t.transpose() * d_hat * t;
    const double upper[6] = {d(0, 0), d(0, 1), d(0, 2), d(1, 1), d(1, 2), d(2, 2)};
    for (int v = 0; v < 6; ++v) q.reference.d[v] = upper[v];
    q.mass_weight = w;
    // The reference invariants by the operations the forces subtract them with: e₀ is stress-free
    // to the last bit.
    ShellPointFields f0;
    pointFields(e0_hat, table_->derivatives[p], f0);
    const ShellSurfaceInvariants s0 = shellSurfaceInvariants(f0);
    for (int v = 0; v < 3; ++v) {
      q.reference.metric0[v] = s0.metric[v];
      q.reference.curv0[v] = s0.curvature[v];
    }
    qp_.push_back(q);
  }
}

double ShellElement::referenceArea() const {
  double area = 0.0;
  for (const QuadPoint& q : qp_) area += q.mass_weight;
  return area;
}

void ShellElement::mass(Mat36& m) const {
  Eigen::Matrix<double, 12, 12> m12 = Eigen::Matrix<double, 12, 12>::Zero();
  for (std::size_t p = 0; p < qp_.size(); ++p)
    m12.noalias() += qp_[p].mass_weight * shape(p).n * shape(p).n.transpose();
  m12 *= section_.density_kg_m3 * section_.thickness_m;
  m.setZero();
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) m.block<3, 3>(3 * i, 3 * j).diagonal().setConstant(m12(i, j));
}

template <ShellStressPart kPart, class AtPoint>
void ShellElement::pointForces(const Vec36& e, const Vec36* edot, const ShellSectionScales& c,
                               Vec36& f, AtPoint&& at_point) const {
  const Mat3x12 e_hat = Map3x12(e.data());
  Mat3x12 edot_hat;
  if constexpr (kPart != ShellStressPart::kElastic) edot_hat = Map3x12(edot->data());
  Mat3x12 f_hat = Mat3x12::Zero();
  for (std::size_t p = 0; p < qp_.size(); ++p) {
    const Eigen::Matrix<double, 12, 5>& derivatives = table_->derivatives[p];
    ShellPointFields fields, rates, dir;
    pointFields(e_hat, derivatives, fields);
    if constexpr (kPart != ShellStressPart::kElastic) pointFields(edot_hat, derivatives, rates);
    ShellPointState st;
    shellPointForce<kPart>(fields, rates, qp_[p].reference, c, st, dir);
    requireSurface(st.surface);
    f_hat.noalias() += Eigen::Map<const Mat3x5>(&dir[0][0]).lazyProduct(derivatives.transpose());
    at_point(p, fields, st);
  }
  MutMap3x12(f.data()) = f_hat;
}

double ShellElement::strainEnergy(const Vec36& e) const {
  const Mat3x12 e_hat = Map3x12(e.data());
  const ShellSectionScales c = shellSectionScales(section_);
  double u = 0.0;
  for (std::size_t p = 0; p < qp_.size(); ++p) {
    ShellPointFields fields;
    pointFields(e_hat, table_->derivatives[p], fields);
    ShellPointState st;
    st.surface = shellSurfaceInvariants(fields);
    requireSurface(st.surface);
    shellPointStrains<false>(fields, fields, qp_[p].reference, st);
    u += shellPointStrainEnergy(qp_[p].reference.d, c, st.strain);
  }
  return u;
}

void ShellElement::elasticForce(const Vec36& e, Vec36& f) const {
  pointForces<ShellStressPart::kElastic>(e, nullptr, shellSectionScales(section_), f,
                                         [](std::size_t, const ShellPointFields&,
                                            const ShellPointState&) {});
}

void ShellElement::elasticForceAndTangent(const Vec36& e, Vec36& f, Mat36& k) const {
  const ShellSectionScales c = shellSectionScales(section_);
  k.setZero();
  Mat6x36 b, db;
  pointForces<ShellStressPart::kElastic>(
      e, nullptr, c, f,
      [&](std::size_t p, const ShellPointFields& fields, const ShellPointState& st) {
        addPointTangents<ShellStressPart::kElastic>(fields, st, shape(p), qp_[p].reference, c, b,
                                                    db, k, k);
      });
}

void ShellElement::dampingForce(const Vec36& e, const Vec36& edot, Vec36& f) const {
  f.setZero();
  if (section_.damping_s == 0.0) return;
  pointForces<ShellStressPart::kDamping>(e, &edot, shellSectionScales(section_), f,
                                         [](std::size_t, const ShellPointFields&,
                                            const ShellPointState&) {});
}

void ShellElement::dampingForceAndTangents(const Vec36& e, const Vec36& edot, Vec36& f, Mat36& c,
                                           Mat36& k_d) const {
  f.setZero();
  c.setZero();
  k_d.setZero();
  if (section_.damping_s == 0.0) return;
  const Map3x12 edot_hat(edot.data());
  const ShellSectionScales scale = shellSectionScales(section_);
  Mat6x36 b, db, rate_jac;
  pointForces<ShellStressPart::kDamping>(
      e, &edot, scale, f,
      [&](std::size_t p, const ShellPointFields& fields, const ShellPointState& st) {
        // C = Bᵀ ∂[σ; m]/∂ė; ∂F_d/∂e = Σ_c s_c ∂²ε_c/∂e² + Bᵀ D ∂(B ė)/∂e, and
        // ∂(B ė)_c/∂e = (∂²ε_c/∂e² ė)ᵀ.
        const ShellPointKinematics kin = addPointTangents<ShellStressPart::kDamping>(
            fields, st, shape(p), qp_[p].reference, scale, b, db, c, k_d);
        shellStrainRateJacobian(kin, shape(p), edot_hat, rate_jac);
        k_d.noalias() += db.transpose() * rate_jac;
      });
}

void ShellElement::iterationTangent(const Vec36& e, const Vec36& edot, double stiffness,
                                    double damping, Mat36& block) const {
  block.setZero();
  const ShellSectionScales c = shellSectionScales(section_);
  const double mu = section_.damping_s;
  // At each point, with D B the elastic law's variation of the strain Jacobian B and s_e, s_d the
  // elastic and damping resultants:
  //   K   = Bᵀ D B + Σ s_e ∂²ε/∂e²,   C = μ Bᵀ D B,
  //   K_d = Σ s_d ∂²ε/∂e² + μ (D B)ᵀ ∂(B ė)/∂e      (dampingForceAndTangents),
  // so the block is (stiffness + damping μ) Bᵀ D B + stiffness Σ (s_e + s_d) ∂²ε/∂e²
  // + stiffness μ (D B)ᵀ ∂(B ė)/∂e: two 36 × 6 × 36 products instead of four.
  const Map3x12 edot_hat(edot.data());
  const double material = stiffness + damping * mu;
  const double rate_term = stiffness * mu;
  Mat6x36 b, db, rate_jac;
  Vec36 unused_force;
  const auto at_point = [&](std::size_t p, const ShellPointFields& fields,
                            const ShellPointState& st) {
    const ShellPointKinematics kin = pointKinematics(fields, st);
    const ShellShapeValues& s = shape(p);
    strainJacobianAndVariation<ShellStressPart::kElastic>(kin, s, qp_[p].reference, c, b, db);
    block.noalias() += b.transpose() * (material * db);
    if (stiffness != 0.0) {
      const Eigen::Vector3d sigma = stiffness * Eigen::Map<const Eigen::Vector3d>(st.resultants);
      const Eigen::Vector3d moment =
          stiffness * Eigen::Map<const Eigen::Vector3d>(st.resultants + 3);
      addShellGeometricTangent(kin, s, sigma, moment, block);
    }
    if (rate_term != 0.0) {
      shellStrainRateJacobian(kin, s, edot_hat, rate_jac);
      block.noalias() += db.transpose() * (rate_term * rate_jac);
    }
  };
  if (mu == 0.0)
    pointForces<ShellStressPart::kElastic>(e, nullptr, c, unused_force, at_point);
  else
    pointForces<ShellStressPart::kBoth>(e, &edot, c, unused_force, at_point);
}

}  // namespace mastrom::fullorder
