// The in-memory ROM database (docs/theory.md §4.3): modal models sampled over a box of continuous
// parameters — on a tensor grid, or at scattered points (a space-filling or adaptive design) —
// plus what the interpolators need. Its HDF5 form (versioned,
// self-describing) is read and written by rom/database/database_io.hpp; it is built by rom/offline/database_build.hpp.
//
// On a grid, sample s sits at the multi-index (i₀, …, i_{p−1}), s = i₀ + n₀(i₁ + n₁(i₂ + …))
// (first parameter fastest). Scattered samples are in no particular order; each axis then holds
// only the box, {lo, hi}, and each sample its own parameters. Every sample's mesh and DOF layout is the same (the parameters change
// values, not topology), so mode shapes of different samples live in one space.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rom/database/affine_reduced.hpp"
#include "rom/database/interpolation_method.hpp"
#include "rom/model/modal_model.hpp"

namespace mastrom::rom {

/// One grid axis: a config key ("interface.thickness") and its sample values (ascending); of a
/// scattered database, the axis' range {lo, hi}.
struct ParameterAxis {
  std::string key;
  std::vector<double> values;
};

struct RomSample {
  std::vector<double> parameters;  ///< one value per axis
  ModalModel modal;                ///< the exact modal model at this sample
  /// Orthogonal alignment of this sample's modes to the reference sample's (Procrustes in the
  /// mass inner product, k × k): Φ_s Q_s ≈ Φ_ref. Identity for the reference sample.
  Eigen::MatrixXd alignment;
  /// MAC-based permutation and signs matching this sample's modes to the reference sample's:
  /// tracked mode j of this sample is mode tracking[j] (≥ 0), with sign tracking_sign[j] (±1).
  std::vector<int> tracking;
  std::vector<int> tracking_sign;
  /// Leave-one-out errors of the default method (rom/offline/leave_one_out.hpp): relative error of this
  /// sample's lowest frequency and NRMSE of the relative end angular acceleration of the reference
  /// deployment when interpolated from the grid without it; for the affine method the same errors
  /// of the affine terms at the sample itself; for the rbf method the estimated largest error in
  /// the sample's neighbourhood (its leave-one-out error carried there by the power function,
  /// rom/offline/rbf_leave_one_out.hpp). −1 = not estimated (e.g. a corner sample).
  double loo_frequency_error = -1.0;
  double loo_response_error = -1.0;
};

/// The configuration key of Young's modulus, the one parameter a database may handle exactly.
inline constexpr const char* kYoungsModulusKey = "material.youngs_modulus";

/// Young's modulus handled exactly instead of sampled (docs/theory.md §4.4 (e),
/// rom/model/modulus_scaling.hpp): its axis (key kYoungsModulusKey) spans the user's box {lo, hi},
/// every sample is solved at reference_pa (its parameter on that axis), and an interpolator
/// evaluates the other axes at the reference and scales the result to the E asked for.
struct ExactModulus {
  double reference_pa = 0.0;
};

/// A held-out probe of a grid build's estimate (rom/offline/probe_estimate.hpp): the centre of a
/// grid cell and the default method's errors measured there (relative error of ω₁, NRMSE of the
/// relative end angular acceleration in the reference deployment).
struct ProbeError {
  std::vector<double> parameters;
  double frequency_error = 0.0;
  double response_error = 0.0;
};

/// Where a database's samples lie.
enum class SampleLayout {
  Grid,      ///< the tensor grid of the axes' values (sample order: see the header)
  Scattered  ///< anywhere in the box (RomSample::parameters); axes hold {lo, hi}
};

struct RomDatabase {
  std::string base_config_toml;          ///< resolved config the samples were built from
  std::vector<ParameterAxis> axes;       ///< the box: axis k spans [values.front(), values.back()]
  SampleLayout layout = SampleLayout::Grid;
  std::vector<RomSample> samples;        ///< grid order (see header), or any order when scattered
  int reference_sample = 0;              ///< the alignment/tracking reference (box centre)
  int modes_per_sample = 0;
  InterpolationMethod default_method = InterpolationMethod::Manifold;
  /// The exact affine terms (method (c)), present when every axis is one of interface.thickness
  /// (at a fixed radius), material.youngs_modulus, material.density and gravity is off.
  std::optional<AffineReducedModel> affine;
  /// Present when Young's modulus is handled exactly (only without gravity).
  std::optional<ExactModulus> exact_modulus;
  /// The samples' loo_* errors are not leave-one-out errors but the default method's errors
  /// measured at held-out probe points (the grid's cell centres, rom/offline/probe_estimate.hpp),
  /// each carried to the corners of its cell, unscaled.
  bool estimate_from_probes = false;
  /// The probes themselves, when estimate_from_probes (what rom/database/probe_point_estimate.hpp
  /// estimates a point's error from).
  std::vector<ProbeError> probes;
  std::string mastrom_version;

  /// The axis of exact_modulus; −1 when there is none.
  int exactModulusAxis() const;

  bool isGrid() const { return layout == SampleLayout::Grid; }
  /// Linear index of a grid multi-index.
  int sampleIndex(const std::vector<int>& multi_index) const;
  /// True when p lies inside the box (with a relative tolerance of 1e-12 of each axis span).
  bool contains(const std::vector<double>& p) const;
};

/// The database the samples span: `db` without the exactly handled axis of Young's modulus (the
/// axis dropped from `axes` and from every sample's parameters; on a grid that axis holds only
/// the box {lo, hi}), or a copy of `db` when it has none. What the interpolators and the error
/// estimates work on.
RomDatabase sampledDatabase(const RomDatabase& db);

/// The multi-index of tensor-grid sample `index` over `axes` (first axis fastest).
std::vector<int> gridIndex(const std::vector<ParameterAxis>& axes, int index);
/// The parameter values of tensor-grid sample `index` over `axes`.
std::vector<double> gridPoint(const std::vector<ParameterAxis>& axes, int index);

/// ρ of the leave-one-out estimate (rom/offline/leave_one_out.hpp, docs/theory.md (4.5)) for grid sample
/// `index`: how the leave-one-out error of the sample translates to the largest error inside the
/// full grid's cells next to it; 0 for a sample on the boundary of every axis (no estimate).
double leaveOneOutScale(const std::vector<ParameterAxis>& axes, int index);
/// The first of the m consecutive nodes of a local interpolation stencil around x on the ascending
/// `nodes` (m ≤ nodes.size()): centred on x's cell [v_i, v_{i+1}] (the first cell below v_0, the
/// last at and beyond the upper end), shifted inwards at the ends. Shared by the Lagrange weights
/// (rom/interpolation/grid_weights.hpp) and the cubic leave-one-out scale.
int localStencilFirst(const std::vector<double>& nodes, double x, int m);

/// ρ of `method`'s leave-one-out for sample `index`: leaveOneOutScale, cubicLeaveOneOutScale for
/// the cubic method, 1 for the affine one (its errors are taken at the samples, unscaled) and the
/// rbf one (its stored errors are already carried to the sample's neighbourhood).
double leaveOneOutScaleFor(const std::vector<ParameterAxis>& axes, int index,
                           InterpolationMethod method);

/// The same for the cubic method's leave-one-out (rom/offline/leave_one_out.hpp, "Cubic"): the
/// sample is left out of every axis where it is interior and has ≥ 5 nodes, and the error of the
/// local cubic at the full grid's cell midpoints is ρ = |π_full(midpoint)| / |π_LOO(x_i)| times
/// its error at the sample, π the node polynomial Π(u − u_k) of the stencil (the leading error
/// term f⁗/4! · π). 0 when the sample is interior along no such axis (no estimate).
double cubicLeaveOneOutScale(const std::vector<ParameterAxis>& axes, int index);

}  // namespace mastrom::rom
