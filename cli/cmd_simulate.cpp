// `mastrom simulate CONFIG [--set k=v]… [-o FILE.h5]`: one nonlinear full-order deployment
// (DESIGN §2, §5.2). Prints the model size and the metrics of DESIGN §1; writes the §5.3 layout
// atomically. The output path is checked before the run starts, so a bad path fails in milliseconds,
// not after minutes of integration.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/cli_common.hpp"
#include "cli/progress.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/results_io.hpp"

namespace mastrom::cli {

void registerSimulateCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "simulate", "Run one nonlinear full-order deployment (generalized-alpha, index-3 DAE)");
  auto args = std::make_shared<ConfigArguments>();
  auto output = std::make_shared<std::string>();
  auto quiet = std::make_shared<bool>(false);
  addConfigArguments(*command, *args);
  command->add_option("-o,--output", *output,
                      "Result file (HDF5, DESIGN 5.3 layout); default: [output] file of the config");
  command->add_flag("-q,--quiet", *quiet, "No progress lines on stderr");
  command->callback([args, output, quiet]() {
    const Config config = loadConfig(*args);
    const std::string path = output->empty() ? config.output.file : *output;
    h5::checkWritable(path);  // before minutes of work

    using namespace fullorder;
    MastModel model = buildMast(mastParametersFromConfig(config));
    DeploymentOptions options;
    options.integrator = integratorFromConfig(config);
    options.end_time_s = config.simulation.end_time_s;
    options.output_every = config.output.every;
    std::printf("mastrom simulate: %d modules, %d DOFs, %d constraints, %d shell elements, "
                "mass %.4f kg\n",
                model.moduleCount(), model.dofCount(), model.constraintCount(),
                model.system().elementCount(), model.totalMass());
    std::printf("  drive %s, %.1f deg in %.3f s; %.3f s simulated with dt = %.3g s (%ld steps)\n",
                toString(config.drive.law).c_str(), config.drive.angle_deg,
                config.drive.duration_s, options.end_time_s, options.integrator.time_step_s,
                static_cast<long>(std::ceil(options.end_time_s / options.integrator.time_step_s - 1e-9)));
    std::fflush(stdout);

    ProgressReporter reporter("simulate", 2.0, !*quiet);
    DeploymentStatistics stats;
    const DeploymentSeries series = simulateDeployment(
        model, options, &stats,
        [&reporter](double t, double end, const DeploymentStatistics& s) {
          char detail[160];
          std::snprintf(detail, sizeof detail, "t = %.4f / %.4f s, %.2f Newton it/step", t, end,
                        s.steps ? double(s.newton_iterations) / double(s.steps) : 0.0);
          reporter.update(t, end, detail);
        });
    const double wall = reporter.elapsedSeconds();
    const DeploymentMetrics metrics = computeMetrics(series, config.drive.duration_s);
    writeDeploymentFile(path, series, metrics, toToml(config), wall, ResultSource::FullOrder);

    std::printf("  wall time %.2f s = %.3f x simulated time; %.2f Newton iterations/step, "
                "%ld factorisations, max |Phi| %.2e\n",
                wall, wall / options.end_time_s,
                double(stats.newton_iterations) / double(std::max(1L, stats.steps)),
                stats.factorizations, stats.max_constraint_residual);
    std::printf("metrics (DESIGN 1; the file stores SI units):\n");
    printDeploymentMetrics(metrics);
    std::printf("wrote %s\n", path.c_str());
  });
}

}  // namespace mastrom::cli
