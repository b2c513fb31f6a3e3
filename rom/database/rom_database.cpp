#include "rom/database/rom_database.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::rom {

int RomDatabase::sampleIndex(const std::vector<int>& multi_index) const {
  MASTROM_REQUIRE(multi_index.size() == axes.size(), InputError, "rom database: index has ",
                  multi_index.size(), " entries for ", axes.size(), " parameters");
  int index = 0, stride = 1;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const int n = static_cast<int>(axes[a].values.size());
    MASTROM_REQUIRE(multi_index[a] >= 0 && multi_index[a] < n, InputError,
                    "rom database: index ", multi_index[a], " outside axis ", axes[a].key);
    index += stride * multi_index[a];
    stride *= n;
  }
  return index;
}

int RomDatabase::exactModulusAxis() const {
  if (!exact_modulus) return -1;
  for (std::size_t a = 0; a < axes.size(); ++a)
    if (axes[a].key == kYoungsModulusKey) return static_cast<int>(a);
  return -1;
}

RomDatabase sampledDatabase(const RomDatabase& db) {
  RomDatabase out = db;
  const int axis = db.exactModulusAxis();
  out.exact_modulus.reset();
  if (axis < 0) return out;
  out.axes.erase(out.axes.begin() + axis);
  for (RomSample& s : out.samples) {
    MASTROM_REQUIRE(s.parameters.size() == db.axes.size(), InputError, "rom database: a sample has ",
                    s.parameters.size(), " parameters for ", db.axes.size(), " axes");
    s.parameters.erase(s.parameters.begin() + axis);
  }
  return out;
}

bool RomDatabase::contains(const std::vector<double>& p) const {
  if (p.size() != axes.size()) return false;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const double lo = axes[a].values.front(), hi = axes[a].values.back();
    const double tol = 1e-12 * std::max(std::abs(hi - lo), std::abs(hi));
    if (!(p[a] >= lo - tol && p[a] <= hi + tol)) return false;
  }
  return true;
}

std::vector<int> gridIndex(const std::vector<ParameterAxis>& axes, int index) {
  std::vector<int> multi(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const int n = static_cast<int>(axes[a].values.size());
    multi[a] = index % n;
    index /= n;
  }
  return multi;
}

std::vector<double> gridPoint(const std::vector<ParameterAxis>& axes, int index) {
  const std::vector<int> multi = gridIndex(axes, index);
  std::vector<double> p(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) p[a] = axes[a].values[multi[a]];
  return p;
}

double leaveOneOutScale(const std::vector<ParameterAxis>& axes, int index) {
  const std::vector<int> multi = gridIndex(axes, index);
  double scale = 0.0;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const std::vector<double>& v = axes[a].values;
    const int i = multi[a];
    if (i <= 0 || i + 1 >= static_cast<int>(v.size())) continue;
    // The coordinate the interpolants' weights are linear in: log p on a positive axis (the
    // manifold's default, ManifoldInterpolationOptions), p otherwise.
    const auto u = [&v](int j) { return v.front() > 0 ? std::log(v[j]) : v[j]; };
    const double h1 = u(i) - u(i - 1), h2 = u(i + 1) - u(i);
    scale = std::max(scale, std::max(h1, h2) * std::max(h1, h2) / (4.0 * h1 * h2));
  }
  return scale;
}

int localStencilFirst(const std::vector<double>& nodes, double x, int m) {
  const int n = static_cast<int>(nodes.size());
  if (n < 2) return 0;
  const int cell = std::clamp(
      static_cast<int>(std::upper_bound(nodes.begin(), nodes.end(), x) - nodes.begin()) - 1, 0,
      n - 2);
  return std::clamp(cell - (m - 1) / 2, 0, n - m);
}

double leaveOneOutScaleFor(const std::vector<ParameterAxis>& axes, int index,
                           InterpolationMethod method) {
  switch (method) {
    case InterpolationMethod::Affine:
    case InterpolationMethod::Rbf:
      return 1.0;
    case InterpolationMethod::Cubic:
      return cubicLeaveOneOutScale(axes, index);
    case InterpolationMethod::Tracked:
    case InterpolationMethod::Manifold:
      break;
  }
  return leaveOneOutScale(axes, index);
}

namespace {

/// |Π (u − u_k)| over the 4 nodes of the local cubic stencil of `u_nodes` around u.
double cubicNodePolynomial(const std::vector<double>& u_nodes, double u) {
  const int first = localStencilFirst(u_nodes, u, 4);
  double product = 1.0;
  for (int k = first; k < first + 4; ++k) product *= u - u_nodes[static_cast<std::size_t>(k)];
  return std::abs(product);
}

}  // namespace

double cubicLeaveOneOutScale(const std::vector<ParameterAxis>& axes, int index) {
  const std::vector<int> multi = gridIndex(axes, index);
  double scale = 0.0;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const std::vector<double>& v = axes[a].values;
    const int n = static_cast<int>(v.size());
    const int i = multi[a];
    if (n < 5 || i <= 0 || i + 1 >= n) continue;
    std::vector<double> u(v.size()), reduced;
    for (int j = 0; j < n; ++j) {
      u[static_cast<std::size_t>(j)] = v.front() > 0 ? std::log(v[j]) : v[j];
      if (j != i) reduced.push_back(u[static_cast<std::size_t>(j)]);
    }
    const double left_out = cubicNodePolynomial(reduced, u[static_cast<std::size_t>(i)]);
    for (const int c : {i - 1, i}) {  // the two full-grid cells next to the sample
      const double mid = 0.5 * (u[static_cast<std::size_t>(c)] + u[static_cast<std::size_t>(c + 1)]);
      scale = std::max(scale, cubicNodePolynomial(u, mid) / left_out);
    }
  }
  return scale;
}

}  // namespace mastrom::rom
