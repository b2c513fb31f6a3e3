// The cubic weights' error at a point from the probes (see probe_point_estimate.hpp).
#include "rom/database/probe_point_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.hpp"

namespace mastrom::rom {
namespace {

/// The interpolation coordinate of axis `a` (log x on a positive axis, §4.4 (a′)).
double coordinate(const ParameterAxis& a, double x) {
  return a.values.front() > 0 && a.values.back() > 0 ? std::log(x) : x;
}

/// |ω(s)| over the local stencil of `s` on the axis' nodes (the cubic weights' stencil).
double nodePolynomial(const ParameterAxis& axis, double s) {
  std::vector<double> nodes;
  for (const double v : axis.values) nodes.push_back(coordinate(axis, v));
  const int m = std::min(4, static_cast<int>(nodes.size()));
  const int first = localStencilFirst(nodes, s, m);
  double product = 1.0;
  for (int k = first; k < first + m; ++k) product *= s - nodes[static_cast<std::size_t>(k)];
  return std::abs(product);
}

}  // namespace

std::pair<double, double> probePointEstimate(const RomDatabase& db, const std::vector<double>& point) {
  if (db.probes.empty() || !db.isGrid()) return {-1.0, -1.0};
  MASTROM_REQUIRE(point.size() == db.axes.size(), InputError, "rom: a point of ", point.size(),
                  " parameters for a database of ", db.axes.size());
  const std::size_t p = db.axes.size();
  // Per axis, in the interpolation coordinate: the cells' centres (where
  // rom/offline/probe_estimate.cpp places the probes), the point's cell, and the point's place
  // between the two centres around it (clamped to the outer centres).
  std::vector<std::vector<double>> centres(p);
  std::vector<int> lower(p);
  std::vector<double> t(p, 0.0), own_centre(p), span(p);
  std::size_t cells = 1;
  for (std::size_t a = 0; a < p; ++a) {
    const ParameterAxis& axis = db.axes[a];
    const std::vector<double>& v = axis.values;
    const double s = coordinate(axis, point[a]);
    span[a] = coordinate(axis, v.back()) - coordinate(axis, v.front());
    for (std::size_t i = 0; i + 1 < v.size(); ++i)
      centres[a].push_back(0.5 * (coordinate(axis, v[i]) + coordinate(axis, v[i + 1])));
    if (centres[a].empty()) centres[a].push_back(coordinate(axis, v.front()));
    cells *= centres[a].size();
    const auto own = std::upper_bound(v.begin() + 1, v.end() - 1, point[a]);
    own_centre[a] = centres[a][std::min(static_cast<std::size_t>(own - v.begin()) - 1,
                                        centres[a].size() - 1)];
    const std::vector<double>& c = centres[a];
    std::size_t j = 0;
    while (j + 2 < c.size() && s > c[j + 1]) ++j;
    lower[a] = static_cast<int>(j);
    if (c.size() > 1) t[a] = std::clamp((s - c[j]) / (c[j + 1] - c[j]), 0.0, 1.0);
  }
  // The centre's error at the point: multilinear between the cells' probes when every cell was
  // probed (the probes are then in cell order, first axis fastest — checked), so that it does not
  // jump at a cell's face; the nearest probe's otherwise.
  bool every_cell = db.probes.size() == cells;
  for (std::size_t k = 0; every_cell && k < cells; ++k) {
    std::size_t rest = k;
    for (std::size_t a = 0; a < p && every_cell; ++a) {
      const double expected = centres[a][rest % centres[a].size()];
      rest /= centres[a].size();
      const double stored = coordinate(db.axes[a], db.probes[k].parameters[a]);
      every_cell = std::abs(stored - expected) <= 1e-9 * std::max(1.0, std::abs(expected));
    }
  }
  double f = 0.0, r = 0.0;
  if (every_cell) {
    for (std::size_t mask = 0; mask < (std::size_t{1} << p); ++mask) {
      double w = 1.0;
      std::size_t index = 0, stride = 1;
      for (std::size_t a = 0; a < p && w > 0; ++a) {
        const bool upper = (mask >> a) & 1;
        if (upper && centres[a].size() < 2) w = 0.0;
        w *= upper ? t[a] : 1.0 - t[a];
        index += stride * (static_cast<std::size_t>(lower[a]) + (upper ? 1 : 0));
        stride *= centres[a].size();
      }
      if (w <= 0) continue;
      f += w * db.probes[index].frequency_error;
      r += w * db.probes[index].response_error;
    }
  } else {
    std::size_t best = 0;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < db.probes.size(); ++i) {
      double d = 0.0;
      for (std::size_t a = 0; a < p; ++a) {
        if (span[a] <= 0) continue;
        const double x = (own_centre[a] - coordinate(db.axes[a], db.probes[i].parameters[a])) / span[a];
        d += x * x;
      }
      if (d < best_distance) {
        best_distance = d;
        best = i;
      }
    }
    f = db.probes[best].frequency_error;
    r = db.probes[best].response_error;
  }
  // (4.13): the node polynomials' largest ratio, point over its cell's centre.
  double scale = 0.0;
  for (std::size_t a = 0; a < p; ++a) {
    if (db.axes[a].values.size() < 2) continue;
    const double at_centre = nodePolynomial(db.axes[a], own_centre[a]);
    if (at_centre > 0)
      scale = std::max(scale,
                       nodePolynomial(db.axes[a], coordinate(db.axes[a], point[a])) / at_centre);
  }
  return {scale * f, scale * r};
}

}  // namespace mastrom::rom
