// The product behind a ROM stress history (docs/theory.md §6.5): an interface's stress rows
// [S | S_res | σ̄] times the states of a block of samples, with an AVX2 + FMA kernel where the CPU
// has one (common/cpu_features.hpp) and Eigen's product otherwise. Not part of the library's
// interface.
#pragma once

#include <Eigen/Core>

namespace mastrom::rom::stress_detail {

/// y.leftCols(count) = rows · states.middleCols(first, count); y has rows.rows() rows and at least
/// `count` columns (sized by the caller, reused across blocks).
void stressBlockProduct(const Eigen::MatrixXd& rows, const Eigen::MatrixXd& states,
                        Eigen::Index first, Eigen::Index count, Eigen::MatrixXd& y);

}  // namespace mastrom::rom::stress_detail
