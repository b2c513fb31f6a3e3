// Quadrature and assembly of the ANCF thin-shell element (docs/theory.md §2.2). The point-wise
// kinematics and their derivatives live in shell_kinematics.cpp.
#include "fullorder/shell_element.hpp"

#include <cmath>
#include <utility>

#include "common/error.hpp"
#include "fullorder/gauss_quadrature.hpp"
#include "fullorder/shell_kinematics.hpp"

namespace mastrom::fullorder {
namespace {

using Map3x12 = Eigen::Map<const Mat3x12>;
using MutMap3x12 = Eigen::Map<Mat3x12>;

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
    const Eigen::Vector3d area = gx.cross(gy);
    const double da = area.norm();
    MASTROM_REQUIRE(da > 0, InputError, "shell: degenerate reference geometry");
    const Eigen::Vector3d nrm = area / da;
    const double w = table_->weights[p] * 0.25 * a_m * b_m * da;
    const Eigen::Matrix3d t = voigtFrameTransform(gx, gy);
    q.d_eff = w * t.transpose() * d_hat * t;
    q.mass_weight = w;
    q.e0_metric << gx.squaredNorm(), gy.squaredNorm(), gx.dot(gy);
    q.k0 << (e0_hat * s.nxx).dot(nrm), (e0_hat * s.nyy).dot(nrm), 2.0 * (e0_hat * s.nxy).dot(nrm);
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

double ShellElement::strainEnergy(const Vec36& e, const ShellTerms& terms) const {
  const Map3x12 e_hat(e.data());
  const double h = section_.thickness_m, young = section_.youngs_modulus_pa;
  const double cm = terms.membrane_scale * young * h * 0.5;
  const double cb = terms.bending_scale * young * h * h * h / 24.0;
  double u = 0.0;
  for (std::size_t p = 0; p < qp_.size(); ++p) {
    const QuadPoint& q = qp_[p];
    const ShellShapeValues& s = shape(p);
    const ShellPointKinematics kin = shellKinematics(e_hat, s, q.e0_metric, q.k0);
    u += cm * kin.membrane.dot(q.d_eff * kin.membrane) + cb * kin.bending.dot(q.d_eff * kin.bending);
  }
  return u;
}

void ShellElement::elasticForce(const Vec36& e, Vec36& f, const ShellTerms& terms) const {
  const Map3x12 e_hat(e.data());
  const double h = section_.thickness_m, young = section_.youngs_modulus_pa;
  const double cm = terms.membrane_scale * young * h;
  const double cb = terms.bending_scale * young * h * h * h / 12.0;
  Mat3x12 f_hat = Mat3x12::Zero();
  for (std::size_t p = 0; p < qp_.size(); ++p) {
    const QuadPoint& q = qp_[p];
    const ShellShapeValues& s = shape(p);
    const ShellPointKinematics kin = shellKinematics(e_hat, s, q.e0_metric, q.k0);
    const Eigen::Vector3d sigma = cm * (q.d_eff * kin.membrane);
    const Eigen::Vector3d moment = cb * (q.d_eff * kin.bending);
    addShellInternalForce(kin, s, sigma, moment, f_hat);
  }
  MutMap3x12(f.data()) = f_hat;
}

void ShellElement::elasticForceAndTangent(const Vec36& e, Vec36& f, Mat36& k,
                                          const ShellTerms& terms) const {
  const Map3x12 e_hat(e.data());
  const double h = section_.thickness_m, young = section_.youngs_modulus_pa;
  const double cm = terms.membrane_scale * young * h;
  const double cb = terms.bending_scale * young * h * h * h / 12.0;
  k.setZero();
  Mat3x12 f_hat = Mat3x12::Zero();
  Mat6x36 b;
  Eigen::Matrix<double, 6, 36> db;
  for (std::size_t p = 0; p < qp_.size(); ++p) {
    const QuadPoint& q = qp_[p];
    const ShellShapeValues& s = shape(p);
    const ShellPointKinematics kin = shellKinematics(e_hat, s, q.e0_metric, q.k0);
    const Eigen::Vector3d sigma = cm * (q.d_eff * kin.membrane);
    const Eigen::Vector3d moment = cb * (q.d_eff * kin.bending);
    addShellInternalForce(kin, s, sigma, moment, f_hat);
    // Material part Bᵀ D B with D = diag(cm·D_q, cb·D_q).
    shellStrainJacobian(kin, s, b);
    db.topRows<3>().noalias() = (cm * q.d_eff) * b.topRows<3>();
    db.bottomRows<3>().noalias() = (cb * q.d_eff) * b.bottomRows<3>();
    k.noalias() += b.transpose() * db;
    addShellGeometricTangent(kin, s, sigma, moment, k);
  }
  MutMap3x12(f.data()) = f_hat;
}

void ShellElement::internalForce(const Vec36& e, const Vec36& edot, Vec36& f) const {
  const Map3x12 e_hat(e.data()), edot_hat(edot.data());
  const double h = section_.thickness_m, young = section_.youngs_modulus_pa;
  const double cm = young * h, cb = young * h * h * h / 12.0;
  const double mu = section_.damping_s;
  // Kelvin–Voigt: stress = D(ε + μ ε̇), so one resultant carries both forces.
  Mat3x12 f_hat = Mat3x12::Zero();
  const Mat3x12 e_copy = e_hat;
  Mat3x12 edot_copy;
  if (mu != 0.0) edot_copy = edot_hat;
  const Mat3x12* rates = mu != 0.0 ? &edot_copy : nullptr;
  for (std::size_t p = 0; p < qp_.size(); ++p) {
    const QuadPoint& q = qp_[p];
    addShellPointInternalForce(e_copy, rates, table_->derivatives[p], q.d_eff, q.e0_metric, q.k0,
                               cm, cb, mu, f_hat);
  }
  MutMap3x12(f.data()) = f_hat;
}

void ShellElement::dampingForce(const Vec36& e, const Vec36& edot, Vec36& f) const {
  f.setZero();
  if (section_.damping_s == 0.0) return;
  const Map3x12 e_hat(e.data()), edot_hat(edot.data());
  const double h = section_.thickness_m, young = section_.youngs_modulus_pa;
  const double cm = section_.damping_s * young * h;
  const double cb = section_.damping_s * young * h * h * h / 12.0;
  Mat3x12 f_hat = Mat3x12::Zero();
  for (std::size_t p = 0; p < qp_.size(); ++p) {
    const QuadPoint& q = qp_[p];
    const ShellShapeValues& s = shape(p);
    const ShellPointKinematics kin = shellKinematics(e_hat, s, q.e0_metric, q.k0);
    const Eigen::Matrix<double, 6, 1> rate = shellStrainRates(kin, s, edot_hat);  // [Ė; k̇]
    addShellInternalForce(kin, s, cm * (q.d_eff * rate.head<3>()),
                          cb * (q.d_eff * rate.tail<3>()), f_hat);
  }
  MutMap3x12(f.data()) = f_hat;
}

void ShellElement::dampingForceAndTangents(const Vec36& e, const Vec36& edot, Vec36& f, Mat36& c,
                                           Mat36& k_d) const {
  f.setZero();
  c.setZero();
  k_d.setZero();
  if (section_.damping_s == 0.0) return;
  const Map3x12 e_hat(e.data()), edot_hat(edot.data());
  const double h = section_.thickness_m, young = section_.youngs_modulus_pa;
  const double cm = section_.damping_s * young * h;
  const double cb = section_.damping_s * young * h * h * h / 12.0;
  Mat6x36 b, db, rate_jac;
  for (std::size_t p = 0; p < qp_.size(); ++p) {
    const QuadPoint& q = qp_[p];
    const ShellShapeValues& s = shape(p);
    const ShellPointKinematics kin = shellKinematics(e_hat, s, q.e0_metric, q.k0);
    shellStrainJacobian(kin, s, b);
    const Eigen::Matrix<double, 6, 1> rate = b * edot;
    const Eigen::Vector3d sigma = cm * (q.d_eff * rate.head<3>());
    const Eigen::Vector3d moment = cb * (q.d_eff * rate.tail<3>());
    f.noalias() += b.topRows<3>().transpose() * sigma + b.bottomRows<3>().transpose() * moment;
    db.topRows<3>().noalias() = (cm * q.d_eff) * b.topRows<3>();
    db.bottomRows<3>().noalias() = (cb * q.d_eff) * b.bottomRows<3>();
    c.noalias() += b.transpose() * db;
    // ∂F_d/∂e = Σ_c s_c ∂²ε_c/∂e² + Bᵀ D ∂(B ė)/∂e, and ∂(B ė)_c/∂e = (∂²ε_c/∂e² ė)ᵀ.
    addShellGeometricTangent(kin, s, sigma, moment, k_d);
    shellStrainRateJacobian(kin, s, edot_hat, rate_jac);
    k_d.noalias() += db.transpose() * rate_jac;
  }
}

}  // namespace mastrom::fullorder
