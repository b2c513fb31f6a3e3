// The lane-parallel shell force of time stepping (fullorder/shell_force_batch.hpp) against the
// element's elastic and damping forces of the iteration matrix and the energy balance
// (ShellElement::elasticForce + dampingForce), which test_shell_element.cpp checks against ∂U/∂e by
// finite differences. Both call the same point function (shellPointForce); the batch reaches the fields
// through monomial coefficients instead of the nodal derivative table (the same polynomials, other
// roundings; see MonomialCoefficientsReproduceTheShapeFunctions), and the order of additions and
// the use of fused multiply-adds differ, so they agree to round-off: 1e-13 of the force scale (each
// component is a sum of ~16 points × 5 fields of terms of that scale, each with relative error
// ~1e-16).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "common/error.hpp"
#include "fullorder/shell_force_batch.hpp"
#include "shell_test_fixtures.hpp"

namespace mastrom::fullorder {
namespace {

using testing::aluminium;
using testing::cylinderReference;
using testing::randomlyDeformed;

struct Fixture {
  std::vector<ShellElement> elements;
  std::vector<std::array<int, 36>> dofs;
  Eigen::VectorXd q, qdot;
};

/// `count` cylinder panels sharing one shape table, each with its own coordinates in q (the global
/// vector is a concatenation in reverse order, so dof lists are not the identity), with sections
/// that differ per element — thickness, modulus and damping, some undamped — and large random
/// deformations and velocities.
Fixture makeFixture(int count, std::mt19937& gen, bool any_damping, int gauss_order = 4) {
  const double radius = 0.041, a = 0.025, b = 2.0 * M_PI * radius / 8.0;
  const auto table = makeShellShapeTable(a, b, gauss_order);
  Fixture fx;
  fx.q.resize(36 * count);
  fx.qdot.resize(36 * count);
  std::uniform_real_distribution<double> ud(0.5, 2.0);
  for (int k = 0; k < count; ++k) {
    const Vec36 e0 = cylinderReference(radius, a, b, 0.4 * k);
    ShellSection s = aluminium(0.002 * ud(gen), (any_damping && k % 3 != 1) ? 1e-4 * ud(gen) : 0.0);
    s.youngs_modulus_pa *= ud(gen);
    fx.elements.emplace_back(table, e0, s);
    std::array<int, 36> d{};
    const int offset = 36 * (count - 1 - k);
    for (int i = 0; i < 36; ++i) d[static_cast<std::size_t>(i)] = offset + i;
    fx.dofs.push_back(d);
    fx.q.segment<36>(offset) = randomlyDeformed(e0, gen, 0.05 * a, 0.05);
    fx.qdot.segment<36>(offset) = Vec36::Random();
  }
  return fx;
}

std::vector<const ShellElement*> pointers(const Fixture& fx) {
  std::vector<const ShellElement*> p;
  for (const ShellElement& e : fx.elements) p.push_back(&e);
  return p;
}

void expectMatchesElementLoop(int count, bool any_damping, int gauss_order = 4) {
  std::mt19937 gen(1234u + static_cast<unsigned>(count));
  const Fixture fx = makeFixture(count, gen, any_damping, gauss_order);
  const ShellForceBatch batch(pointers(fx), fx.dofs);
  ASSERT_EQ(batch.elementCount(), count);
  std::vector<double> per_element;
  batch.internalForces(fx.q.data(), fx.qdot.data(), per_element);
  Eigen::VectorXd global = Eigen::VectorXd::Constant(fx.q.size(), 1.0);
  batch.subtractInternalForces(fx.q.data(), fx.qdot.data(), global.data());
  for (int k = 0; k < count; ++k) {
    const int offset = fx.dofs[static_cast<std::size_t>(k)][0];
    const Vec36 e = fx.q.segment<36>(offset), edot = fx.qdot.segment<36>(offset);
    Vec36 elastic, damping;
    fx.elements[static_cast<std::size_t>(k)].elasticForce(e, elastic);
    fx.elements[static_cast<std::size_t>(k)].dampingForce(e, edot, damping);
    const Vec36 reference = elastic + damping;
    const Eigen::Map<const Vec36> batched(per_element.data() + 36 * k);
    const double scale = reference.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    EXPECT_LT((batched - reference).cwiseAbs().maxCoeff(), 1e-13 * scale) << "element " << k;
    // The global form subtracts the same numbers at the element's dofs.
    const Vec36 from_global = Vec36::Ones() - global.segment<36>(offset);
    EXPECT_LT((from_global - reference).cwiseAbs().maxCoeff(), 1e-13 * scale) << "element " << k;
  }
}

TEST(ShellForceBatch, EqualsTheElementLoopForAFullChunk) {
  expectMatchesElementLoop(ShellForceBatch::kLanes, true);
}

TEST(ShellForceBatch, EqualsTheElementLoopWithAPartialLastChunk) {
  expectMatchesElementLoop(2 * ShellForceBatch::kLanes + 3, true);  // padding lanes never leak
}

TEST(ShellForceBatch, EqualsTheElementLoopWithoutDamping) {
  expectMatchesElementLoop(5, false);  // the undamped kernel (velocities never read)
}

TEST(ShellForceBatch, EqualsTheElementLoopWithAFiveByFiveRule) {
  expectMatchesElementLoop(ShellForceBatch::kLanes + 1, true, 5);  // the kernel is generic in n
}

TEST(ShellForceBatch, MonomialCoefficientsReproduceTheShapeFunctions) {
  // The kernel evaluates the fields from monomial coefficients (shellMonomialCoefficients), so
  // Σ_i C(k, i) ∂(ξ^p_i η^q_i) with the chain rule must give evaluateShellShape's values and
  // derivatives. Both sides are sums of at most 12 products of a few rounded factors, so each is
  // within ~16 ε · Σ_i |term_i| of the exact value: the tolerance is 32 ε · Σ_i |term_i|.
  const double a = 0.025, b = 0.032;
  const ShellMonomialMatrix c = shellMonomialCoefficients(a, b);
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> ud(-1.0, 1.0);
  const auto derivative = [](int power, int order, double s) {  // ∂^order(s^power)/∂s^order
    double v = 1.0;
    for (int o = 0; o < order; ++o) v *= power - o;
    for (int e = 0; e < power - order; ++e) v *= s;
    return power < order ? 0.0 : v;
  };
  const int xi_order[6] = {0, 1, 0, 2, 1, 0}, eta_order[6] = {0, 0, 1, 0, 1, 2};
  for (int trial = 0; trial < 20; ++trial) {
    const double xi = ud(gen), eta = ud(gen);
    const ShellShapeValues v = evaluateShellShape(xi, eta, a, b);
    const Vec12* expected[6] = {&v.n, &v.nx, &v.ny, &v.nxx, &v.nxy, &v.nyy};
    for (int d = 0; d < 6; ++d) {
      const double chain =
          std::pow(2.0 / a, xi_order[d]) * std::pow(2.0 / b, eta_order[d]);  // ∂ξ/∂x = 2/a
      for (int k = 0; k < 12; ++k) {
        double sum = 0.0, magnitude = 0.0;
        for (int i = 0; i < 12; ++i) {
          const double term = c[k][i] * chain *
                              derivative(kShellMonomialXiPower[i], xi_order[d], xi) *
                              derivative(kShellMonomialEtaPower[i], eta_order[d], eta);
          sum += term;
          magnitude += std::abs(term);
        }
        const double tol = 32.0 * std::numeric_limits<double>::epsilon() * magnitude;
        EXPECT_NEAR(sum, (*expected[d])[k], tol) << "function " << k << ", derivative " << d;
      }
    }
  }
}

TEST(ShellForceBatch, TheReferenceStateIsExactlyStressFree) {
  // The batch takes its reference metric and curvature from the kernel itself (constructor), so at
  // e₀ every strain cancels to the last bit and the force is exactly zero — for a partial chunk,
  // with damping, and with either Gauss rule. (The element loop's own reference values come from
  // the nodal derivative table; against those the monomial path would leave round-off.)
  for (int order : {4, 5}) {
    std::mt19937 gen(77);
    Fixture fx = makeFixture(ShellForceBatch::kLanes + 3, gen, true, order);
    for (std::size_t k = 0; k < fx.elements.size(); ++k)
      fx.q.segment<36>(fx.dofs[k][0]) = fx.elements[k].referenceCoordinates();
    fx.qdot.setZero();
    const ShellForceBatch batch(pointers(fx), fx.dofs);
    std::vector<double> forces;
    batch.internalForces(fx.q.data(), fx.qdot.data(), forces);
    double largest = 0.0;
    for (double f : forces) largest = std::max(largest, std::abs(f));
    EXPECT_EQ(largest, 0.0) << order << " x " << order << " rule";
  }
}

TEST(ShellForceBatch, ALaneDoesNotDependOnItsNeighbours) {
  // Element 2 alone and inside a chunk of others give bit-identical forces (determinism of the
  // full order must not depend on how elements are grouped).
  std::mt19937 gen(99);
  const Fixture fx = makeFixture(ShellForceBatch::kLanes, gen, true);
  const ShellForceBatch all(pointers(fx), fx.dofs);
  const ShellForceBatch one({&fx.elements[2]}, {fx.dofs[2]});
  std::vector<double> f_all, f_one;
  all.internalForces(fx.q.data(), fx.qdot.data(), f_all);
  one.internalForces(fx.q.data(), fx.qdot.data(), f_one);
  for (int i = 0; i < 36; ++i)
    EXPECT_EQ(f_all[static_cast<std::size_t>(72 + i)], f_one[static_cast<std::size_t>(i)]);
}

TEST(ShellForceBatch, NamesTheElementWithADegenerateSurface) {
  std::mt19937 gen(7);
  Fixture fx = makeFixture(10, gen, true);
  // Element 9 (last chunk, lane 1) collapsed to a point: g_x = g_y = 0 everywhere.
  const int offset = fx.dofs[9][0];
  fx.q.segment<36>(offset).setZero();
  const ShellForceBatch batch(pointers(fx), fx.dofs);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(fx.q.size());
  try {
    batch.subtractInternalForces(fx.q.data(), fx.qdot.data(), f.data());
    FAIL() << "no error for a degenerate element";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("shell element 9"), std::string::npos) << e.what();
  }
}

TEST(ShellForceBatch, RefusesElementsWithDifferentShapeTables) {
  const ShellElement a(0.02, 0.03, cylinderReference(0.041, 0.02, 0.03), aluminium(0.002));
  const ShellElement b(0.02, 0.03, cylinderReference(0.041, 0.02, 0.03), aluminium(0.002));
  std::array<int, 36> d{};
  EXPECT_THROW(ShellForceBatch({&a, &b}, {d, d}), InputError);  // equal sides, separate tables
  EXPECT_THROW(ShellForceBatch({&a}, {d, d}), InputError);      // counts differ
}

}  // namespace
}  // namespace mastrom::fullorder
