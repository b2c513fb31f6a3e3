// Scalar results of a ROM deployment computed while stepping, without storing the time series: the
// fast path of screening (10⁴ deployments) and of the leave-one-out estimate (rom/database_build).
//
// Both step the modal oscillators exactly as simulateModalDeployment does
// (rom/modal_deployment.hpp: first-order hold of the forcing −Γθ̈ − Γ_cθ̇² + Lᵀ(Rᵀg − g₀), left limit
// at the end of a step) and evaluate its output formulas at the same instants, but only the outputs
// the metrics need:
//   relative end angular acceleration  r = α_z − θ̈ = (ψη̈)_z   (R rotates about Z: z unchanged,
//                                                               and (Z × v)_z = 0)
//   joint force   F = R[Lη̈ + θ̈ Z×s + θ̇² Z×(Z×s) + 2θ̇ Z×(Lη̇)] − m g,   s = m c̄ + Lη
//   drive torque  τ = θ̈(J − 2Γ_cᵀη) − 2θ̇ Γ_cᵀη̇ + Γᵀη̈ − (R s × g)_z
// and reduce them on the fly with the definitions of fullorder::computeMetrics (peaks, residual,
// time-weighted RMS by the trapezoidal rule, settling by linear re-entry into the band). The
// results agree with simulateModalDeployment + computeMetrics to round-off
// (tests/rom/test_screening.cpp): both run the same stepping kernel (rom/modal_stepping.hpp), with
// or without the Coriolis coupling.
#pragma once

#include "fullorder/deployment_result.hpp"
#include "fullorder/drive_law.hpp"
#include "rom/modal_deployment.hpp"
#include "rom/modal_model.hpp"
#include "rom/modal_stepping.hpp"

namespace mastrom::rom {

/// computeMetrics(simulateModalDeployment(model, drive, options), drive_end_time_s, band) without
/// the series. Same errors: InputError when the record ends before drive_end_time_s or the band is
/// not > 0; NumericalError on a non-finite output.
fullorder::DeploymentMetrics modalDeploymentMetrics(
    const ModalModel& model, const fullorder::DriveLaw& drive,
    const ModalDeploymentOptions& options, double drive_end_time_s,
    double settling_band_rad_s2 = fullorder::kDefaultSettlingBandRadS2);

/// The same on a drive sampled once (sampleDrive): what a screen runs per design, sharing the
/// sampling of each drive law over all its designs.
fullorder::DeploymentMetrics modalDeploymentMetrics(
    const ModalModel& model, const SampledDrive& drive, bool coriolis_coupling,
    double drive_end_time_s, double settling_band_rad_s2 = fullorder::kDefaultSettlingBandRadS2);

/// max |relative end angular acceleration| of a ROM deployment (no end-time requirement).
double peakRelativeEndAcceleration(const ModalModel& model, const fullorder::DriveLaw& drive,
                                   const ModalDeploymentOptions& options);

}  // namespace mastrom::rom
