// `mastrom modes CONFIG [--set k=v]… [-o FILE.h5] [--backend NAME]`: modal analysis of the mast
// locked at [modes] angle_deg, after the static equilibrium under the configured gravity
// (docs/theory.md §3; docs/user_guide.md §3). Prints a table (mode, Hz, damping ratio,
// participation, effective-mass fraction, label), writes /modes/* of docs/user_guide.md §5
// atomically, plus FILE.xdmf next to it: ParaView opens it to show every mode shape on the shell
// mesh with the modules as boxes (modes/xdmf_writer.hpp).
//
// MPI: `mpirun -n N mastrom modes …` runs the same command on every rank; the SLEPc backend shares
// one distributed eigenproblem between them (the model itself is small and built on every rank),
// the other backends solve serially on every rank. Only rank 0 prints and writes.
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/cli_common.hpp"
#include "cli/resource_estimates.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/mast_config.hpp"
#include "modes/linearize.hpp"
#include "modes/modal_analysis.hpp"
#include "modes/modes_file.hpp"
#include "modes/slepc_session.hpp"
#include "modes/xdmf_writer.hpp"

namespace mastrom::cli {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
constexpr const char* kDefaultOutput = "modes.h5";

struct ModesArguments {
  ConfigArguments config;
  std::string output;
  std::string backend;
  bool quiet = false;
  bool allow_unstable = false;
  bool allow_large = false;
};

void printTable(const modes::ModalAnalysis& a) {
  std::printf("%5s %16s %13s %18s %14s  %s\n", "mode", "frequency [Hz]", "damping [1]",
              "particip. [kg^.5m]", "eff. mass [1]", "label");
  for (int k = 0; k < a.eigen.converged; ++k) {
    std::printf("%5d %16.4f %13.4e %18.4e %14.4f  %s\n", k + 1, a.eigen.frequencies_hz(k),
                a.damping_ratio(k), a.participation(k), a.effective_mass_fraction(k),
                a.labels[static_cast<std::size_t>(k)].c_str());
  }
  std::printf(
      "  sum of effective-mass fractions %.4f (rotation about the joint axis, J = %.6g "
      "kg*m^2)\n",
      a.effective_mass_fraction.sum(), a.rotational_inertia_kg_m2);
}

void run(const ModesArguments& args) {
  Config config = loadConfig(args.config);
  if (!args.backend.empty()) {
    const std::optional<EigenBackendKind> kind = parseEigenBackendKind(args.backend);
    MASTROM_REQUIRE(kind.has_value(), InputError, "--backend = '", args.backend,
                    "' is not a backend (allowed: ", allowedEigenBackendNames(), ")");
    config.modes.backend = *kind;  // stored in the file's resolved config as what ran
  }
  const std::string path = args.output.empty() ? kDefaultOutput : args.output;

  const modes::SlepcSession session;  // MPI + PETSc + SLEPc for the life of the command
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const bool root = rank == 0;
  const bool talk = root && !args.quiet;
  if (root) {
    h5::checkWritable(path);  // before any work
    requireResources(modesEstimate(config), path, args.allow_large);
  }

  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const double angle = config.modes.angleRad();
  const fullorder::MastModel model =
      modes::buildLockedMast(fullorder::mastParametersFromConfig(config), angle);
  const Eigen::Vector3d g = model.parameters().gravity_m_s2;
  if (root) {
    std::printf(
        "mastrom modes: %d modules, %d DOFs, %d constraints, %d shell elements; joint "
        "locked at %.4g deg; gravity (%g, %g, %g) m/s^2\n",
        model.moduleCount(), model.dofCount(), model.constraintCount(),
        model.system().elementCount(), config.modes.angle_deg, g.x(), g.y(), g.z());
    std::fflush(stdout);
  }

  modes::LinearizationOptions linearization;
  linearization.stability =
      args.allow_unstable ? modes::StabilityPolicy::Record : modes::StabilityPolicy::Refuse;
  const modes::Linearization lin = modes::linearizeMast(model, linearization);
  if (talk) {
    std::fprintf(stderr, "modes: linearised in %.2f s%s\n", lin.linearize_time_s,
                 lin.equilibrium_solved ? " (static equilibrium under gravity)" : "");
    std::fprintf(stderr, "modes: solving for %d modes with %s on %d rank%s …\n", config.modes.count,
                 toString(config.modes.backend).c_str(), ranks, ranks == 1 ? "" : "s");
  }
  if (root && lin.equilibrium_solved)
    std::printf(
        "  static equilibrium: %d Newton iterations, relative force residual %.2e, "
        "joint force (%.4g, %.4g, %.4g) N, drive torque %.4g N*m\n",
        lin.statics.iterations, lin.statics.relative_force_residual,
        model.jointForce(lin.lambda).x(), model.jointForce(lin.lambda).y(),
        model.jointForce(lin.lambda).z(), model.driveTorque(lin.lambda));
  if (root) {
    std::printf(
        "  stability of the equilibrium (negative eigenvalues of the constrained tangent, "
        "counted by an LDL^T factorisation): %s\n",
        lin.stability.describe().c_str());
    if (!lin.stability.stable())
      std::printf(
          "  WARNING: unstable equilibrium, written as asked (--allow-unstable) and "
          "flagged in the file: these modes do not describe vibrations about it\n");
  }

  modes::EigenSolverOptions solver;
  solver.backend = config.modes.backend;
  solver.count = config.modes.count;
  const modes::ModalAnalysis analysis = modes::analyzeMast(model, lin, solver);
  const modes::EigenResult& eigen = analysis.eigen;
  MASTROM_REQUIRE(eigen.converged > 0, NumericalError, "eigen-solver ", toString(eigen.backend),
                  " ", toString(eigen.status), " with no converged pair: ", eigen.message,
                  "; nothing written");

  if (root) {
    std::printf(
        "  eigen-solver %s on %d rank%s: %s, %d of %d pairs in %.3f s, max projected "
        "residual %.1e\n",
        toString(eigen.backend).c_str(), ranks, ranks == 1 ? "" : "s",
        toString(eigen.status).c_str(), eigen.converged, eigen.requested, eigen.solve_time_s,
        analysis.residuals.maxCoeff());
    printTable(analysis);
    std::fflush(stdout);

    modes::ModesData data = modes::modesData(analysis, lin, angle);
    data.stability_checked = lin.stability.checked;
    data.stable = lin.stability.stable();
    data.instability = lin.stability.stable() ? "" : lin.stability.describe();
    h5::AtomicH5Writer writer(path);
    modes::writeModes(writer.file(), data, toToml(config), elapsed());
    const modes::VisualizationLayout layout =
        modes::writeModeVisualization(writer.file(), model.system(), lin.q, eigen.modes);
    writer.commit();
    const std::string xdmf = modes::xdmfPathFor(path);
    modes::writeXdmf(xdmf, std::filesystem::path(path).filename().string(), layout,
                     eigen.frequencies_hz, analysis.labels);
    std::printf(
        "wrote %s and %s (ParaView: open the .xdmf, Warp By Vector 'mode_shape'); wall "
        "time %.2f s\n",
        path.c_str(), xdmf.c_str(), elapsed());
    std::fflush(stdout);
  }
  MASTROM_REQUIRE(eigen.ok(), NumericalError, "eigen-solver ", toString(eigen.backend), " ",
                  toString(eigen.status), " (", eigen.converged, " of ", eigen.requested,
                  " pairs): ", eigen.message, "; the converged pairs were written to ", path);
}

}  // namespace

void registerModesCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "modes",
      "Modal analysis of the mast locked at [modes] angle_deg (static equilibrium under gravity, "
      "then the constrained eigenproblem); writes the modes (HDF5) and a ParaView XDMF");
  auto args = std::make_shared<ModesArguments>();
  addConfigArguments(*command, args->config);
  command->add_option("-o,--output", args->output,
                      "Result file (HDF5, /modes layout of docs/user_guide.md; FILE.xdmf is "
                      "written next to it); default: modes.h5");
  command
      ->add_option("--backend", args->backend,
                   "Eigen-solver backend, overrides [modes] backend: slepc, arpack or dense")
      ->type_name("NAME");
  command->add_flag("-q,--quiet", args->quiet, "No progress lines on stderr");
  command->add_flag("--allow-unstable", args->allow_unstable,
                    "Write the modes of an unstable equilibrium (refused otherwise), flagged in "
                    "the file (/modes attributes stable = 0, instability) and in the report");
  addAllowLargeFlag(*command, args->allow_large);
  command->footer("MPI: mpirun -n N mastrom modes ... distributes the SLEPc eigenproblem.");
  command->callback([args]() { run(*args); });
}

}  // namespace mastrom::cli
