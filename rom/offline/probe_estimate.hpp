// The cubic weights as a grid database's default, and their error measured at held-out probes
// (docs/theory.md §4.3, "Cubic by default").
//
// On smooth data the cubic weights (§4.4 (a′)) are an order more accurate than the tracked and
// manifold ones (main job's box, 3 × 3: NRMSE 0.8 % against 9.5 % at the worst of 10 random points,
// benchmarks/README.md "ROM against the step-converged full order"), but they interpolate tracked
// features and so follow a mode veering no better than (a). The build therefore makes them the
// default where the tracking of the modes the drive excites is clean (smallest MAC of those over
// all samples ≥ kCubicTrackingMac) and the manifold method, robust to veering, otherwise.
//
// Their leave-one-out needs 5 nodes on an axis (4 remain for the stencil); on coarser grids the
// quadratic error term cannot be estimated from the samples. So the error is measured instead:
// the modes are solved at the centres of the grid's cells (the middle of each cell in the
// interpolation coordinate, log x on a positive axis: where the error of a local interpolant is
// largest, up to 3 % for the quadratic on three nodes), the cubic interpolant is deployed there
// against the probe's own modal model, and the NRMSE of the relative end angular acceleration and
// the error of ω₁ are kept. That is a held-out validation, honest at those points by construction;
// the database's estimate is their maximum, and each sample carries the largest error of the cells
// it is a corner of. Costs one modal solve per probe (at most kMaxProbes, spread over the ranks).
#pragma once

#include <vector>

#include "fullorder/drive_law.hpp"
#include "rom/database/build_report.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/model/modal_deployment.hpp"

namespace mastrom::rom {

/// Smallest MAC of the drive-excited modes (BuildReport::min_coupled_mac) for the cubic default.
constexpr double kCubicTrackingMac = 0.9;

/// At most this many probes per build (the cells spread evenly by index when there are more).
constexpr int kMaxProbes = 64;

/// True when a grid build without --method should default to the cubic weights: some axis has at
/// least 3 nodes (on 2 nodes everywhere they are the tracked method's), the drive-excited modes
/// track cleanly (`report`), and the exact affine terms do not apply (`affine`).
bool cubicIsDefault(const BuildReport& report, const std::vector<ParameterAxis>& axes, bool affine);

/// True when the cubic method has a leave-one-out estimate on this grid (every axis ≥ 5 nodes);
/// otherwise its estimate comes from probes.
bool cubicHasLeaveOneOut(const std::vector<ParameterAxis>& axes);

/// A probe: the centre of one grid cell and the samples at its corners.
struct Probe {
  std::vector<double> parameters;
  std::vector<int> corners;  ///< sample indices (2^p, fewer where an axis has one cell)
};

/// The probes of a grid over `axes`: every cell's centre, or kMaxProbes of them evenly spread by
/// cell index when there are more cells.
std::vector<Probe> cellCentreProbes(const RomDatabase& db);

/// The errors of `method` on `db` at the probes, against `solved[i]`, the modal model solved at
/// probes[i] (tracked like a sample): per sample the largest error of the cells it is a corner of
/// (−1 where none), the estimates the largest over all probes (frequency: relative error of ω₁;
/// response: NRMSE of the relative end angular acceleration, reference deployment); each probe's
/// own errors in `measured` (what the file keeps, rom/database/probe_point_estimate.hpp).
LeaveOneOutResult probeErrors(const RomDatabase& db, InterpolationMethod method,
                              const std::vector<Probe>& probes,
                              const std::vector<ModalModel>& solved,
                              const fullorder::DriveLaw& drive, const ModalDeploymentOptions& deploy,
                              std::vector<ProbeError>& measured);

}  // namespace mastrom::rom
