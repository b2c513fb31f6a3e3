// Rigid rotations of the model's coordinates. Every coordinate of the mast is a 3-vector block — a
// position or a slope of a shell node, a point or a direction vector of a rigid module in natural
// coordinates — so a rigid rotation R of the whole mast acts as the same R on every block
// (docs/theory.md (4.1)). The one definition of a rotation about the global Z axis (the joint axis)
// and of its action on stacked 3-blocks, for the full order, the modes and the ROM.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "common/error.hpp"

namespace mastrom::fullorder {

/// Rotation by `angle_rad` about +Z (counter-clockwise seen from +Z). The Z row and column are
/// exactly (0, 0, 1).
inline Eigen::Matrix3d rotationAboutZ(double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  Eigen::Matrix3d r;
  r << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  return r;
}

/// `rotation` applied to every 3-block of rows of x (a coordinate vector, or mode shapes as
/// columns). Throws InputError when the row count is not a multiple of 3.
template <class Derived>
Eigen::Matrix<double, Derived::RowsAtCompileTime, Derived::ColsAtCompileTime> rotateEveryBlock(
    const Eigen::MatrixBase<Derived>& x, const Eigen::Matrix3d& rotation) {
  MASTROM_REQUIRE(x.rows() % 3 == 0, InputError, "rigid rotation: ", x.rows(),
                  " coordinates are not whole 3-vector blocks");
  Eigen::Matrix<double, Derived::RowsAtCompileTime, Derived::ColsAtCompileTime> out(x.rows(),
                                                                                     x.cols());
  for (Eigen::Index b = 0; b < x.rows(); b += 3)
    out.template middleRows<3>(b) = rotation * x.template middleRows<3>(b);
  return out;
}

/// Ωx: Z × every 3-block of x, the velocity field of a unit rotation rate about the Z axis through
/// the origin (docs/theory.md (4.1)). Throws InputError when x is not whole 3-blocks.
inline Eigen::VectorXd rotationRateField(const Eigen::Ref<const Eigen::VectorXd>& x) {
  MASTROM_REQUIRE(x.size() % 3 == 0, InputError, "rotation field: ", x.size(),
                  " coordinates are not whole 3-vector blocks");
  Eigen::VectorXd out(x.size());
  for (Eigen::Index b = 0; b < x.size(); b += 3) {
    out[b] = -x[b + 1];  // Z × (x, y, z) = (−y, x, 0)
    out[b + 1] = x[b];
    out[b + 2] = 0.0;
  }
  return out;
}

}  // namespace mastrom::fullorder
