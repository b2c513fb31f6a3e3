// The modal contractions the metrics' outputs need at one instant (rom/model/deployment_outputs.hpp):
// 14 rows against (η, η̇, η̈), accumulated in one pass over the modes. It is the largest part of a
// screen's deployment (evaluated at every sample and every refined sub-node: ≈ 40 % of the
// metrics' time at 2 ms, 20 modes, before it had its own kernel), so it is compiled twice
// (common/cpu_features.hpp): the baseline copy adds the modes in order, exactly as the Eigen
// products it replaced did (bit-identical results); the AVX2 + FMA copy holds the 14 rows in four
// registers and accumulates even and odd modes separately, halving the chain of dependent
// additions (the results differ from the baseline's by round-off). Not part of the library's
// interface.
#pragma once

#include <vector>

#include "rom/model/modal_model.hpp"

namespace mastrom::rom::metrics_detail {

class OutputContraction {
public:
  /// Rows per mode, 14 used and two zero (four AVX registers of four doubles):
  ///   0–3   with η:  (Lη)_x, (Lη)_y, Γ_cᵀη, 0
  ///   4–7   with η̇:  (Lη̇)_x, (Lη̇)_y, Γ_cᵀη̇, 0
  ///   8–13  with η̈:  (ψη̈)_z, (Lη̈)_x,y,z, Γᵀη̈, 0
  ///   14–15 zero.
  static constexpr int kRows = 16;
  static constexpr int kEta = 0, kRate = 4, kAcc = 8;

  explicit OutputContraction(const ModalModel& m);

  /// y[0 … kRows) from the states (each of the model's mode count).
  void apply(const double* eta, const double* eta_dot, const double* eta_ddot, double* y) const;

private:
  long modes_ = 0;
  std::vector<double> rows_;  ///< kRows × modes, column-major: mode i's rows contiguous
};

}  // namespace mastrom::rom::metrics_detail
