// Cost of one ANCF shell element evaluation (docs/theory.md §2.2: element force + tangent in µs per
// element).
// Element: one panel of the default interface mesh (R = 41 mm, L = 50 mm, 2 × 8 elements), 5×5 Gauss,
// at a randomly deformed state.
#include <cmath>
#include <random>
#include <vector>
#include <array>

#include <benchmark/benchmark.h>

#include "fullorder/shell_element.hpp"
#include "fullorder/shell_force_batch.hpp"

namespace {
using namespace mastrom::fullorder;

Vec36 panel(double radius, double a, double b) {
  Vec36 e;
  const double phi[2] = {0.0, b / radius};
  const double x[2] = {0.0, a};
  const int corner_x[4] = {0, 1, 1, 0}, corner_phi[4] = {0, 0, 1, 1};
  for (int c = 0; c < 4; ++c) {
    const double p = phi[corner_phi[c]];
    e.segment<3>(9 * c) << x[corner_x[c]], radius * std::cos(p), radius * std::sin(p);
    e.segment<3>(9 * c + 3) << 1, 0, 0;
    e.segment<3>(9 * c + 6) << 0, -std::sin(p), std::cos(p);
  }
  return e;
}

struct Setup {
  ShellElement element;
  Vec36 e, edot;
  explicit Setup(int gauss)
      : element(0.025, 2 * M_PI * 0.041 / 8, panel(0.041, 0.025, 2 * M_PI * 0.041 / 8),
                ShellSection{0.002, 70e9, 0.33, 2700.0, 1e-5}, gauss) {
    std::mt19937 gen(1);
    std::uniform_real_distribution<double> ud(-1e-4, 1e-4);
    e = element.referenceCoordinates();
    for (int i = 0; i < 36; ++i) e[i] += ud(gen), edot[i] = ud(gen);
  }
};

void BM_ElasticForce(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  Vec36 f;
  for (auto _ : state) {
    s.element.elasticForce(s.e, f);
    benchmark::DoNotOptimize(f.data());
  }
}
// The damping force alone (the energy balance's dissipated power).
void BM_DampingForce(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  Vec36 f;
  for (auto _ : state) {
    s.element.dampingForce(s.e, s.edot, f);
    benchmark::DoNotOptimize(f.data());
  }
}
// The elastic + Kelvin–Voigt force as the full order evaluates it (the time-stepping hot path): 16
// copies of the element (one interface of the default mesh) in one ShellForceBatch, 8 elements per
// SIMD pass. Time per element.
void BM_InternalForceBatched(benchmark::State& state) {
  constexpr int kElements = 16;
  const auto table = mastrom::fullorder::makeShellShapeTable(0.025, 2 * M_PI * 0.041 / 8,
                                                             static_cast<int>(state.range(0)));
  const Setup s(static_cast<int>(state.range(0)));
  std::vector<ShellElement> elements;
  std::vector<std::array<int, 36>> dofs;
  Eigen::VectorXd q(36 * kElements), qdot(36 * kElements), f(36 * kElements);
  for (int k = 0; k < kElements; ++k) {
    elements.emplace_back(table, s.element.referenceCoordinates(), s.element.section());
    std::array<int, 36> d{};
    for (int i = 0; i < 36; ++i) d[static_cast<std::size_t>(i)] = 36 * k + i;
    dofs.push_back(d);
    q.segment<36>(36 * k) = s.e;
    qdot.segment<36>(36 * k) = s.edot;
  }
  std::vector<const ShellElement*> members;
  for (const ShellElement& e : elements) members.push_back(&e);
  const ShellForceBatch batch(members, dofs);
  for (auto _ : state) {
    f.setZero();
    batch.subtractInternalForces(q.data(), qdot.data(), f.data());
    benchmark::DoNotOptimize(f.data());
  }
  state.SetItemsProcessed(state.iterations() * kElements);  // items/s = elements/s
}
void BM_ElasticForceAndTangent(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  Vec36 f;
  Mat36 k;
  for (auto _ : state) {
    s.element.elasticForceAndTangent(s.e, f, k);
    benchmark::DoNotOptimize(k.data());
  }
}
void BM_DampingForceAndTangents(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  Vec36 f;
  Mat36 c, kd;
  for (auto _ : state) {
    s.element.dampingForceAndTangents(s.e, s.edot, f, c, kd);
    benchmark::DoNotOptimize(kd.data());
  }
}
// The element's block of a refactorised iteration matrix: the two tangents above combined
// (MultibodySystem's assembly before), against the one-pass ShellElement::iterationTangent.
void BM_TangentsCombined(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  Vec36 f;
  Mat36 k, c, kd, block;
  for (auto _ : state) {
    s.element.elasticForceAndTangent(s.e, f, k);
    s.element.dampingForceAndTangents(s.e, s.edot, f, c, kd);
    block.noalias() = 0.5 * (k + kd) + 0.25 * c;
    benchmark::DoNotOptimize(block.data());
  }
}
void BM_IterationTangent(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  Mat36 block;
  for (auto _ : state) {
    s.element.iterationTangent(s.e, s.edot, 0.5, 0.25, block);
    benchmark::DoNotOptimize(block.data());
  }
}
BENCHMARK(BM_TangentsCombined)->Arg(4)->Arg(5)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_IterationTangent)->Arg(4)->Arg(5)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ElasticForce)->Arg(3)->Arg(4)->Arg(5)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DampingForce)->Arg(4)->Arg(5)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_InternalForceBatched)->Arg(4)->Arg(5)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ElasticForceAndTangent)->Arg(3)->Arg(4)->Arg(5)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DampingForceAndTangents)->Arg(5)->Unit(benchmark::kMicrosecond);
}  // namespace

BENCHMARK_MAIN();
