// Scaling of the modal analysis (benchmark): wall time of the 20 lowest
// modes against the DOF count for the three backends, on Scheme 1 (2 modules, 1 interface) with an
// increasingly refined interface mesh, up to ≥ 10⁵ unknowns for SLEPc and ARPACK. Goal: 10⁵
// unknowns in ≤ 30 s on one core; under `mpirun -n 2` the SLEPc rows give the 2-rank speed-up.
//
//   bench_modes_scaling [--backends slepc,arpack,dense] [--min-dofs N] [--max-dofs N] [--count K]
//   [PETSc options]
//
// A plain program (not Google Benchmark: one solve of a large model is the unit). Prints one row
// per (mesh, backend): DOFs, constraints, the times of building the model (buildMast), of the
// linearisation (equilibrium check + assembly of K, M, G, C), of the eigen-solve and of the
// per-mode quantities, the first frequency and the largest projected residual. Only rank 0 prints;
// every rank builds the model.
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "fullorder/mast_config.hpp"
#include "modes/linearize.hpp"
#include "modes/modal_analysis.hpp"
#include "modes/slepc_session.hpp"

namespace {

using namespace mastrom;

struct Mesh {
  int axial, circumferential;
};

bool wants(const std::string& list, const std::string& name) {
  return ("," + list + ",").find("," + name + ",") != std::string::npos;
}

}  // namespace

int main(int argc, char** argv) {
  const modes::SlepcSession session(&argc, &argv);  // -log_view, -eps_view … reach PETSc
  std::string backends = "slepc,arpack,dense";
  long max_dofs = 110000, min_dofs = 0;
  int count = 20;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--backends")) backends = argv[i + 1];
    if (!std::strcmp(argv[i], "--max-dofs")) max_dofs = std::atol(argv[i + 1]);
    if (!std::strcmp(argv[i], "--min-dofs")) min_dofs = std::atol(argv[i + 1]);
    if (!std::strcmp(argv[i], "--count")) count = std::atoi(argv[i + 1]);
  }
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);

  const std::vector<Mesh> meshes{{2, 8},   {4, 16},   {8, 32},   {12, 48}, {16, 64},
                                 {24, 96}, {32, 128}, {40, 160}, {56, 200}};
  if (rank == 0)
    std::printf(
        "# Scheme 1, %d lowest modes, %d rank%s\n# %8s %8s %8s %8s %8s %11s %9s %8s %9s "
        "%14s %9s\n",
        count, ranks, ranks == 1 ? "" : "s", "mesh", "dofs", "constr", "backend", "build_s",
        "linearize_s", "solve_s", "post_s", "total_s", "f1_hz", "max_res");
  for (const Mesh& mesh : meshes) {
    Config c;
    c.mast.modules = 2;
    c.interface.elements_axial = mesh.axial;
    c.interface.elements_circumferential = mesh.circumferential;
    const long dofs = 24 + 9L * (mesh.axial + 1) * mesh.circumferential;
    if (dofs > max_dofs) break;
    if (dofs < min_dofs) continue;
    const auto now = [] { return std::chrono::steady_clock::now(); };
    const auto seconds = [](auto a, auto b) {
      return std::chrono::duration<double>(b - a).count();
    };
    const auto t0 = now();
    const fullorder::MastModel model =
        modes::buildLockedMast(fullorder::mastParametersFromConfig(c), 0.0);
    const auto t1 = now();
    const modes::Linearization lin = modes::linearizeMast(model);
    const auto t2 = now();
    const double build_s = seconds(t0, t1), linearize_s = seconds(t1, t2);
    for (EigenBackendKind backend :
         {EigenBackendKind::Slepc, EigenBackendKind::Arpack, EigenBackendKind::Dense}) {
      if (!wants(backends, toString(backend))) continue;
      if (backend == EigenBackendKind::Dense && dofs > modes::kDenseBackendMaxDofs) continue;
      modes::ModalAnalysisOptions options;
      options.solver.backend = backend;
      options.solver.count = count;
      options.end_body = model.endModule();
      // runModalAnalysis in two timed halves: the eigen-solve (with the cluster margin) and the
      // per-mode quantities.
      modes::EigenSolverOptions solver = options.solver;
      solver.count = count + modes::kClusterMargin;
      const auto t3 = now();
      modes::EigenResult eigen = modes::solveConstrainedEigenproblem(lin.problem, solver);
      const auto t4 = now();
      const modes::ModalAnalysis a =
          modes::computeModalQuantities(model.system(), lin, std::move(eigen), options);
      const auto t5 = now();
      const double solve_s = seconds(t3, t4), post_s = seconds(t4, t5);
      if (rank == 0) {
        char name[32];
        std::snprintf(name, sizeof name, "%dx%d", mesh.axial, mesh.circumferential);
        std::printf("  %8s %8d %8d %8s %8.3f %11.3f %9.3f %8.3f %9.3f %14.6f %9.1e%s\n", name,
                    model.dofCount(), model.constraintCount(), toString(backend).c_str(), build_s,
                    linearize_s, solve_s, post_s, build_s + linearize_s + solve_s + post_s,
                    a.eigen.converged ? a.eigen.frequencies_hz(0) : 0.0,
                    a.eigen.converged ? a.residuals.maxCoeff() : 0.0,
                    a.eigen.ok() ? "" : ("  (" + a.eigen.message + ")").c_str());
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
