// A recovery point's six stress rows at a state, y = B x (docs/theory.md (6.9)): the one sum every
// exact stress evaluation of the ROM makes (ModalStressEvaluator::largestAbove, its History). Not
// part of the library's interface.
#pragma once

#include <Eigen/Core>

namespace mastrom::rom::stress_detail {

/// y[r] = Σ_j B(r, j) x_j for r < 6, summed over j in order with a multiply, then an add per term,
/// whatever the instruction set (the AVX2 copy has no FMA): the same bits in either copy and in
/// every caller. `rows` points at B(0, 0); column j starts at rows + j·column_stride.
void pointRows(const double* rows, Eigen::Index column_stride, const double* x, int inputs,
               double* y);

}  // namespace mastrom::rom::stress_detail
