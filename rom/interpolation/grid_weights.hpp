// Weights on a database's tensor grid: which samples, with what weights, make up the interpolant at
// a point — multilinear (tensor-product hats, docs/theory.md (4.6); the tracked and the manifold
// interpolation) and tensor-product local Lagrange of higher degree (docs/theory.md (4.9); the
// cubic interpolation).
#pragma once

#include <vector>

#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

/// One term of a multilinear interpolant: the weight of a grid sample.
struct GridWeight {
  int sample = 0;
  double weight = 0.0;
};

/// The local coordinate t ∈ [0, 1] of a point in its grid cell [v_i, v_{i+1}] along one axis.
enum class AxisWeighting {
  Linear,      ///< t = (x − v_i)/(v_{i+1} − v_i) on every axis
  Logarithmic  ///< t = log(x/v_i)/log(v_{i+1}/v_i) on axes whose values are all > 0, else linear
};

/// Multilinear weights of `parameters` on the tensor grid of `axes` (sample index first axis
/// fastest, as in rom/database/rom_database.hpp): the 2^p corners of the cell containing the point, or of the
/// boundary cell outside the box (linear extrapolation in t); exactly-zero weights are dropped, so
/// at a grid node one sample with weight exactly 1 is returned. The weights sum to 1. Throws
/// InputError when the number of values is wrong, a value is not finite (or not > 0 on a
/// logarithmic axis), or an axis is empty or not strictly ascending.
std::vector<GridWeight> multilinearWeights(const std::vector<ParameterAxis>& axes,
                                           const std::vector<double>& parameters,
                                           AxisWeighting weighting = AxisWeighting::Linear);

/// Tensor-product Lagrange weights of degree ≤ `degree` (≥ 1) per axis: on each axis the
/// m = min(degree + 1, n) consecutive nodes centred on the point's cell (shifted inwards at the
/// ends of the axis), the Lagrange basis of those nodes in x (or log x, as multilinearWeights)
/// evaluated at the point, multiplied over the axes. Reproduces every polynomial of degree < m in
/// each variable exactly; at a grid node one sample with weight exactly 1 is returned; the weights
/// sum to 1 (to round-off) and may be negative. Outside the box: polynomial extrapolation from the
/// boundary stencil. Same errors as multilinearWeights.
std::vector<GridWeight> lagrangeWeights(const std::vector<ParameterAxis>& axes,
                                        const std::vector<double>& parameters, int degree,
                                        AxisWeighting weighting = AxisWeighting::Linear);

}  // namespace mastrom::rom
