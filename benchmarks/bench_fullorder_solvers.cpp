// One solve with the generalized-α iteration matrix of the default Scheme 3 mast (408 unknowns and
// 78 multipliers after the elimination), as the time integrator runs it once per Newton iteration
// with a factorisation kept for thousands of steps:
//  * SparseLu:       Eigen's supernodal SparseLU of the whole saddle matrix (the general route);
//  * SchurSupernodal: SchurComplement over SupernodalCholesky of the (1,1) block (the default);
//  * SchurSimplicial: the same Schur complement over Eigen's SimplicialLLT::solve, to show what the
//                     supernode panels gain.
//  * SaddleLdltSolve: SaddleLdlt, the LDLᵀ factor of the whole saddle matrix (the default route of
//                     long masts; 4 to 64 modules, with the megabytes of its packed panels, which a
//                     solve reads twice, and of the factor's entries as counters).
// The matrix is taken at a turned and slightly deformed state with elastic velocities. The
// benchmarks with an argument take the mast of that many modules: the two symmetric routes, of the
// iteration matrix and of the index-1 recovery's [M Gᵀ; G 0] (MassSaddle*), against the number of
// modules, with saddleLdltIsCheaper's choice as the counter `ldlt_chosen`.
#include <benchmark/benchmark.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <map>
#include <memory>
#include <random>

#include "common/config.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/mass_saddle_solver.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"
#include "fullorder/saddle_ldlt.hpp"
#include "fullorder/schur_complement.hpp"
#include "fullorder/supernodal_cholesky.hpp"

namespace {
using namespace mastrom;
using namespace mastrom::fullorder;

struct Problem {
  SparseMatrix h, a_symmetric, g;
  int n = 0, m = 0;
  Eigen::VectorXd rhs;
  // The state and coefficients the matrix was assembled at (for the factorisation's parts).
  EliminatedSystem* system = nullptr;
  Eigen::VectorXd q, v, lambda;
  IterationCoefficients coefficients;
};

Problem makeProblem(int modules) {
  Config c;
  c.mast.modules = modules;
  static std::map<int, std::unique_ptr<MastModel>> masts;
  static std::map<int, std::unique_ptr<EliminatedSystem>> systems;
  MastModel& mast =
      *(masts[modules] = std::make_unique<MastModel>(buildMast(mastParametersFromConfig(c))));
  EliminatedSystem& reduced =
      *(systems[modules] = std::make_unique<EliminatedSystem>(mast.system()));
  Problem out;
  out.n = reduced.dofCount();
  out.m = reduced.constraintCount();
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q = reduced.restrict(mast.rotatedReference(0.4)), v(out.n), lambda(out.m);
  for (int i = 0; i < out.n; ++i) {
    q[i] += 1e-7 * u(gen);
    v[i] = 1e-3 * u(gen);
  }
  for (int i = 0; i < out.m; ++i) lambda[i] = u(gen);
  // Coefficients of GeneralizedAlpha at ρ∞ = 0.9, h = 100 µs (docs/theory.md §5).
  const double r = 0.9, h = c.simulation.time_step_s;
  const double am = (2 * r - 1) / (r + 1), af = r / (r + 1), gamma = 0.5 + af - am;
  const double beta = 0.25 * (gamma + 0.5) * (gamma + 0.5);
  const double bp = (1 - am) / (h * h * beta * (1 - af)), gp = gamma / (h * beta);
  out.coefficients = {1.0, gp / bp, 1.0 / bp, 1.0};
  reduced.iterationMatrix(q, v, lambda, 0.0, out.coefficients, out.h);
  out.system = &reduced;
  out.q = q;
  out.v = v;
  out.lambda = lambda;
  const SparseMatrix a = out.h.topLeftCorner(out.n, out.n);
  out.a_symmetric = 0.5 * (a + SparseMatrix(a.transpose()));
  out.g = out.h.bottomLeftCorner(out.m, out.n);
  out.rhs.resize(out.n + out.m);
  for (Eigen::Index i = 0; i < out.rhs.size(); ++i) out.rhs[i] = u(gen);
  return out;
}

const Problem& problem(int modules = 4) {
  static std::map<int, Problem> problems;
  auto it = problems.find(modules);
  if (it == problems.end()) it = problems.emplace(modules, makeProblem(modules)).first;
  return it->second;
}

void SparseLu(benchmark::State& state) {
  const Problem& p = problem();
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(p.h);
  Eigen::VectorXd x(p.n + p.m);
  for (auto _ : state) {
    x = lu.solve(p.rhs);
    benchmark::DoNotOptimize(x.data());
  }
}
BENCHMARK(SparseLu)->Unit(benchmark::kMicrosecond);

void SchurSupernodal(benchmark::State& state) {
  const Problem& p = problem(state.range(0));
  SupernodalCholesky chol;
  if (!chol.compute(p.a_symmetric)) return state.SkipWithError("block not positive definite");
  SchurComplement schur;
  if (!schur.setup([&chol](double* x) { chol.solveInPlace(x); }, p.n, p.g))
    return state.SkipWithError("Schur complement singular");
  Eigen::VectorXd x(p.n + p.m);
  for (auto _ : state) {
    schur.solve(p.rhs, x);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["supernodes"] = chol.supernodeCount();
}
BENCHMARK(SchurSupernodal)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMicrosecond);

void SaddleLdltSolve(benchmark::State& state) {
  const Problem& p = problem(state.range(0));
  SaddleLdlt ldlt;
  if (!ldlt.compute(p.a_symmetric, p.g)) return state.SkipWithError("saddle LDLT refused");
  SupernodalCholesky chol;
  if (!chol.compute(p.a_symmetric)) return state.SkipWithError("block not positive definite");
  Eigen::VectorXd x(p.n + p.m);
  for (auto _ : state) {
    ldlt.solve(p.rhs, x);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["supernodes"] = ldlt.factor().supernodeCount();
  // What a solve streams through twice (forward, backward): the packed panels, against the
  // factor's own entries and diagonal.
  state.counters["panel_MB"] = 8e-6 * static_cast<double>(ldlt.factor().panelEntries());
  state.counters["factor_MB"] =
      8e-6 * static_cast<double>(ldlt.factorEntries() + static_cast<std::size_t>(p.n + p.m));
  state.counters["ldlt_chosen"] = saddleLdltIsCheaper(
      ldlt.factorEntries(), 2.0 * static_cast<double>(chol.factorEntries()), p.n, p.m);
}
BENCHMARK(SaddleLdltSolve)->Arg(4)->Arg(8)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);

/// The index-1 recovery's [M Gᵀ; G 0] solve by MassSaddleSolver on the route of range(1) (0: Schur
/// complement, 1: the whole matrix's LDLᵀ factor).
void MassSaddle(benchmark::State& state) {
  const Problem& p = problem(state.range(0));
  const bool whole = state.range(1) == 1;
  MassSaddleSolver solver(p.system->massMatrix(),
                          whole ? SaddleRoute::whole_ldlt : SaddleRoute::schur_complement);
  solver.setConstraintJacobian(p.g, 0.0);
  Eigen::VectorXd x(p.n + p.m);
  for (auto _ : state) {
    solver.solve(p.rhs, x);
    benchmark::DoNotOptimize(x.data());
  }
  MassSaddleSolver chosen(p.system->massMatrix());
  chosen.setConstraintJacobian(p.g, 0.0);
  state.counters["ldlt_chosen"] = chosen.solvesWhole();
}
BENCHMARK(MassSaddle)
    ->ArgNames({"modules", "whole"})
    ->ArgsProduct({{4, 8, 16}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

void SchurSimplicial(benchmark::State& state) {
  const Problem& p = problem();
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> llt(p.a_symmetric);
  if (llt.info() != Eigen::Success) return state.SkipWithError("block not positive definite");
  Eigen::VectorXd work(p.n);
  SchurComplement schur;
  const auto solve_a = [&](double* x) {
    Eigen::Map<Eigen::VectorXd> v(x, p.n);
    work = llt.solve(v);
    v = work;
  };
  if (!schur.setup(solve_a, p.n, p.g)) return state.SkipWithError("Schur complement singular");
  Eigen::VectorXd x(p.n + p.m);
  for (auto _ : state) {
    schur.solve(p.rhs, x);
    benchmark::DoNotOptimize(x.data());
  }
}
BENCHMARK(SchurSimplicial)->Unit(benchmark::kMicrosecond);

// What a refactorisation of the integrator costs (GeneralizedAlpha::factorize), in its parts: the
// iteration matrix's assembly (element tangents), the Cholesky factor of the (1,1) block, and the
// Schur complement's setup (one block solve per multiplier, then its dense factor). Against the
// solve above this is the price of renewing a stale factorisation instead of iterating once more.
void AssembleIterationMatrix(benchmark::State& state) {
  const Problem& p = problem();
  SparseMatrix h;
  for (auto _ : state) {
    p.system->iterationMatrix(p.q, p.v, p.lambda, 0.0, p.coefficients, h);
    benchmark::DoNotOptimize(h.valuePtr());
  }
}
BENCHMARK(AssembleIterationMatrix)->Unit(benchmark::kMicrosecond);

void CholeskyOfTheBlock(benchmark::State& state) {
  const Problem& p = problem();
  SupernodalCholesky chol;
  for (auto _ : state) {
    if (!chol.compute(p.a_symmetric)) return state.SkipWithError("block not positive definite");
  }
}
BENCHMARK(CholeskyOfTheBlock)->Unit(benchmark::kMicrosecond);

void SchurSetup(benchmark::State& state) {
  const Problem& p = problem();
  SupernodalCholesky chol;
  if (!chol.compute(p.a_symmetric)) return state.SkipWithError("block not positive definite");
  SchurComplement schur;
  for (auto _ : state) {
    if (!schur.setup([&chol](double* x) { chol.solveInPlace(x); }, p.n, p.g))
      return state.SkipWithError("Schur complement singular");
  }
}
BENCHMARK(SchurSetup)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
