// The database's own estimate of its interpolation error (docs/theory.md §4.3).
//
// Leave-one-out (docs/theory.md §4.3, leave-one-out): a sample that is
// interior along at least one axis is interpolated from the grid without it — along each axis where
// it is interior only its two neighbours remain (the coarsened stencil), along the others the full
// axis (where it is a node, so that direction contributes no error). Per sample two relative
// errors are stored: of the lowest frequency ω₁, and the NRMSE of the relative end angular
// acceleration of a reference deployment (the base configuration's drive, end time and output
// step, simulated with the ROM on the interpolated and on the sample's own modal model) — the
// quantity `mastrom validate` reports, restricted to the interpolation error.
//
// From the stencil to the full grid (leaveOneOutScale). Multilinear interpolation in the
// coordinate u the weights are linear in (u = log p on an axis of positive values, p otherwise) has
// the error e(t) ≈ ½ t(1 − t) H² f''(u) at the local coordinate t of a cell of width H (f smooth,
// the response NRMSE linear in the modal errors while they are small). The left-out sample sits in
// its stencil of width h₁ + h₂ at t = h₁/(h₁ + h₂): e_LOO = ½ h₁h₂ f''. The largest error in
// the two full-grid cells next to it is at their midpoints, ⅛ max(h₁, h₂)² f''. Hence
//     e_interior ≈ ρ e_LOO,   ρ = max(h₁, h₂)² / (4 h₁ h₂)   (= ¼ on a uniform axis),
// and the database's estimate is max over samples of ρ_s e_LOO,s (ρ_s the largest over the axes
// where sample s is interior). What it bounds: the interpolation error (interpolated ROM against
// the ROM of a direct modal solve at the same point), which `validate` reports next to the error
// against the full order; the latter adds the modal model's own error at a sample (docs/theory.md
// §4.1, ≤ 3 % target). The estimate is an estimate, not a bound: it is exact to O(H³) for smooth f,
// and it underestimates when the stencil's error leaves the linear range (a phase error of the
// response beyond ≈ 1 rad, NRMSE ≳ 50 %).
//
// Cubic. The local cubic of method "cubic" has the error f⁗ π(u)/4!, π the node polynomial of its
// 4-node stencil. Left out, a sample is dropped from every axis where it is interior and that has
// ≥ 5 nodes (so that the coarsened axis still has the 4 nodes a cubic needs; other axes keep all
// their nodes), and ρ = |π_full(cell midpoint)| / |π_LOO(x_i)| (cubicLeaveOneOutScale; 9/64 on a
// uniform axis). Databases with fewer than 5 nodes along every axis get no cubic estimate.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "fullorder/drive_law.hpp"
#include "rom/database/build_report.hpp"
#include "rom/database/interpolation_method.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

/// The database without sample `index`, coarsened around it as described in the header, or
/// nothing when the sample lies on the box boundary along every axis.
std::optional<RomDatabase> leaveOneOutStencil(
    const RomDatabase& db, int index, InterpolationMethod method = InterpolationMethod::Tracked);

/// Leave-one-out errors of `method` for every sample, with the reference deployment given by
/// `drive` and `options`. Throws InputError when the method is not available.
LeaveOneOutResult leaveOneOut(const RomDatabase& db, InterpolationMethod method,
                              const fullorder::DriveLaw& drive,
                              const ModalDeploymentOptions& options);

/// The errors of the samples s ≡ first (mod stride) only, the others −1 (the share of one rank of
/// a build); estimates not yet summarised. `exact` caches the samples' own response series between
/// methods (empty entries = not computed yet).
LeaveOneOutResult leaveOneOutShare(const RomDatabase& db, InterpolationMethod method,
                                   const fullorder::DriveLaw& drive,
                                   const ModalDeploymentOptions& options, int first, int stride,
                                   std::vector<std::vector<double>>& exact);

/// Fill the estimate of `r` from its per-sample errors (see leaveOneOutScale).
void summariseLeaveOneOut(LeaveOneOutResult& r, const std::vector<ParameterAxis>& axes);

/// The relative end angular acceleration of a ROM deployment (the estimate's signal), at the
/// output samples of simulateModalDeployment; computed alone (the other outputs are not formed).
std::vector<double> relativeAccelerationSeries(const ModalModel& modal,
                                               const fullorder::DriveLaw& drive,
                                               const ModalDeploymentOptions& options);
/// The same on a drive sampled once for many models (sampleDrive(drive, options)). Without the
/// Coriolis coupling only the modes of modesInRelativeAcceleration are stepped; the others change
/// r by less than kUnobservedModeShare of its scale.
std::vector<double> relativeAccelerationSeries(const ModalModel& modal, const SampledDrive& drive,
                                               const ModalDeploymentOptions& options);
/// The same with every mode stepped (the reference of the reduction, for tests).
std::vector<double> relativeAccelerationSeriesOfAll(const ModalModel& modal,
                                                    const SampledDrive& drive,
                                                    const ModalDeploymentOptions& options);

/// r of several models on one drive, stepped together: the modes each contributes to r
/// (modesInRelativeAcceleration) side by side in one array, so that one pass of the stepping per
/// sample serves them all (a step of a few modes is bound by the latency of its chain of
/// dependent operations; many modes fill the vector units instead). Each series equals
/// relativeAccelerationSeries(*models[j], drive, options) to round-off. Models that differ in θ₀
/// or g, or the Coriolis coupling, are deployed one by one.
std::vector<std::vector<double>> relativeAccelerationSeriesTogether(
    const std::vector<const ModalModel*>& models, const SampledDrive& drive,
    const ModalDeploymentOptions& options);

/// responseNrmse(*references[j], r of *models[j]) for every j, the models stepped together as in
/// relativeAccelerationSeriesTogether, without forming their series.
std::vector<double> responseNrmseTogether(const std::vector<const ModalModel*>& models,
                                          const std::vector<const std::vector<double>*>& references,
                                          const SampledDrive& drive,
                                          const ModalDeploymentOptions& options);

/// What the estimate's passes share (leave-one-out and probes): for each j, the response NRMSE of
/// candidates[j] against the cached series exact[index[j]], that series first computed (together
/// with the others missing) from own(index[j]) where it is still empty.
std::vector<double> responseNrmseAgainstCached(const std::vector<std::size_t>& index,
                                               const std::vector<ModalModel>& candidates,
                                               const std::function<const ModalModel&(std::size_t)>& own,
                                               std::vector<std::vector<double>>& exact,
                                               const SampledDrive& drive,
                                               const ModalDeploymentOptions& options);

/// A mode whose bound on its share of r (the relative end angular acceleration) is at most this
/// fraction of the largest mode's is left out of r's deployments. Symmetric meshes give whole
/// families of modes that the drive does not excite or the end's Z rotation does not see, with
/// |ψ_z Γ| at the round-off of the eigenvectors (1e-28 against 1.5 on Scheme 3).
constexpr double kUnobservedModeShare = 1e-12;

/// The modes that can contribute to r on `drive`: mode k's bound is
/// |ψ_z,k| · (|Γ_k| max|θ̈| + |Γ_c,k| max θ̇² + 2|g|(|L_x,k| + |L_y,k|)) · max(2, 1/(2ζ_k)),
/// the largest forcing times a damped oscillator's largest gain; kept are those above
/// kUnobservedModeShare of the largest bound (ascending indices).
std::vector<int> modesInRelativeAcceleration(const ModalModel& modal, const SampledDrive& drive);

/// NRMSE of `candidate` against `reference` (same instants), as rom/model/comparison.hpp defines it.
double responseNrmse(const std::vector<double>& reference, const std::vector<double>& candidate);

}  // namespace mastrom::rom
