// Multilinear weights on a tensor grid (see grid_weights.hpp).
#include "rom/interpolation/grid_weights.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::rom {

std::vector<GridWeight> multilinearWeights(const std::vector<ParameterAxis>& axes,
                                           const std::vector<double>& parameters,
                                           AxisWeighting weighting) {
  const std::size_t p = axes.size();
  MASTROM_REQUIRE(parameters.size() == p, InputError, "rom: ", parameters.size(),
                  " parameter values for ", p, " database axes");
  std::vector<int> base(p), nodes(p), strides(p);
  std::vector<double> t(p);
  int stride = 1;
  for (std::size_t a = 0; a < p; ++a) {
    const std::vector<double>& v = axes[a].values;
    MASTROM_REQUIRE(!v.empty(), InputError, "rom database: axis ", axes[a].key, " has no values");
    for (std::size_t i = 1; i < v.size(); ++i)
      MASTROM_REQUIRE(v[i] > v[i - 1], InputError, "rom database: the values of axis ",
                      axes[a].key, " are not strictly ascending");
    const double x = parameters[a];
    MASTROM_REQUIRE(std::isfinite(x), InputError, "rom: ", axes[a].key, " = ", x,
                    " is not finite");
    strides[a] = stride;
    stride *= static_cast<int>(v.size());
    if (v.size() == 1) {
      base[a] = 0;
      t[a] = 0.0;
      nodes[a] = 1;
      continue;
    }
    // Cell [v_i, v_{i+1}] with v_i ≤ x (the last cell at and beyond the upper end): t is exactly 0
    // at every node but the last, where it is exactly (v_n − v_{n−1})/(v_n − v_{n−1}) = 1.
    const int n = static_cast<int>(v.size());
    const int i = std::clamp(
        static_cast<int>(std::upper_bound(v.begin(), v.end(), x) - v.begin()) - 1, 0, n - 2);
    base[a] = i;
    t[a] = (x - v[i]) / (v[i + 1] - v[i]);
    if (weighting == AxisWeighting::Logarithmic && v.front() > 0.0) {
      MASTROM_REQUIRE(x > 0.0, InputError, "rom: ", axes[a].key, " = ", x,
                      " must be > 0 (logarithmic weights on an axis of positive values)");
      t[a] = std::log(x / v[i]) / std::log(v[i + 1] / v[i]);
    }
    nodes[a] = 2;
  }
  std::vector<GridWeight> out;
  for (int c = 0; c < (1 << p); ++c) {
    double w = 1.0;
    int index = 0;
    bool valid = true;
    for (std::size_t a = 0; a < p; ++a) {
      const int bit = (c >> a) & 1;
      if (bit >= nodes[a]) {
        valid = false;
        break;
      }
      w *= bit ? t[a] : 1.0 - t[a];
      index += strides[a] * (base[a] + bit);
    }
    if (valid && w != 0.0) out.push_back({index, w});
  }
  return out;
}

namespace {

/// One axis of a tensor-product stencil: the first node, and the 1-D weight of each stencil node.
struct AxisStencil {
  int first = 0;
  std::vector<double> weights;
};

AxisStencil lagrangeStencil(const ParameterAxis& axis, double x, int degree,
                            AxisWeighting weighting) {
  const std::vector<double>& v = axis.values;
  MASTROM_REQUIRE(!v.empty(), InputError, "rom database: axis ", axis.key, " has no values");
  for (std::size_t i = 1; i < v.size(); ++i)
    MASTROM_REQUIRE(v[i] > v[i - 1], InputError, "rom database: the values of axis ", axis.key,
                    " are not strictly ascending");
  MASTROM_REQUIRE(std::isfinite(x), InputError, "rom: ", axis.key, " = ", x, " is not finite");
  const int n = static_cast<int>(v.size());
  if (n == 1) return {0, {1.0}};
  const int m = std::min(degree + 1, n);
  // The m nodes centred on the cell holding x (as multilinearWeights' cell).
  const int first = localStencilFirst(v, x, m);
  const bool logarithmic = weighting == AxisWeighting::Logarithmic && v.front() > 0.0;
  MASTROM_REQUIRE(!logarithmic || x > 0.0, InputError, "rom: ", axis.key, " = ", x,
                  " must be > 0 (logarithmic weights on an axis of positive values)");
  const auto coordinate = [logarithmic](double value) {
    return logarithmic ? std::log(value) : value;
  };
  const double s = coordinate(x);
  AxisStencil stencil{first, std::vector<double>(static_cast<std::size_t>(m), 1.0)};
  for (int j = 0; j < m; ++j) {
    const double sj = coordinate(v[static_cast<std::size_t>(first + j)]);
    for (int k = 0; k < m; ++k) {
      if (k == j) continue;
      const double sk = coordinate(v[static_cast<std::size_t>(first + k)]);
      // At a node: exactly (s_j − s_k)/(s_j − s_k) = 1, or a factor exactly 0.
      stencil.weights[static_cast<std::size_t>(j)] *= (s - sk) / (sj - sk);
    }
  }
  return stencil;
}

}  // namespace

std::vector<GridWeight> lagrangeWeights(const std::vector<ParameterAxis>& axes,
                                        const std::vector<double>& parameters, int degree,
                                        AxisWeighting weighting) {
  const std::size_t p = axes.size();
  MASTROM_REQUIRE(parameters.size() == p, InputError, "rom: ", parameters.size(),
                  " parameter values for ", p, " database axes");
  MASTROM_REQUIRE(degree >= 1, InputError, "rom: interpolation degree ", degree, " must be >= 1");
  std::vector<AxisStencil> stencils;
  std::vector<int> strides(p);
  int stride = 1;
  for (std::size_t a = 0; a < p; ++a) {
    stencils.push_back(lagrangeStencil(axes[a], parameters[a], degree, weighting));
    strides[a] = stride;
    stride *= static_cast<int>(axes[a].values.size());
  }
  // Every combination of one stencil node per axis (odometer over the axes, first fastest).
  std::vector<GridWeight> out;
  std::vector<std::size_t> digit(p, 0);
  while (true) {
    double w = 1.0;
    int index = 0;
    for (std::size_t a = 0; a < p; ++a) {
      w *= stencils[a].weights[digit[a]];
      index += strides[a] * (stencils[a].first + static_cast<int>(digit[a]));
    }
    if (w != 0.0) out.push_back({index, w});
    std::size_t a = 0;
    while (a < p && ++digit[a] == stencils[a].weights.size()) digit[a++] = 0;
    if (a == p) break;
  }
  return out;
}

}  // namespace mastrom::rom
