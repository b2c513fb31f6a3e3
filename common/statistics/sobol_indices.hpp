// Variance-based sensitivity (docs/theory.md §7.4): first-order and total Sobol indices of a
// function of k independent inputs by Saltelli's sampling and Jansen's estimators, with bootstrap
// confidence intervals [Saltelli et al. 2010, Comput. Phys. Commun. 181, 259–270, Table 2 (b),
// (f); Jansen 1999, Comput. Phys. Commun. 117, 35–43]. No Debian library offers them (GSL has the
// sequences and statistics they are built on).
//
// Saltelli's design: a point u of dimension 2k gives two input points A = u[0, k) and B = u[k, 2k),
// and k more, AB_i = A with its i-th coordinate taken from B. The k + 2 function values of base
// sample j are stored together, f[(k + 2) j + r] with r = 0: A, 1: B, 2 + i: AB_i. Then, with
// V the variance of the 2N values f(A), f(B):
//     S_i  = 1 − Σ_j (f(B_j) − f(AB_i,j))² / (2 N V)        (B and AB_i share only x_i)
//     ST_i =     Σ_j (f(A_j) − f(AB_i,j))² / (2 N V)        (A and AB_i share all but x_i)
// The bootstrap redraws the N base samples with replacement; an interval is the percentile range
// of the redrawn estimates (GSL quantiles).
#pragma once

#include <cstddef>
#include <vector>

#include "common/statistics/sample_statistics.hpp"

namespace mastrom::stats {

/// The k + 2 input rows of Saltelli's design from one unit point u of dimension 2k, each row k
/// values, written to rows[(k + 2) × k] (in the order A, B, AB_1 … AB_k).
void saltelliRows(const double* u, int k, double* rows);

struct SobolIndices {
  double variance = 0.0;        ///< V of f(A) ∪ f(B)
  std::vector<Interval> first;  ///< S_i, one per input
  std::vector<Interval> total;  ///< ST_i
  /// The widest interval of any index (the stopping test of an adaptive sample).
  double widestInterval() const;
};

struct BootstrapOptions {
  int resamples = 200;
  double confidence = 0.95;
  unsigned long seed = 1;
};

/// Jansen's indices from the values of N base samples in Saltelli's order (f.size() = N (k + 2),
/// N ≥ 2). A constant function (V = 0) has all indices 0 with zero-width intervals.
SobolIndices jansenIndices(const std::vector<double>& f, int k, const BootstrapOptions& bootstrap);

}  // namespace mastrom::stats
