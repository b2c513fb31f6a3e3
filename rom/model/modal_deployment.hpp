// One deployment from the modal model (docs/theory.md §4.1): every mode is a damped oscillator
// driven by the drive law's θ̈ and θ̇² (and gravity), stepped exactly under first-order-hold
// forcing (rom/model/modal_oscillator.hpp), then mapped to the same outputs as the full order
// (fullorder/deployment_result.hpp) — so `computeMetrics`, the result file and every comparison
// are shared. Cost: O(modes × samples) — the drive law is sampled once, then each step is one pass
// over the modes (rom/model/modal_stepping.hpp) and each output one fused contraction (24 rows × modes,
// AVX2 + FMA where the CPU has them: rom/model/modal_deployment.cpp).
#pragma once

#include <cstddef>
#include <functional>

#include "common/config.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/drive_law.hpp"
#include "rom/model/modal_model.hpp"

namespace mastrom::rom {

struct ModalDeploymentOptions {
  double end_time_s = 8.0;
  double step_s = 1e-4;          ///< sample spacing of the outputs (and of the exact stepping)
  bool coriolis_coupling = false;  ///< include −2θ̇ΦᵀMΩΦη̇ (lagged one step; O(θ̇/ω₁) ≈ 1e-4 here)
};

/// Simulate a deployment with the modal model. The series starts at t = 0 with the mast at rest in
/// the reference configuration rotated to θ(0).
fullorder::DeploymentSeries simulateModalDeployment(const ModalModel& model,
                                                    const fullorder::DriveLaw& drive,
                                                    const ModalDeploymentOptions& options);

struct SampledDrive;  // rom/model/modal_stepping.hpp
namespace stepping_detail {
struct ForcingScalars;
}

/// Called at every output sample n with the modal state there and the forcing scalars of the
/// drive's value at t_n: what the stress recovery records in the same pass as the series or the
/// metrics (rom/model/modal_stress_response.hpp).
using ModalSampleObserver =
    std::function<void(long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                       const stepping_detail::ForcingScalars& forcing)>;

/// The same on a drive sampled once (sampleDrive; its step is the output step). `observer` (may be
/// null) sees every sample.
fullorder::DeploymentSeries simulateModalDeployment(const ModalModel& model,
                                                    const SampledDrive& drive,
                                                    bool coriolis_coupling,
                                                    const ModalSampleObserver* observer = nullptr);

/// Receives the series a block of rows at a time, in time order (streamModalDeployment).
using ModalSeriesBlockSink = std::function<void(const fullorder::DeploymentSeries& block)>;

/// The same series handed to `sink` in blocks of at most `block_rows` rows as it is stepped,
/// never held whole: memory does not grow with the samples (`rom eval -o`). Every row equals
/// simulateModalDeployment's bit for bit, whatever the block size. An exception the sink throws
/// ends the stepping.
void streamModalDeployment(const ModalModel& model, const SampledDrive& drive,
                           bool coriolis_coupling, const ModalSeriesBlockSink& sink,
                           std::size_t block_rows, const ModalSampleObserver* observer = nullptr);

/// The deployment options a configuration implies for the ROM: its end time and output step
/// (simulation.end_time, output step). The reference deployment of the leave-one-out estimate and
/// of screens and studies.
ModalDeploymentOptions deploymentOptionsFromConfig(const Config& config);

}  // namespace mastrom::rom
