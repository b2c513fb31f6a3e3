#include "tests/modes/test_models.hpp"

#include <array>
#include <cmath>
#include <random>

namespace mastrom::modes::test_models {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

SparseMatrix fromTriplets(Eigen::Index rows, Eigen::Index cols, const Triplets& entries) {
  SparseMatrix a(rows, cols);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  return a;
}

}  // namespace

ConstrainedEigenproblem fixedFreeChain(int masses, double mass_kg, double stiffness_n_m) {
  const int n = masses + 1;
  Triplets k, m, g;
  for (int i = 1; i < n; ++i) {
    k.emplace_back(i - 1, i - 1, stiffness_n_m);
    k.emplace_back(i, i, stiffness_n_m);
    k.emplace_back(i - 1, i, -stiffness_n_m);
    k.emplace_back(i, i - 1, -stiffness_n_m);
    m.emplace_back(i, i, mass_kg);
  }
  g.emplace_back(0, 0, 1.0);
  ConstrainedEigenproblem problem;
  problem.stiffness = fromTriplets(n, n, k);
  problem.mass = fromTriplets(n, n, m);
  problem.constraint_jacobian = fromTriplets(1, n, g);
  return problem;
}

Eigen::VectorXd fixedFreeChainOmegas(int masses, double mass_kg, double stiffness_n_m, int count) {
  const double pi = 3.141592653589793;
  Eigen::VectorXd omega(count);
  for (int j = 1; j <= count; ++j)
    omega(j - 1) = 2.0 * std::sqrt(stiffness_n_m / mass_kg) *
                   std::sin((2 * j - 1) * pi / (2.0 * (2 * masses + 1)));
  return omega;
}

ConstrainedEigenproblem latticeTower(int storeys) {
  constexpr double side = 1.0, height = 0.8;
  constexpr double axial_stiffness = 2.0e7;  // EA [N]
  constexpr double line_density = 1.5;       // ρA [kg/m]
  const int levels = storeys + 1;
  const int nodes = 4 * levels;
  const int n = 3 * nodes;
  const auto node = [](int level, int corner) { return 4 * level + corner; };
  std::vector<Eigen::Vector3d> position(static_cast<std::size_t>(nodes));
  const std::array<std::array<double, 2>, 4> corners{
      {{0.0, 0.0}, {side, 0.0}, {side, side}, {0.0, side}}};
  for (int l = 0; l < levels; ++l)
    for (int c = 0; c < 4; ++c)
      position[static_cast<std::size_t>(node(l, c))] =
          Eigen::Vector3d(corners[c][0], corners[c][1], l * height);

  std::vector<std::array<int, 2>> bars;
  for (int l = 0; l < levels; ++l) {
    for (int c = 0; c < 4; ++c) bars.push_back({node(l, c), node(l, (c + 1) % 4)});
    bars.push_back({node(l, 0), node(l, 2)});  // horizontal diagonal (the other one is left open)
    if (l + 1 < levels) {
      for (int c = 0; c < 4; ++c) {
        bars.push_back({node(l, c), node(l + 1, c)});            // vertical
        bars.push_back({node(l, c), node(l + 1, (c + 1) % 4)});  // face diagonal
      }
    }
  }

  Triplets k, m, g;
  for (const auto& bar : bars) {
    const Eigen::Vector3d d =
        position[static_cast<std::size_t>(bar[1])] - position[static_cast<std::size_t>(bar[0])];
    const double length = d.norm();
    const Eigen::Vector3d e = d / length;
    const Eigen::Matrix3d kb = axial_stiffness / length * e * e.transpose();
    const double mb = line_density * length;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const double sign = a == b ? 1.0 : -1.0;
        const double mass_factor =
            a == b ? mb / 3.0 : mb / 6.0;  // consistent bar mass (1/6)[2 1; 1 2]
        for (int i = 0; i < 3; ++i) {
          m.emplace_back(3 * bar[static_cast<std::size_t>(a)] + i,
                         3 * bar[static_cast<std::size_t>(b)] + i, mass_factor);
          for (int j = 0; j < 3; ++j)
            k.emplace_back(3 * bar[static_cast<std::size_t>(a)] + i,
                           3 * bar[static_cast<std::size_t>(b)] + j, sign * kb(i, j));
        }
      }
  }
  std::mt19937 generator(7u);
  std::uniform_real_distribution<double> spread(0.8, 1.2);
  for (int p = 0; p < nodes; ++p) {
    const double lumped = 0.5 * spread(generator);
    for (int i = 0; i < 3; ++i) m.emplace_back(3 * p + i, 3 * p + i, lumped);
  }

  int row = 0;
  for (int c = 0; c < 4; ++c)
    for (int i = 0; i < 3; ++i) g.emplace_back(row++, 3 * node(0, c) + i, 1.0);
  {  // rigid link along the open top diagonal: eᵀ(u_b − u_a) = 0
    const int a = node(levels - 1, 1), b = node(levels - 1, 3);
    const Eigen::Vector3d e =
        (position[static_cast<std::size_t>(b)] - position[static_cast<std::size_t>(a)])
            .normalized();
    for (int i = 0; i < 3; ++i) {
      g.emplace_back(row, 3 * b + i, e(i));
      g.emplace_back(row, 3 * a + i, -e(i));
    }
    ++row;
  }
  {  // tie of two DOFs: u_x(a) − u_x(b) = 0
    const int a = node(levels / 2, 0), b = node(levels / 2, 2);
    g.emplace_back(row, 3 * a, 1.0);
    g.emplace_back(row, 3 * b, -1.0);
    ++row;
  }
  {  // slider: a mid-height node does not move along (1, 2, 2)/3
    const int a = node(levels / 3 + 1, 3);
    const Eigen::Vector3d d(1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0);
    for (int i = 0; i < 3; ++i) g.emplace_back(row, 3 * a + i, d(i));
    ++row;
  }
  {  // multi-point: u_y(a) = ½ (u_y(b) + u_y(c))
    const int a = node(levels - 2, 1), b = node(levels - 3, 1), c = node(levels - 1, 1);
    g.emplace_back(row, 3 * a + 1, 1.0);
    g.emplace_back(row, 3 * b + 1, -0.5);
    g.emplace_back(row, 3 * c + 1, -0.5);
    ++row;
  }

  ConstrainedEigenproblem problem;
  problem.stiffness = fromTriplets(n, n, k);
  problem.mass = fromTriplets(n, n, m);
  problem.constraint_jacobian = fromTriplets(row, n, g);
  return problem;
}

}  // namespace mastrom::modes::test_models
