#include "rom/interpolation/tracked_interpolation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/error.hpp"
#include "fullorder/block_rotation.hpp"
#include "rom/interpolation/weighted_sum_batch.hpp"

namespace mastrom::rom {
namespace {

/// Offsets of the feature vector for k modes (see the header).
struct Layout {
  Eigen::Index k;
  Eigen::Index omega() const { return 0; }
  Eigen::Index zeta() const { return k; }
  Eigen::Index gamma() const { return 2 * k; }
  Eigen::Index gamma_c() const { return 3 * k; }
  Eigen::Index psi() const { return 4 * k; }
  Eigen::Index translation() const { return 7 * k; }
  Eigen::Index momentum() const { return 10 * k; }
  Eigen::Index coriolis() const { return 13 * k; }
  // The rigid data of the reference configuration after the per-mode blocks.
  Eigen::Index inertia() const { return 13 * k + k * k; }  // J
  Eigen::Index mass() const { return inertia() + 1; }       // m
  Eigen::Index centroid() const { return mass() + 1; }      // c̄ (3)
  Eigen::Index end_position() const { return centroid() + 3; }  // p̄ (3)
  Eigen::Index angle() const { return end_position() + 3; }     // θ₀
  Eigen::Index gravity() const { return angle() + 1; }          // g (3)
  Eigen::Index size() const { return gravity() + 3; }
};

Eigen::VectorXd features(const RomSample& s, int k, bool rotate, bool logarithmic) {
  const ModalModel& m = s.modal;
  const Layout l{k};
  Eigen::VectorXd f(l.size());
  // Back to the stowed frame when θ₀ varies (R(−θ₀)); identity otherwise (no rounding at all).
  const Eigen::Matrix3d back =
      rotate ? fullorder::rotationAboutZ(-m.reference_angle_rad) : Eigen::Matrix3d::Identity();
  for (int j = 0; j < k; ++j) {
    const int i = s.tracking[j];
    const double sg = s.tracking_sign[j];
    // log ω (> 0: checked by the constructor) or ω.
    f[l.omega() + j] = logarithmic ? std::log(m.omega_rad_s[i]) : m.omega_rad_s[i];
    f[l.zeta() + j] = m.damping_ratio[i];
    f[l.gamma() + j] = sg * m.rotation_participation[i];
    f[l.gamma_c() + j] = sg * m.centrifugal_participation[i];
    const Eigen::Vector3d psi = sg * m.end_rotation.col(i);
    const Eigen::Vector3d tr = sg * m.end_translation.col(i);
    const Eigen::Vector3d mo = sg * m.momentum_participation.col(i);
    f.segment<3>(l.psi() + 3 * j) = rotate ? Eigen::Vector3d(back * psi) : psi;
    f.segment<3>(l.translation() + 3 * j) = rotate ? Eigen::Vector3d(back * tr) : tr;
    f.segment<3>(l.momentum() + 3 * j) = rotate ? Eigen::Vector3d(back * mo) : mo;
    for (int r = 0; r < k; ++r) {
      const double c = m.coriolis.size() == 0 ? 0.0 : m.coriolis(s.tracking[r], i);
      f[l.coriolis() + r + static_cast<Eigen::Index>(k) * j] = s.tracking_sign[r] * sg * c;
    }
  }
  f[l.inertia()] = m.inertia_z_kg_m2;
  f[l.mass()] = m.total_mass_kg;
  f.segment<3>(l.centroid()) = rotate ? Eigen::Vector3d(back * m.centroid_m) : m.centroid_m;
  f.segment<3>(l.end_position()) =
      rotate ? Eigen::Vector3d(back * m.end_position_m) : m.end_position_m;
  f[l.angle()] = m.reference_angle_rad;
  f.segment<3>(l.gravity()) = m.gravity_m_s2;
  return f;
}

}  // namespace

TrackedInterpolator::TrackedInterpolator(const RomDatabase& db, AxisWeighting weighting,
                                         int degree)
    : logarithmic_(weighting == AxisWeighting::Logarithmic), degree_(degree) {
  MASTROM_REQUIRE(degree_ >= 1, InputError, "rom: interpolation degree ", degree_,
                  " must be >= 1");
  MASTROM_REQUIRE(!db.axes.empty(), InputError, "rom database: no parameter axes");
  std::size_t count = 1;
  for (const ParameterAxis& a : db.axes) {
    MASTROM_REQUIRE(!a.values.empty(), InputError, "rom database: axis ", a.key, " has no values");
    for (std::size_t i = 0; i < a.values.size(); ++i) {
      MASTROM_REQUIRE(std::isfinite(a.values[i]) && (i == 0 || a.values[i] > a.values[i - 1]),
                      InputError, "rom database: the values of axis ", a.key,
                      " are not finite and strictly ascending");
    }
    count *= a.values.size();
    axes_.push_back(a);
  }
  MASTROM_REQUIRE(db.isGrid(), InputError,
                  "rom: the tracked and cubic methods need a tensor-grid database; this one has "
                  "scattered samples (use the rbf method)");
  MASTROM_REQUIRE(db.samples.size() == count, InputError, "rom database: ", db.samples.size(),
                  " samples for a grid of ", count);
  addSamples(db);
}

TrackedInterpolator::TrackedInterpolator(const RomDatabase& db, RadialBasisTag,
                                         int tail_degree) {
  MASTROM_REQUIRE(!db.axes.empty(), InputError, "rom database: no parameter axes");
  MASTROM_REQUIRE(!db.samples.empty(), InputError, "rom database: no samples");
  axes_ = db.axes;
  std::vector<std::vector<double>> points;
  for (const RomSample& s : db.samples) points.push_back(s.parameters);
  rbf_.emplace(db.axes, points, tail_degree);
  addSamples(db);
}

std::unique_ptr<TrackedInterpolator> TrackedInterpolator::radialBasis(const RomDatabase& db,
                                                                     int tail_degree) {
  return std::unique_ptr<TrackedInterpolator>(
      new TrackedInterpolator(db, RadialBasisTag{}, tail_degree));
}

void TrackedInterpolator::addSamples(const RomDatabase& db) {
  const std::size_t count = db.samples.size();
  modes_ = static_cast<int>(db.samples.front().tracking.size());
  MASTROM_REQUIRE(modes_ >= 1, InputError, "rom database: samples carry no mode tracking");
  const double theta0 = db.samples.front().modal.reference_angle_rad;
  for (const RomSample& s : db.samples) rotate_ = rotate_ || s.modal.reference_angle_rad != theta0;
  features_.reserve(count);
  for (std::size_t n = 0; n < count; ++n) {
    const RomSample& s = db.samples[n];
    const int k_s = s.modal.modeCount();
    MASTROM_REQUIRE(static_cast<int>(s.tracking.size()) == modes_ &&
                        static_cast<int>(s.tracking_sign.size()) == modes_ && k_s >= modes_,
                    InputError, "rom database: sample ", n, " tracks ", s.tracking.size(),
                    " of its ", k_s, " modes, expected ", modes_);
    std::vector<char> seen(static_cast<std::size_t>(k_s), 0);
    for (int j = 0; j < modes_; ++j) {
      const int i = s.tracking[j];
      MASTROM_REQUIRE(
          i >= 0 && i < k_s && !seen[i] && (s.tracking_sign[j] == 1 || s.tracking_sign[j] == -1),
          InputError, "rom database: sample ", n,
          " has an invalid mode tracking (not a one-to-one matching with signs ±1)");
      seen[i] = 1;
    }
    s.modal.validate();
    MASTROM_REQUIRE(!logarithmic_ || (s.modal.omega_rad_s.array() > 0.0).all(), InputError,
                    "rom database: sample ", n,
                    " has a frequency <= 0 (logarithmic interpolation needs ω > 0)");
    features_.push_back(features(s, modes_, rotate_, logarithmic_));
    // Stresses (docs/theory.md §6.5): plane stresses in element frames, which the rigid rotation
    // θ₀ does not change — no back-rotation, only the tracking's permutation and signs.
    const ModalStress& st = s.modal.stress;
    if (st.empty()) continue;
    const Eigen::Index rows = st.modes.rows();
    Eigen::MatrixXd f(rows, modes_ + kStressLoadCount + 1);
    for (int j = 0; j < modes_; ++j) f.col(j) = s.tracking_sign[j] * st.modes.col(s.tracking[j]);
    f.middleCols(modes_, kStressLoadCount) = st.loads;
    f.col(modes_ + kStressLoadCount) = st.preload;
    stress_features_.push_back(std::move(f));
    stress_points_.push_back(st.points);
    stress_damping_.push_back(st.damping_s);
    stress_offsets_ = st.interface_offsets;
  }
  MASTROM_REQUIRE(stress_features_.empty() || stress_features_.size() == count, InputError,
                  "rom database: some samples carry stresses and some do not");
}

ModalModel TrackedInterpolator::evaluate(const std::vector<double>& parameters) const {
  return evaluateModel(parameters, false);
}

ModalModel TrackedInterpolator::evaluateWithStresses(const std::vector<double>& parameters) const {
  return evaluateModel(parameters, true);
}

std::vector<GridWeight> TrackedInterpolator::weightsAt(const std::vector<double>& parameters) const {
  if (rbf_) return rbf_->weights(parameters);
  const AxisWeighting weighting =
      logarithmic_ ? AxisWeighting::Logarithmic : AxisWeighting::Linear;
  return degree_ == 1 ? multilinearWeights(axes_, parameters, weighting)
                      : lagrangeWeights(axes_, parameters, degree_, weighting);
}

namespace {

/// The modes in ascending interpolated ω.
std::vector<int> ascendingOrder(const Eigen::VectorXd& f, const Layout& l) {
  std::vector<int> order(static_cast<std::size_t>(l.k));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&f, &l](int a, int b) { return f[l.omega() + a] < f[l.omega() + b]; });
  return order;
}

}  // namespace

ModalModel TrackedInterpolator::modelFromFeatures(const Eigen::VectorXd& f) const {
  const Layout l{modes_};
  MASTROM_REQUIRE(f.size() == l.size(), InputError, "rom: a feature vector of ", f.size(),
                  " entries for ", modes_, " modes (expected ", l.size(), ")");
  const int k = modes_;
  const std::vector<int> order = ascendingOrder(f, l);
  const double theta0 = f[l.angle()];
  const Eigen::Matrix3d forward =
      rotate_ ? fullorder::rotationAboutZ(theta0) : Eigen::Matrix3d::Identity();
  ModalModel m;
  m.resizeModes(k, true);
  for (int jj = 0; jj < k; ++jj) {
    const int j = order[jj];
    m.omega_rad_s[jj] =
        logarithmic_ ? std::exp(f[l.omega() + j]) : std::max(0.0, f[l.omega() + j]);
    m.damping_ratio[jj] = std::max(0.0, f[l.zeta() + j]);
    m.rotation_participation[jj] = f[l.gamma() + j];
    m.centrifugal_participation[jj] = f[l.gamma_c() + j];
    const Eigen::Vector3d psi = f.segment<3>(l.psi() + 3 * j);
    const Eigen::Vector3d tr = f.segment<3>(l.translation() + 3 * j);
    const Eigen::Vector3d mo = f.segment<3>(l.momentum() + 3 * j);
    m.end_rotation.col(jj) = rotate_ ? Eigen::Vector3d(forward * psi) : psi;
    m.end_translation.col(jj) = rotate_ ? Eigen::Vector3d(forward * tr) : tr;
    m.momentum_participation.col(jj) = rotate_ ? Eigen::Vector3d(forward * mo) : mo;
    for (int ii = 0; ii < k; ++ii)
      m.coriolis(ii, jj) = f[l.coriolis() + order[ii] + static_cast<Eigen::Index>(k) * j];
  }
  // J and m are positive at every sample; linear extrapolation far outside could cross zero.
  m.inertia_z_kg_m2 = std::max(f[l.inertia()], 1e-300);
  m.total_mass_kg = std::max(f[l.mass()], 1e-300);
  const Eigen::Vector3d c = f.segment<3>(l.centroid()), pe = f.segment<3>(l.end_position());
  m.centroid_m = rotate_ ? Eigen::Vector3d(forward * c) : c;
  m.end_position_m = rotate_ ? Eigen::Vector3d(forward * pe) : pe;
  m.reference_angle_rad = theta0;
  m.gravity_m_s2 = f.segment<3>(l.gravity());
  return m;
}

Eigen::VectorXd TrackedInterpolator::featuresAt(const std::vector<double>& parameters) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(Layout{modes_}.size());
  for (const GridWeight& w : weightsAt(parameters))
    f.noalias() += w.weight * features_[static_cast<std::size_t>(w.sample)];
  return f;
}

Eigen::VectorXd TrackedInterpolator::featuresOf(const RomSample& sample) const {
  return features(sample, modes_, rotate_, logarithmic_);
}

ModalModel TrackedInterpolator::evaluateModel(const std::vector<double>& parameters,
                                              bool stresses) const {
  if (stresses && !stress_features_.empty())
    return std::move(evaluateWithStressesAt({parameters}).front());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(Layout{modes_}.size());
  for (const GridWeight& w : weightsAt(parameters))
    f.noalias() += w.weight * features_[static_cast<std::size_t>(w.sample)];
  return modelFromFeatures(f);
}

std::vector<ModalModel> TrackedInterpolator::evaluateWithStressesAt(
    const std::vector<std::vector<double>>& points) const {
  const Layout l{modes_};
  std::vector<std::vector<GridWeight>> weights;
  std::vector<Eigen::VectorXd> features;
  std::vector<ModalModel> models;
  for (const std::vector<double>& p : points) {
    weights.push_back(weightsAt(p));
    Eigen::VectorXd f = Eigen::VectorXd::Zero(l.size());
    for (const GridWeight& w : weights.back())
      f.noalias() += w.weight * features_[static_cast<std::size_t>(w.sample)];
    models.push_back(modelFromFeatures(f));
    features.push_back(std::move(f));
  }
  if (stress_features_.empty()) return models;
  // Batches of points whose weights name the same samples in the same order.
  const auto same_samples = [&](std::size_t a, std::size_t b) {
    return std::equal(
        weights[a].begin(), weights[a].end(), weights[b].begin(), weights[b].end(),
        [](const GridWeight& x, const GridWeight& y) { return x.sample == y.sample; });
  };
  std::vector<char> done(points.size(), 0);
  for (std::size_t first = 0; first < points.size(); ++first) {
    if (done[first]) continue;
    std::vector<std::size_t> batch;
    for (std::size_t b = first; b < points.size(); ++b)
      if (!done[b] && same_samples(first, b)) batch.push_back(b), done[b] = 1;
    addStresses(weights, features, batch, models);
  }
  return models;
}

void TrackedInterpolator::addStresses(const std::vector<std::vector<GridWeight>>& weights,
                                      const std::vector<Eigen::VectorXd>& features,
                                      const std::vector<std::size_t>& batch,
                                      std::vector<ModalModel>& models) const {
  const Layout l{modes_};
  const int k = modes_;
  const std::vector<GridWeight>& samples = weights[batch.front()];
  const Eigen::Index rows = stress_features_.front().rows();
  const Eigen::Index cols = k + kStressLoadCount + 1;
  std::vector<const double*> sources;
  for (const GridWeight& w : samples)
    sources.push_back(stress_features_[static_cast<std::size_t>(w.sample)].data());
  std::vector<double> w_batch;
  std::vector<Eigen::MatrixXd> sf(batch.size(), Eigen::MatrixXd(rows, cols));
  std::vector<double*> out;
  for (std::size_t b = 0; b < batch.size(); ++b) {
    for (const GridWeight& w : weights[batch[b]]) w_batch.push_back(w.weight);
    out.push_back(sf[b].data());
  }
  weightedSumBatch(sources, static_cast<long>(rows * cols), w_batch, out);
  for (std::size_t b = 0; b < batch.size(); ++b) {
    const std::vector<int> order = ascendingOrder(features[batch[b]], l);  // modelFromFeatures'
    Eigen::MatrixXd points = Eigen::MatrixXd::Zero(2, stress_points_.front().cols());
    double damping = 0.0;
    for (const GridWeight& w : weights[batch[b]]) {
      const auto n = static_cast<std::size_t>(w.sample);
      points.noalias() += w.weight * stress_points_[n];
      damping += w.weight * stress_damping_[n];
    }
    ModalStress& st = models[batch[b]].stress;
    st.interface_offsets = stress_offsets_;
    st.modes.resize(rows, k);
    for (int jj = 0; jj < k; ++jj) st.modes.col(jj) = sf[b].col(order[jj]);
    st.loads = sf[b].middleCols(k, kStressLoadCount);
    st.preload = sf[b].col(k + kStressLoadCount);
    st.points = points;
    st.damping_s = std::max(0.0, damping);
  }
}

}  // namespace mastrom::rom
