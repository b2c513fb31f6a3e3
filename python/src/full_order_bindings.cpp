// mastrom.simulate (the nonlinear full-order deployment) and mastrom.modes (the modes of the locked
// mast): the library functions behind `mastrom simulate` and `mastrom modes`, with the GIL released
// while they run.
#include <pybind11/stl.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/configured_deployment.hpp"
#include "fullorder/interface_stress_io.hpp"
#include "fullorder/results_io.hpp"
#include "fullorder/run_footprint.hpp"
#include "modes/mast_modes.hpp"
#include "python/src/arrays.hpp"
#include "python/src/bindings.hpp"
#include "python/src/runtime.hpp"
#include "rom/studies/default_output_step.hpp"

namespace py = pybind11;

namespace mastrom::python {
namespace {

/// The command line's default: two threads where the machine has two cores (results are
/// bit-identical for any count).
int defaultThreads() { return std::thread::hardware_concurrency() >= 2 ? 2 : 1; }

/// progress=True prints a line on stderr like the command line; a callable gets (t, end_time).
py::object progressCallback(const py::object& progress) {
  if (progress.is_none() || (py::isinstance<py::bool_>(progress) && !progress.cast<bool>()))
    return py::none();
  if (py::isinstance<py::bool_>(progress)) {
    return py::cpp_function([](double t, double end) {
      std::fprintf(stderr, "simulate: t = %.4f / %.4f s (%.0f %%)\n", t, end,
                   end > 0 ? 100.0 * t / end : 100.0);
    });
  }
  if (!PyCallable_Check(progress.ptr()))
    throw py::type_error("mastrom.simulate: progress= takes a bool or a callable(t, end_time)");
  return progress;
}

py::dict simulate(const Config& given, const py::object& progress, std::optional<int> threads,
                  const std::optional<std::string>& path) {
  PythonPoller poller(progressCallback(progress), 0.5);
  // An unset output.step is chosen as `mastrom simulate` chooses it (docs/theory.md §5.4a).
  Config config = given;
  if (!config.output.step_s && config.simulation.adaptive) {
    py::gil_scoped_release release;
    const std::unique_lock<std::mutex> lock = lockEigenSolvers(true);
    rom::resolveFullOrderOutputStep(
        config, fullorder::resultBytesPerSample(fullorder::mastSize(config), true));
  }
  fullorder::ConfiguredDeploymentOptions options;
  options.threads = threads.value_or(defaultThreads());
  options.progress = [&poller](double t, double end, const fullorder::DeploymentStatistics&) {
    poller.poll(t >= end, t, end);
  };
  std::optional<fullorder::ConfiguredDeployment> run;
  try {
    py::gil_scoped_release release;
    if (path) h5::checkWritable(*path);  // before minutes of work, as the command line does
    const auto start = std::chrono::steady_clock::now();
    run = fullorder::runConfiguredDeployment(config, options);
    if (path) {
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      fullorder::writeDeploymentFileWithStresses(*path, run->series, run->metrics, toToml(config),
                                                 wall, run->stresses,
                                                 config.material.yield_strength_pa);
    }
  } catch (const PythonPoller::Aborted&) {
    poller.rethrowIfAborted();
  }
  py::dict result = seriesDict(std::move(run->series));
  py::dict metrics = metricsDict(run->metrics);
  // The interface stresses' metrics, named as in the file's /metrics (docs/theory.md §6).
  if (run->stresses) {
    for (const auto& [name, value] : fullorder::interfaceStressMetricAttributes(
             *run->stresses, config.material.yield_strength_pa))
      metrics[py::str(name)] = value;
  }
  result["metrics"] = metrics;
  py::dict stats;
  stats["steps"] = run->statistics.steps;
  stats["newton_iterations"] = run->statistics.newton_iterations;
  stats["factorizations"] = run->statistics.factorizations;
  stats["max_constraint_residual"] = run->statistics.max_constraint_residual;
  stats["dofs"] = run->dofs;
  stats["constraints"] = run->constraints;
  stats["shell_elements"] = run->shell_elements;
  result["statistics"] = stats;
  result["source"] = "full-order";
  result["config"] = config;
  return result;
}

py::dict modes(const Config& config, const std::optional<std::string>& backend) {
  Config c = config;
  if (backend) {
    const std::optional<EigenBackendKind> kind = parseEigenBackendKind(*backend);
    MASTROM_REQUIRE(kind.has_value(), InputError, "backend = '", *backend,
                    "' is not a backend (allowed: ", allowedEigenBackendNames(), ")");
    c.modes.backend = *kind;
  }
  std::optional<modes::MastModes> solved;
  {
    py::gil_scoped_release release;
    // PETSc always: the stability check of the linearisation factorises with MUMPS.
    const std::unique_lock<std::mutex> lock = lockEigenSolvers(true);
    solved = modes::solveMastModes(c);
  }
  const modes::ModesData& d = solved->data;
  py::dict r;
  r["frequencies_hz"] = copyVector(d.frequency_hz);
  r["damping_ratio"] = copyVector(d.damping_ratio);
  r["participation"] = copyVector(d.participation);
  r["effective_mass_fraction"] = copyVector(d.effective_mass_fraction);
  r["centrifugal_participation"] = copyVector(d.centrifugal_participation);
  r["translation_participation"] = copyMatrix(d.translation_participation);
  r["coriolis"] = copyMatrix(d.coriolis);
  r["shapes"] = copyMatrix(d.shapes);
  r["end_rotation"] = copyMatrix(d.end_rotation);
  r["end_displacement"] = copyMatrix(d.end_displacement);
  r["residual"] = copyVector(d.residual);
  r["reference"] = copyVector(d.reference);
  r["labels"] = d.labels;
  r["angle_rad"] = d.angle_rad;
  r["rotational_inertia_kg_m2"] = d.rotational_inertia_kg_m2;
  r["backend"] = d.backend;
  r["status"] = d.status;
  r["equilibrium_solved"] = solved->equilibrium_solved;
  r["solve_time_s"] = solved->solve_time_s;
  r["config"] = c;
  return r;
}

}  // namespace

void bindFullOrder(py::module_& m) {
  m.def(
      "simulate", &simulate, py::arg("config"), py::arg("progress") = false,
      py::arg("threads") = py::none(), py::arg("path") = py::none(),
      R"doc(One nonlinear full-order deployment (generalized-alpha, index-3 DAE), as `mastrom simulate`.

config: a Config. progress: False (silent), True (a line on stderr every half second) or a callable
progress(t, end_time) [s, s] called about twice per second of wall time; an exception it raises
stops the run. threads: threads for the shell element forces, at most (default: 2 on a machine
with two cores or more; results are bit-identical for any count; steps run on one thread where
that is measured faster, on cores shared with other work). path: also write the result file there
(HDF5, the layout of `mastrom simulate -o`; its writability is checked before the run). The GIL is
released while it runs; Ctrl-C interrupts it.

Returns a dict of NumPy float64 arrays, N = the output instants (adaptive steps: every output.step,
chosen from the response where it is unset as `mastrom simulate` chooses it, docs/theory.md §5.4a;
fixed steps: every output.every-th step plus the first and the last), keyed as the datasets of the
result file:
  "time" (N,) s; "drive/angle", "drive/rate", "drive/acceleration" (N,) rad, rad/s, rad/s^2;
  "end/angular_acceleration" (N, 3) rad/s^2 (global; Z = the paper's absolute one);
  "end/relative_angular_acceleration" (N,) rad/s^2 (Z minus the drive's acceleration);
  "end/position" (N, 3) m; "end/acceleration" (N, 3) m/s^2 (last module's centroid);
  "joint/force" (N, 3) N (base joint on module 1, global); "joint/torque" (N,) N*m (drive torque);
  "solver/newton_iterations" (N,) int32; "solver/constraint_residual" (N,);
plus "metrics" (dict of floats, SI: peak_abs_end_angular_acceleration [rad/s^2], … , settled
[bool], peak_von_mises_interface_K [Pa] per interface and, with material.yield_strength, the
margins of safety), "statistics" (steps, Newton iterations, factorisations, model size), "source"
("full-order") and "config". Raises InputError for a record that ends before the drive and
NumericalError (a RuntimeError) when a step fails.)doc");
  m.def(
      "modes", &modes, py::arg("config"), py::arg("backend") = py::none(),
      R"doc(Modes of the mast locked at modes.angle_deg (static equilibrium under gravity first), as `mastrom modes`.

config: a Config (modes.count modes, modes.backend unless `backend` = "slepc", "arpack" or
"dense" is given). The first call with the SLEPc backend initialises PETSc/SLEPc (≈ 0.4 s). The GIL
is released while it runs.

Returns a dict, k = modes.count, n = degrees of freedom:
  "frequencies_hz" (k,) Hz; "damping_ratio" (k,); "participation" (k,) kg^0.5*m (forcing by the
  joint's angular acceleration); "effective_mass_fraction" (k,); "centrifugal_participation" (k,)
  kg^0.5*m; "translation_participation" (k, 3) kg^0.5; "coriolis" (k, k); "shapes" (k, n)
  mass-normalised (shapes M shapes^T = I); "end_rotation" (k, 3) rad/(kg^0.5*m);
  "end_displacement" (k, 3) kg^-0.5; "residual" (k,); "reference" (n,) the linearisation point;
  "labels" (list of k str); "angle_rad", "rotational_inertia_kg_m2" (kg*m^2), "backend", "status",
  "equilibrium_solved", "solve_time_s", "config".
Raises NumericalError when the eigen-solver does not deliver the k pairs.)doc");
}

}  // namespace mastrom::python
