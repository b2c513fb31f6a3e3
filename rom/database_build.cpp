#include "rom/database_build.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"
#include "common/version.hpp"
#include "fullorder/mast_config.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"
#include "rom/affine_interpolation.hpp"
#include "rom/affine_model.hpp"
#include "rom/interpolator.hpp"
#include "rom/modal_extraction.hpp"
#include "rom/mode_tracking.hpp"
#include "rom/mpi_gather.hpp"
#include "rom/parameter_space.hpp"

namespace mastrom::rom {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// One sample's modal solve, with what tracking needs (Φ and the mass matrix stay on this rank).
struct SampleSolution {
  ModalModel modal;
  Eigen::MatrixXd modes;  ///< Φ with the extra modes (columns beyond the stored count)
  Eigen::SparseMatrix<double> mass;
  double assembly_s = 0.0, eigensolve_s = 0.0, extraction_s = 0.0;
};

std::string describePoint(const std::vector<ParameterAxis>& axes, const std::vector<double>& p) {
  std::string text;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    text += (a ? ", " : "") + formatOverride(axes[a].key, p[a]);
  }
  return text;
}

/// Extra modes solved beyond the stored count, so that a degenerate pair or triplet cut by the
/// window's upper edge is still aligned as a whole (see alignClusters).
constexpr int kExtraModes = 2;
/// Eigenvalues closer than this (relative) form one degenerate cluster. Symmetric masts (a cube
/// module on a cylinder) have exactly double bending pairs; solvers separate them to ~1e-10.
constexpr double kDegenerateTolerance = 1e-6;

/// The modes rigidly rotated by `angle_rad` about Z: every 3-block of a field (positions, slopes,
/// NCF vectors) rotates alike (rom/modal_model.hpp). Samples locked at different angles θ₀ (a θ₀
/// axis with gravity on) are compared in the reference's frame: rotated by θ_ref − θ_s, a mode
/// differs from the reference's only by its elastic change, so MAC tracking and the Procrustes
/// alignment see the shapes, not the rigid rotation of the whole mast (which mixes every bending
/// mode with its neighbours in the global frame). M commutes with the rotation (MR = RM).
Eigen::MatrixXd rotateModes(const Eigen::MatrixXd& phi, double angle_rad) {
  if (angle_rad == 0.0) return phi;
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  MASTROM_REQUIRE(phi.rows() % 3 == 0, NumericalError, "rom build: ", phi.rows(),
                  " DOFs are not 3-blocks");
  Eigen::MatrixXd out(phi.rows(), phi.cols());
  for (Eigen::Index b = 0; b < phi.rows(); b += 3) out.middleRows<3>(b) = r * phi.middleRows<3>(b);
  return out;
}

/// [begin, end) ranges of ≥ 2 numerically equal eigenvalues (ascending ω²).
std::vector<std::pair<int, int>> degenerateClusters(const Eigen::VectorXd& omega2) {
  std::vector<std::pair<int, int>> clusters;
  const int n = static_cast<int>(omega2.size());
  const double scale = omega2.cwiseAbs().maxCoeff();
  for (int i = 0; i < n;) {
    int j = i + 1;
    while (j < n && std::abs(omega2[j] - omega2[j - 1]) <=
                        kDegenerateTolerance * std::max(std::abs(omega2[j]), 1e-12 * scale))
      ++j;
    if (j - i >= 2) clusters.emplace_back(i, j);
    i = j;
  }
  return clusters;
}

/// The reference sample's basis of a degenerate eigenspace is arbitrary; make it canonical: a
/// Householder reflection within the cluster puts the whole rotation participation Γ = ΦᵀMΩq̄ (or,
/// when Γ vanishes, Γ_c) into the cluster's first mode. For a pair (the bending pair) this fixes
/// the basis: the in-plane mode the drive excites and the out-of-plane one it does not.
void canonicalizeClusters(Eigen::MatrixXd& phi, const std::vector<std::pair<int, int>>& clusters,
                          const Eigen::SparseMatrix<double>& mass, const Eigen::VectorXd& q) {
  const Eigen::VectorXd omega_q = rotateFieldAboutZ(q);
  const Eigen::VectorXd m_omega_q = mass * omega_q;
  const Eigen::VectorXd m_omega2_q = mass * rotateFieldAboutZ(omega_q);
  for (const auto& [b, e] : clusters) {
    const int c = e - b;
    Eigen::VectorXd g = phi.middleCols(b, c).transpose() * m_omega_q;
    const double scale = std::sqrt(m_omega_q.dot(omega_q));  // √J: |Γ| ≤ √J
    if (g.norm() <= 1e-9 * scale) g = phi.middleCols(b, c).transpose() * m_omega2_q;
    const double norm = g.norm();
    if (norm <= 1e-9 * scale) continue;
    // H = I − 2vvᵀ/vᵀv with v = g − |g|e₁ maps g to |g|e₁ (v = g + |g|e₁ if that is closer).
    Eigen::VectorXd v = g;
    v[0] += g[0] >= 0 ? norm : -norm;
    const Eigen::MatrixXd h =
        Eigen::MatrixXd::Identity(c, c) - 2.0 * v * v.transpose() / v.squaredNorm();
    const Eigen::MatrixXd rotated = phi.middleCols(b, c) * h;
    phi.middleCols(b, c) = rotated;
  }
}

/// A sample's basis of a degenerate eigenspace, rotated to match the reference's modes: the c
/// reference modes the cluster projects onto most, then orthogonal Procrustes within the cluster
/// (mass inner product of the reference), so that MAC tracking sees the same shapes.
void alignClusters(Eigen::MatrixXd& phi, const std::vector<std::pair<int, int>>& clusters,
                   const Eigen::MatrixXd& phi_ref, const Eigen::SparseMatrix<double>& mass_ref) {
  if (clusters.empty()) return;
  const Eigen::MatrixXd m_ref = mass_ref * phi_ref;
  for (const auto& [b, e] : clusters) {
    const int c = e - b;
    const Eigen::MatrixXd x = phi.middleCols(b, c).transpose() * m_ref;  // c × k_ref
    const Eigen::VectorXd weight = x.colwise().squaredNorm().transpose();
    std::vector<int> order(static_cast<std::size_t>(weight.size()));
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(),
                     [&weight](int a, int z) { return weight[a] > weight[z]; });
    order.resize(static_cast<std::size_t>(std::min<Eigen::Index>(c, weight.size())));
    std::sort(order.begin(), order.end());
    if (static_cast<int>(order.size()) < c) continue;
    Eigen::MatrixXd y(c, c);
    for (int j = 0; j < c; ++j) y.col(j) = x.col(order[j]);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(y, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::MatrixXd r = svd.matrixU() * svd.matrixV().transpose();
    const Eigen::MatrixXd rotated = phi.middleCols(b, c) * r;
    phi.middleCols(b, c) = rotated;
  }
}

/// Solve one sample. `reference` = nullptr for the reference sample itself (its degenerate
/// eigenspaces are canonicalised); otherwise they are aligned to the reference's modes.
SampleSolution solveSample(const Config& base, const DatabaseBuildOptions& options, int modes,
                           EigenBackendKind backend, int index, const SampleSolution* reference) {
  const std::vector<double> point = gridPoint(options.axes, index);
  const std::string where =
      detail::concat("rom build: sample ", index, " (", describePoint(options.axes, point), ")");
  SampleSolution out;
  auto start = Clock::now();
  Config config;
  try {
    config = applyOverrides(base, parameterOverrides(options.axes, point));
  } catch (const InputError& e) {
    throw InputError(where + ": " + e.what());
  }
  const fullorder::MastModel model =
      modes::buildLockedMast(fullorder::mastParametersFromConfig(config), config.modes.angleRad());
  modes::Linearization lin;
  try {
    lin = modes::linearizeMast(model);
  } catch (const NumericalError& e) {
    throw NumericalError(where + ": " + e.what());
  }
  out.assembly_s = secondsSince(start);

  start = Clock::now();
  modes::EigenSolverOptions eo;
  const int available = static_cast<int>(lin.problem.dofs() - lin.problem.constraints());
  MASTROM_REQUIRE(modes <= available, InputError, where, ": ", modes,
                  " modes requested, the model has ", available, " degrees of freedom");
  const int count = std::min(modes + kExtraModes, available);
  eo.count = count;
  eo.backend = backend;
  eo.communicator = MPI_COMM_SELF;  // every rank its own eigenproblem (ignored by ARPACK, dense)
  const modes::EigenResult res = modes::solveConstrainedEigenproblem(lin.problem, eo);
  out.eigensolve_s = secondsSince(start);
  MASTROM_REQUIRE(res.ok() && res.converged >= count, NumericalError, where, ": modal solve ",
                  modes::toString(res.status), " (", res.converged, " of ", count,
                  " modes): ", res.message);

  start = Clock::now();
  LinearizedModes lm;
  lm.q_reference = lin.q;
  lm.reference_angle_rad = config.modes.angleRad();
  lm.mass = lin.problem.mass;
  lm.damping = lin.damping;
  Eigen::MatrixXd phi = res.modes.leftCols(count);
  const std::vector<std::pair<int, int>> clusters =
      degenerateClusters(res.eigenvalues_rad2_s2.head(count));
  if (reference == nullptr) {
    canonicalizeClusters(phi, clusters, lin.problem.mass, lin.q);
  } else {
    // In the reference's frame (rotateModes), then back: the cluster rotation acts on the right,
    // the frame rotation on the left, so they commute.
    const double to_reference = reference->modal.reference_angle_rad - config.modes.angleRad();
    phi = rotateModes(phi, to_reference);
    alignClusters(phi, clusters, reference->modes, reference->mass);
    phi = rotateModes(phi, -to_reference);
  }
  lm.omega_squared = res.eigenvalues_rad2_s2.head(modes);
  lm.modes = phi.leftCols(modes);
  out.modal = extractModalModel(model, lm);
  out.modes = std::move(phi);
  out.mass = std::move(lm.mass);
  out.extraction_s = secondsSince(start);
  return out;
}

// --- flat serialisation of a sample (for the gather) ---------------------------------------------
void put(std::vector<double>& b, const Eigen::Ref<const Eigen::MatrixXd>& m) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i) b.push_back(m(i, j));
}

void packSample(std::vector<double>& b, int index, const RomSample& s, const double mac_min[2],
                const double times[3]) {
  const ModalModel& m = s.modal;
  const int k = m.modeCount(), kt = static_cast<int>(s.tracking.size());
  b.push_back(index);
  b.push_back(k);
  b.push_back(kt);
  put(b, m.omega_rad_s);
  put(b, m.damping_ratio);
  put(b, m.rotation_participation);
  put(b, m.centrifugal_participation);
  put(b, m.end_rotation);
  put(b, m.end_translation);
  put(b, m.momentum_participation);
  put(b, m.coriolis);
  b.push_back(m.inertia_z_kg_m2);
  b.push_back(m.total_mass_kg);
  put(b, m.centroid_m);
  put(b, m.end_position_m);
  b.push_back(m.reference_angle_rad);
  put(b, m.gravity_m_s2);
  put(b, s.alignment);
  for (int j = 0; j < kt; ++j) b.push_back(s.tracking[j]);
  for (int j = 0; j < kt; ++j) b.push_back(s.tracking_sign[j]);
  b.push_back(mac_min[0]);
  b.push_back(mac_min[1]);
  for (int i = 0; i < 3; ++i) b.push_back(times[i]);
}

class Reader {
public:
  explicit Reader(const std::vector<double>& b) : b_(b) {}
  double next() {
    MASTROM_REQUIRE(pos_ < b_.size(), NumericalError, "rom build: gathered sample data truncated");
    return b_[pos_++];
  }
  void fill(Eigen::Ref<Eigen::MatrixXd> m) {
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      for (Eigen::Index i = 0; i < m.rows(); ++i) m(i, j) = next();
  }
  bool done() const { return pos_ >= b_.size(); }

private:
  const std::vector<double>& b_;
  std::size_t pos_ = 0;
};

int unpackSample(Reader& r, RomSample& s, double mac_min[2], double times[3]) {
  const int index = static_cast<int>(r.next());
  const int k = static_cast<int>(r.next()), kt = static_cast<int>(r.next());
  ModalModel& m = s.modal;
  m.omega_rad_s.resize(k);
  m.damping_ratio.resize(k);
  m.rotation_participation.resize(k);
  m.centrifugal_participation.resize(k);
  m.end_rotation.resize(3, k);
  m.end_translation.resize(3, k);
  m.momentum_participation.resize(3, k);
  m.coriolis.resize(k, k);
  r.fill(m.omega_rad_s);
  r.fill(m.damping_ratio);
  r.fill(m.rotation_participation);
  r.fill(m.centrifugal_participation);
  r.fill(m.end_rotation);
  r.fill(m.end_translation);
  r.fill(m.momentum_participation);
  r.fill(m.coriolis);
  m.inertia_z_kg_m2 = r.next();
  m.total_mass_kg = r.next();
  r.fill(m.centroid_m);
  r.fill(m.end_position_m);
  m.reference_angle_rad = r.next();
  r.fill(m.gravity_m_s2);
  s.alignment.resize(k, kt);
  r.fill(s.alignment);
  s.tracking.resize(kt);
  s.tracking_sign.resize(kt);
  for (int j = 0; j < kt; ++j) s.tracking[j] = static_cast<int>(r.next());
  for (int j = 0; j < kt; ++j) s.tracking_sign[j] = static_cast<int>(r.next());
  mac_min[0] = r.next();
  mac_min[1] = r.next();
  for (int i = 0; i < 3; ++i) times[i] = r.next();
  return index;
}

/// The relative end angular acceleration of a ROM deployment (the validation's signal).
std::vector<double> relativeAccelerationSeries(const ModalModel& modal,
                                               const fullorder::DriveLaw& drive,
                                               const ModalDeploymentOptions& options) {
  return simulateModalDeployment(modal, drive, options).end_relative_angular_acceleration_rad_s2;
}

/// NRMSE of `candidate` against `reference` (same instants), as rom/comparison.hpp defines it.
double nrmse(const std::vector<double>& reference, const std::vector<double>& candidate) {
  MASTROM_REQUIRE(reference.size() == candidate.size(), NumericalError,
                  "rom build: leave-one-out deployments of different lengths");
  double diff = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    diff += (candidate[i] - reference[i]) * (candidate[i] - reference[i]);
    norm += reference[i] * reference[i];
  }
  return norm > 0 ? std::sqrt(diff / norm) : 0.0;
}

/// Leave-one-out errors of the samples s ≡ first (mod stride); the others stay −1. `exact`
/// caches the samples' own response series between methods (empty = not computed yet).
LeaveOneOutResult leaveOneOutShare(const RomDatabase& db, InterpolationMethod method,
                                   const fullorder::DriveLaw& drive,
                                   const ModalDeploymentOptions& options, int first, int stride,
                                   std::vector<std::vector<double>>& exact) {
  MASTROM_REQUIRE(interpolationMethodAvailable(method), InputError, "rom: ", toString(method),
                  " interpolation is not available in this build");
  LeaveOneOutResult r;
  r.method = method;
  const std::size_t n = db.samples.size();
  r.frequency_error.assign(n, -1.0);
  r.response_error.assign(n, -1.0);
  exact.resize(n);
  for (std::size_t s = static_cast<std::size_t>(first); s < n;
       s += static_cast<std::size_t>(stride)) {
    const std::optional<RomDatabase> stencil = leaveOneOutStencil(db, static_cast<int>(s));
    if (!stencil) continue;
    const RomSample& sample = db.samples[s];
    const ModalModel interp = makeInterpolator(*stencil, method)->evaluate(sample.parameters);
    const double w_exact = sample.modal.omega_rad_s.minCoeff();
    const double w_interp = interp.omega_rad_s.minCoeff();
    r.frequency_error[s] = w_exact > 0 ? std::abs(w_interp - w_exact) / w_exact : 0.0;
    if (exact[s].empty()) exact[s] = relativeAccelerationSeries(sample.modal, drive, options);
    r.response_error[s] = nrmse(exact[s], relativeAccelerationSeries(interp, drive, options));
  }
  return r;
}

/// The affine terms over the box of `axes` (the parameters not on an axis fixed at the base's
/// values), locked at the base's modes.angle_deg.
AffineReducedModel buildAffineTerms(const Config& base, const std::vector<ParameterAxis>& axes,
                                    int modes, EigenBackendKind backend) {
  AffineModelOptions o;
  o.box.thickness_min_m = o.box.thickness_max_m = base.interface.thickness_m;
  o.box.youngs_modulus_min_pa = o.box.youngs_modulus_max_pa = base.material.youngs_modulus_pa;
  o.box.density_min_kg_m3 = o.box.density_max_kg_m3 = base.material.density_kg_m3;
  for (const ParameterAxis& a : axes) {
    const double lo = a.values.front(), hi = a.values.back();
    if (a.key == "interface.thickness") {
      o.box.thickness_min_m = lo;
      o.box.thickness_max_m = hi;
    } else if (a.key == "material.youngs_modulus") {
      o.box.youngs_modulus_min_pa = lo;
      o.box.youngs_modulus_max_pa = hi;
    } else if (a.key == "material.density") {
      o.box.density_min_kg_m3 = lo;
      o.box.density_max_kg_m3 = hi;
    }
  }
  o.lock_angle_rad = base.modes.angleRad();
  o.modes = modes;
  // Snapshots: the stored modes plus the window margin of the samples, at 3 points per varying
  // axis (h, ρ; E does not change a mode shape) — the defaults of rom/affine_model.hpp, whose
  // tests measure the truncation error they leave.
  o.snapshot_modes = std::max(o.snapshot_modes, modes + kExtraModes);
  o.backend = backend;
  return AffineModalModel::build(fullorder::mastParametersFromConfig(base), o).reduced();
}

/// Fill the estimate of `r` from its per-sample errors (see leaveOneOutScale).
void summarise(LeaveOneOutResult& r, const std::vector<ParameterAxis>& axes) {
  r.estimated = 0;
  r.max_frequency_error = r.max_response_error = -1.0;
  r.frequency_estimate = r.response_estimate = -1.0;
  for (std::size_t s = 0; s < r.frequency_error.size(); ++s) {
    if (r.frequency_error[s] < 0) continue;
    ++r.estimated;
    const double scale = leaveOneOutScale(axes, static_cast<int>(s));
    r.max_frequency_error = std::max(r.max_frequency_error, r.frequency_error[s]);
    r.max_response_error = std::max(r.max_response_error, r.response_error[s]);
    r.frequency_estimate = std::max(r.frequency_estimate, scale * r.frequency_error[s]);
    r.response_estimate = std::max(r.response_estimate, scale * r.response_error[s]);
  }
}

}  // namespace

std::vector<int> gridIndex(const std::vector<ParameterAxis>& axes, int index) {
  std::vector<int> multi(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const int n = static_cast<int>(axes[a].values.size());
    multi[a] = index % n;
    index /= n;
  }
  return multi;
}

std::vector<double> gridPoint(const std::vector<ParameterAxis>& axes, int index) {
  const std::vector<int> multi = gridIndex(axes, index);
  std::vector<double> p(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) p[a] = axes[a].values[multi[a]];
  return p;
}

ModalDeploymentOptions deploymentOptionsFromConfig(const Config& config) {
  ModalDeploymentOptions o;
  o.end_time_s = config.simulation.end_time_s;
  o.step_s = outputInterval(config);
  return o;
}

RomDatabase buildDatabase(const Config& base_in, const DatabaseBuildOptions& options,
                          BuildReport* report) {
  const auto wall_start = Clock::now();
  MASTROM_REQUIRE(!options.axes.empty(), InputError,
                  "rom build: no parameter axis (give at least one --param KEY=LO:HI:N)");
  const Config base = databaseBaseConfig(base_in, options.axes);
  const int modes = options.modes > 0 ? options.modes : base.modes.count;
  MASTROM_REQUIRE(options.modes >= 0, InputError, "rom build: --modes = ", options.modes,
                  " must be >= 1");
  const EigenBackendKind backend = options.backend.value_or(base.modes.backend);

  long total = 1;
  for (const ParameterAxis& a : options.axes) {
    MASTROM_REQUIRE(a.values.size() >= 2, InputError, "rom build: axis ", a.key,
                    " needs at least 2 values");
    total *= static_cast<long>(a.values.size());
  }
  MASTROM_REQUIRE(total <= 1000000, InputError, "rom build: ", total,
                  " samples is too many (at most 1e6)");
  const int samples = static_cast<int>(total);

  RomDatabase db;
  {
    Config stored = base;  // the file's configuration says what ran
    stored.modes.count = modes;
    stored.modes.backend = backend;
    db.base_config_toml = toToml(stored);
  }
  db.axes = options.axes;
  db.modes_per_sample = modes;
  db.mastrom_version = std::string(kVersion);
  db.default_method = interpolationMethodAvailable(InterpolationMethod::Manifold)
                          ? InterpolationMethod::Manifold
                          : InterpolationMethod::Tracked;
  {
    std::vector<int> centre(options.axes.size());
    for (std::size_t a = 0; a < options.axes.size(); ++a)
      centre[a] = static_cast<int>(options.axes[a].values.size() - 1) / 2;
    db.reference_sample = db.sampleIndex(centre);
  }

  const MPI_Comm comm = options.communicator;
  int rank = 0, size = 1;
  communicatorRankSize(comm, rank, size);

  // --- local phase: the reference, then this rank's share
  // -----------------------------------------
  std::vector<double> buffer;
  double local_times[4] = {0, 0, 0, 0};  // assembly, eigensolve, extraction, solves
  std::string error;
  bool numerical = false;
  try {
    const SampleSolution ref =
        solveSample(base, options, modes, backend, db.reference_sample, nullptr);
    local_times[0] += ref.assembly_s;
    local_times[1] += ref.eigensolve_s;
    local_times[2] += ref.extraction_s;
    local_times[3] += 1;
    const int share = (samples - rank + size - 1) / size;
    int done = 0;
    for (int s = rank; s < samples; s += size) {
      RomSample sample;
      double mac_min[2] = {1.0, 1.0};  // all matched pairs; drive-coupled reference modes
      double times[3] = {0, 0, 0};
      if (s == db.reference_sample) {
        sample.modal = ref.modal;
        sample.alignment = Eigen::MatrixXd::Identity(modes, modes);
        for (int j = 0; j < modes; ++j) {
          sample.tracking.push_back(j);
          sample.tracking_sign.push_back(1);
        }
        times[0] = ref.assembly_s;
        times[1] = ref.eigensolve_s;
        times[2] = ref.extraction_s;
      } else {
        const SampleSolution sol = solveSample(base, options, modes, backend, s, &ref);
        const auto start = Clock::now();
        const ModeTracking t = trackModes(
            rotateModes(sol.modes.leftCols(modes),
                        ref.modal.reference_angle_rad - sol.modal.reference_angle_rad),
            ref.modes.leftCols(modes), ref.mass);
        sample.modal = sol.modal;
        sample.alignment = t.alignment;
        sample.tracking = t.tracking;
        sample.tracking_sign = t.sign;
        mac_min[0] = t.mac.minCoeff();
        // The modes the drive excites: |Γ_j| of the reference above 1e-3 of the largest.
        const Eigen::VectorXd& g = ref.modal.rotation_participation;
        const double g_max = g.cwiseAbs().maxCoeff();
        for (int j = 0; j < modes; ++j)
          if (std::abs(g[j]) >= 1e-3 * g_max) mac_min[1] = std::min(mac_min[1], t.mac[j]);
        times[0] = sol.assembly_s;
        times[1] = sol.eigensolve_s;
        times[2] = sol.extraction_s + secondsSince(start);
        local_times[0] += times[0];
        local_times[1] += times[1];
        local_times[2] += times[2];
        local_times[3] += 1;
      }
      packSample(buffer, s, sample, mac_min, times);
      ++done;
      if (options.progress) options.progress(done, share);
    }
  } catch (const NumericalError& e) {
    error = e.what();
    numerical = true;
  } catch (const Error& e) {
    error = e.what();
  } catch (const std::exception& e) {
    error = std::string("rom build: ") + e.what();
  }

  // --- gather to every rank (the leave-one-out estimate is shared out too) ----------------------
  const auto comm_start = Clock::now();
  throwIfAnyRankFailed(comm, error, numerical);
  BuildTiming timing;
  timing.ranks = size;
  const std::vector<double> all = gatherToAll(comm, buffer);
  timing.communication_s = secondsSince(comm_start);

  BuildReport rep;
  db.samples.assign(static_cast<std::size_t>(samples), RomSample{});
  std::vector<char> filled(static_cast<std::size_t>(samples), 0);
  Reader reader(all);
  while (!reader.done()) {
    RomSample s;
    double mac_min[2] = {1.0, 1.0}, times[3];
    const int index = unpackSample(reader, s, mac_min, times);
    MASTROM_REQUIRE(index >= 0 && index < samples && !filled[index], NumericalError,
                    "rom build: gathered sample ", index, " is invalid or duplicated");
    s.parameters = gridPoint(db.axes, index);
    if (mac_min[0] < rep.min_mac) {
      rep.min_mac = mac_min[0];
      rep.min_mac_sample = index;
    }
    if (mac_min[1] < rep.min_coupled_mac) {
      rep.min_coupled_mac = mac_min[1];
      rep.min_coupled_mac_sample = index;
    }
    db.samples[index] = std::move(s);
    filled[index] = 1;
  }
  for (int s = 0; s < samples; ++s)
    MASTROM_REQUIRE(filled[s], NumericalError, "rom build: sample ", s, " was not computed");

  // --- leave-one-out estimate: samples round-robin again, errors gathered to rank 0
  // ---------------
  const auto loo_start = Clock::now();
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(base));
  const ModalDeploymentOptions deploy = deploymentOptionsFromConfig(base);
  std::vector<InterpolationMethod> methods;
  for (const InterpolationMethod m : {InterpolationMethod::Tracked, InterpolationMethod::Manifold})
    if (interpolationMethodAvailable(m)) methods.push_back(m);
  std::vector<double> local_loo;  // per method and own sample: index, frequency, response
  std::vector<std::vector<double>> exact_series;
  error.clear();
  try {
    for (const InterpolationMethod m : methods) {
      const LeaveOneOutResult r = leaveOneOutShare(db, m, drive, deploy, rank, size, exact_series);
      for (int s = rank; s < samples; s += size) {
        local_loo.push_back(s);
        local_loo.push_back(r.frequency_error[s]);
        local_loo.push_back(r.response_error[s]);
      }
    }
  } catch (const NumericalError& e) {
    error = e.what();
    numerical = true;
  } catch (const std::exception& e) {
    error = std::string("rom build: leave-one-out: ") + e.what();
  }
  double local_times_loo[5] = {local_times[0], local_times[1], local_times[2], local_times[3],
                               secondsSince(loo_start)};
  throwIfAnyRankFailed(comm, error, numerical);
  const std::vector<double> loo = gatherToRoot(comm, local_loo);
  double sums[5] = {local_times_loo[0], local_times_loo[1], local_times_loo[2], local_times_loo[3],
                    local_times_loo[4]};
  if (comm != MPI_COMM_NULL) MPI_Reduce(local_times_loo, sums, 5, MPI_DOUBLE, MPI_SUM, 0, comm);
  timing.assembly_s = sums[0];
  timing.eigensolve_s = sums[1];
  timing.extraction_s = sums[2];
  timing.solves = static_cast<int>(sums[3]);
  timing.leave_one_out_s = sums[4];
  if (rank != 0) {
    db.samples.clear();
    if (report) report->timing = timing;
    return db;
  }

  // The exact affine terms (method (c)) where they apply: rank 0 alone (a few snapshot solves);
  // its error at every sample (truncation to the basis only, nothing is interpolated) is stored
  // as its estimate, unscaled.
  std::optional<LeaveOneOutResult> affine_errors;
  if (affineApplicable(base, db.axes)) {
    const auto affine_start = Clock::now();
    db.affine = buildAffineTerms(base, db.axes, modes, backend);
    const AffineInterpolator interp(db);
    LeaveOneOutResult r;
    r.method = InterpolationMethod::Affine;
    r.frequency_error.assign(static_cast<std::size_t>(samples), -1.0);
    r.response_error.assign(static_cast<std::size_t>(samples), -1.0);
    for (int s = 0; s < samples; ++s) {
      const RomSample& sample = db.samples[static_cast<std::size_t>(s)];
      const ModalModel m = interp.evaluate(sample.parameters);
      const double w = sample.modal.omega_rad_s.minCoeff();
      r.frequency_error[s] = std::abs(m.omega_rad_s.minCoeff() - w) / w;
      r.response_error[s] = nrmse(relativeAccelerationSeries(sample.modal, drive, deploy),
                                  relativeAccelerationSeries(m, drive, deploy));
      ++r.estimated;
      r.max_frequency_error = std::max(r.max_frequency_error, r.frequency_error[s]);
      r.max_response_error = std::max(r.max_response_error, r.response_error[s]);
    }
    r.frequency_estimate = r.max_frequency_error;
    r.response_estimate = r.max_response_error;
    affine_errors = std::move(r);
    db.default_method = InterpolationMethod::Affine;
    timing.affine_s = secondsSince(affine_start);
  }

  // Every rank's block holds, method by method, its own samples (rank order = block order).
  for (const InterpolationMethod m : methods) {
    LeaveOneOutResult r;
    r.method = m;
    r.frequency_error.assign(static_cast<std::size_t>(samples), -1.0);
    r.response_error.assign(static_cast<std::size_t>(samples), -1.0);
    rep.leave_one_out.push_back(std::move(r));
  }
  {
    std::size_t pos = 0;
    for (int r = 0; r < size; ++r) {
      const int own = (samples - r + size - 1) / size;
      for (std::size_t m = 0; m < methods.size(); ++m) {
        for (int i = 0; i < own; ++i, pos += 3) {
          const int s = static_cast<int>(loo[pos]);
          rep.leave_one_out[m].frequency_error[s] = loo[pos + 1];
          rep.leave_one_out[m].response_error[s] = loo[pos + 2];
        }
      }
    }
  }
  for (LeaveOneOutResult& r : rep.leave_one_out) summarise(r, db.axes);
  if (affine_errors) rep.leave_one_out.push_back(std::move(*affine_errors));
  for (LeaveOneOutResult& r : rep.leave_one_out) {
    if (r.method == db.default_method) {
      for (int s = 0; s < samples; ++s) {
        db.samples[s].loo_frequency_error = r.frequency_error[s];
        db.samples[s].loo_response_error = r.response_error[s];
      }
    }
  }
  timing.wall_s = secondsSince(wall_start);
  rep.timing = timing;
  if (report) *report = std::move(rep);
  return db;
}

std::optional<RomDatabase> leaveOneOutStencil(const RomDatabase& db, int index) {
  const std::vector<int> multi = gridIndex(db.axes, index);
  RomDatabase sub;
  sub.base_config_toml = db.base_config_toml;
  sub.modes_per_sample = db.modes_per_sample;
  sub.default_method = db.default_method;
  sub.mastrom_version = db.mastrom_version;
  bool interior_somewhere = false;
  // Per axis: the original node indices the stencil keeps.
  std::vector<std::vector<int>> keep(db.axes.size());
  for (std::size_t a = 0; a < db.axes.size(); ++a) {
    const int n = static_cast<int>(db.axes[a].values.size());
    const int i = multi[a];
    ParameterAxis axis;
    axis.key = db.axes[a].key;
    if (i > 0 && i < n - 1) {
      interior_somewhere = true;
      keep[a] = {i - 1, i + 1};
    } else {
      for (int j = 0; j < n; ++j) keep[a].push_back(j);
    }
    for (const int j : keep[a]) axis.values.push_back(db.axes[a].values[j]);
    sub.axes.push_back(std::move(axis));
  }
  if (!interior_somewhere) return std::nullopt;
  long count = 1;
  for (const ParameterAxis& a : sub.axes) count *= static_cast<long>(a.values.size());
  sub.samples.reserve(static_cast<std::size_t>(count));
  for (int s = 0; s < count; ++s) {
    const std::vector<int> sub_multi = gridIndex(sub.axes, s);
    std::vector<int> original(db.axes.size());
    for (std::size_t a = 0; a < db.axes.size(); ++a) original[a] = keep[a][sub_multi[a]];
    sub.samples.push_back(db.samples[db.sampleIndex(original)]);
  }
  // The tracking and alignment stay relative to the full database's reference; the stencil's own
  // reference is its sample nearest the centre.
  std::vector<int> centre(sub.axes.size());
  for (std::size_t a = 0; a < sub.axes.size(); ++a)
    centre[a] = static_cast<int>(sub.axes[a].values.size() - 1) / 2;
  sub.reference_sample = sub.sampleIndex(centre);
  return sub;
}

double leaveOneOutScale(const std::vector<ParameterAxis>& axes, int index) {
  const std::vector<int> multi = gridIndex(axes, index);
  double scale = 0.0;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const std::vector<double>& v = axes[a].values;
    const int i = multi[a];
    if (i <= 0 || i + 1 >= static_cast<int>(v.size())) continue;
    // The coordinate the interpolants' weights are linear in: log p on a positive axis (the
    // manifold's default, ManifoldInterpolationOptions), p otherwise.
    const auto u = [&v](int j) { return v.front() > 0 ? std::log(v[j]) : v[j]; };
    const double h1 = u(i) - u(i - 1), h2 = u(i + 1) - u(i);
    scale = std::max(scale, std::max(h1, h2) * std::max(h1, h2) / (4.0 * h1 * h2));
  }
  return scale;
}

LeaveOneOutResult leaveOneOut(const RomDatabase& db, InterpolationMethod method,
                              const fullorder::DriveLaw& drive,
                              const ModalDeploymentOptions& options) {
  std::vector<std::vector<double>> exact_series;
  LeaveOneOutResult r = leaveOneOutShare(db, method, drive, options, 0, 1, exact_series);
  summarise(r, db.axes);
  return r;
}

}  // namespace mastrom::rom
