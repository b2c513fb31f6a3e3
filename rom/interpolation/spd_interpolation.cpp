#include "rom/interpolation/spd_interpolation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "common/error.hpp"
#include "modes/mode_basis.hpp"
#include "fullorder/block_rotation.hpp"

namespace mastrom::rom {
namespace {


std::string describeSample(const RomDatabase& db, std::size_t s) {
  std::string out = "sample " + std::to_string(s) + " (";
  const RomSample& sample = db.samples[s];
  for (std::size_t a = 0; a < db.axes.size() && a < sample.parameters.size(); ++a)
    out += (a ? ", " : "") + db.axes[a].key + " = " + detail::concat(sample.parameters[a]);
  return out + ")";
}

}  // namespace

ManifoldInterpolator::ManifoldInterpolator(const RomDatabase& db,
                                           const ManifoldInterpolationOptions& options)
    : axes_(db.axes), options_(options) {
  MASTROM_REQUIRE(!db.axes.empty(), InputError, "rom database: no parameter axes");
  {
    std::vector<double> origin;
    for (const ParameterAxis& a : db.axes) origin.push_back(a.values.empty() ? 0.0 : a.values[0]);
    multilinearWeights(db.axes, origin, options_.weighting);  // validates every axis
  }
  std::size_t count = 1;
  for (const ParameterAxis& a : db.axes) count *= a.values.size();
  MASTROM_REQUIRE(db.samples.size() == count, InputError, "rom database: ", db.samples.size(),
                  " samples for a grid of ", count);
  MASTROM_REQUIRE(db.reference_sample >= 0 && db.reference_sample < static_cast<int>(count),
                  InputError, "rom database: reference sample ", db.reference_sample,
                  " outside the grid of ", count);
  const RomSample& ref = db.samples[static_cast<std::size_t>(db.reference_sample)];
  modes_ = ref.modal.modeCount();
  MASTROM_REQUIRE(modes_ >= 1, InputError, "rom database: the reference sample has no modes");
  gravity_ = ref.modal.gravity_m_s2;
  for (const RomSample& s : db.samples) {
    rotate_ = rotate_ || s.modal.reference_angle_rad != ref.modal.reference_angle_rad;
    coriolis_ = coriolis_ && s.modal.coriolis.size() != 0;
  }

  // Aligned stiffness of every sample; the reference's is the base point of the log map.
  std::vector<Eigen::MatrixXd> stiffness(count);
  for (std::size_t n = 0; n < count; ++n) {
    const RomSample& s = db.samples[n];
    const ModalModel& m = s.modal;
    m.validate();
    const Eigen::MatrixXd& q = s.alignment;
    MASTROM_REQUIRE(q.rows() == m.modeCount() && q.cols() == modes_, InputError,
                    "rom database: ", describeSample(db, n), " has a ", q.rows(), " × ", q.cols(),
                    " alignment for ", m.modeCount(), " modes (expected ", m.modeCount(), " × ",
                    modes_, ")");
    const double orth = (q.transpose() * q - Eigen::MatrixXd::Identity(modes_, modes_))
                            .cwiseAbs()
                            .maxCoeff();
    MASTROM_REQUIRE(q.allFinite() && orth <= 1e-8, InputError, "rom database: the alignment of ",
                    describeSample(db, n), " is not orthonormal (max|QᵀQ − I| = ", orth, ")");
    MASTROM_REQUIRE((m.gravity_m_s2 - gravity_).norm() <= 1e-12 * (1.0 + gravity_.norm()),
                    InputError, "rom database: gravity differs between ", describeSample(db, n),
                    " and the reference sample");
    const Eigen::VectorXd w2 = m.omega_rad_s.cwiseAbs2();
    Eigen::MatrixXd k;
    k.noalias() = q.transpose() * w2.asDiagonal() * q;
    stiffness[n] = 0.5 * (k + k.transpose());
  }
  if (options_.metric == SpdMetric::AffineInvariant)
    base_ = std::make_unique<SpdBasePoint>(
        stiffness[static_cast<std::size_t>(db.reference_sample)],
        "aligned stiffness of the reference " +
            describeSample(db, static_cast<std::size_t>(db.reference_sample)));

  samples_.resize(count);
  for (std::size_t n = 0; n < count; ++n) {
    const RomSample& s = db.samples[n];
    const ModalModel& m = s.modal;
    const Eigen::MatrixXd& q = s.alignment;
    Aligned& a = samples_[n];
    const std::string what = "aligned stiffness of " + describeSample(db, n);
    a.log_stiffness = base_ ? base_->logWhitened(stiffness[n], what) : spdLog(stiffness[n], what);
    const Eigen::VectorXd c2 = 2.0 * m.damping_ratio.cwiseProduct(m.omega_rad_s);
    a.damping.noalias() = q.transpose() * c2.asDiagonal() * q;
    a.gamma.noalias() = q.transpose() * m.rotation_participation;
    a.gamma_c.noalias() = q.transpose() * m.centrifugal_participation;
    const Eigen::Matrix3d back =
        rotate_ ? fullorder::rotationAboutZ(-m.reference_angle_rad) : Eigen::Matrix3d::Identity();
    a.psi.noalias() = back * m.end_rotation * q;
    a.translation.noalias() = back * m.end_translation * q;
    a.momentum.noalias() = back * m.momentum_participation * q;
    if (coriolis_) a.coriolis.noalias() = q.transpose() * m.coriolis * q;
    a.inertia = m.inertia_z_kg_m2;
    a.mass = m.total_mass_kg;
    a.theta0 = m.reference_angle_rad;
    a.centroid = back * m.centroid_m;
    a.end_position = back * m.end_position_m;
    // Stresses in element frames: unchanged by θ₀; aligned like the mode shapes (Φ̃ = ΦQ).
    const ModalStress& st = m.stress;
    if (!st.empty()) {
      a.stress.resize(st.modes.rows(), modes_ + kStressLoadCount + 1);
      a.stress.leftCols(modes_).noalias() = st.modes * q;
      a.stress.middleCols(modes_, kStressLoadCount) = st.loads;
      a.stress.col(modes_ + kStressLoadCount) = st.preload;
      a.stress_points = st.points;
      a.stress_damping = st.damping_s;
      stress_offsets_ = st.interface_offsets;
    }
    MASTROM_REQUIRE(st.empty() == (samples_.front().stress.size() == 0), InputError,
                    "rom database: some samples carry stresses and some do not");
  }
}

Eigen::MatrixXd ManifoldInterpolator::alignedStiffness(
    const std::vector<double>& parameters) const {
  const std::vector<GridWeight> weights = multilinearWeights(axes_, parameters, options_.weighting);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(modes_, modes_);
  for (const GridWeight& w : weights)
    x.noalias() += w.weight * samples_[static_cast<std::size_t>(w.sample)].log_stiffness;
  return expLog(x);
}

Eigen::MatrixXd ManifoldInterpolator::expLog(const Eigen::MatrixXd& x) const {
  return base_ ? base_->expWhitened(x, "interpolated aligned stiffness")
               : symmetricExp(x, "interpolated aligned stiffness");
}

ModalModel ManifoldInterpolator::evaluate(const std::vector<double>& parameters) const {
  return evaluateModel(parameters, false);
}

ModalModel ManifoldInterpolator::evaluateWithStresses(const std::vector<double>& parameters) const {
  return evaluateModel(parameters, true);
}

ModalModel ManifoldInterpolator::evaluateModel(const std::vector<double>& parameters,
                                               bool stresses) const {
  const std::vector<GridWeight> weights = multilinearWeights(axes_, parameters, options_.weighting);
  const int k = modes_;

  // Everything but the stiffness: linear in the weights.
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(k, k), damping = Eigen::MatrixXd::Zero(k, k);
  Eigen::MatrixXd coriolis = Eigen::MatrixXd::Zero(coriolis_ ? k : 0, coriolis_ ? k : 0);
  Eigen::VectorXd gamma = Eigen::VectorXd::Zero(k), gamma_c = Eigen::VectorXd::Zero(k);
  Eigen::Matrix3Xd psi = Eigen::Matrix3Xd::Zero(3, k), translation = Eigen::Matrix3Xd::Zero(3, k);
  Eigen::Matrix3Xd momentum = Eigen::Matrix3Xd::Zero(3, k);
  double inertia = 0.0, mass = 0.0, theta0 = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), end_position = Eigen::Vector3d::Zero();
  for (const GridWeight& gw : weights) {
    const Aligned& a = samples_[static_cast<std::size_t>(gw.sample)];
    const double w = gw.weight;
    x.noalias() += w * a.log_stiffness;
    damping.noalias() += w * a.damping;
    if (coriolis_) coriolis.noalias() += w * a.coriolis;
    gamma.noalias() += w * a.gamma;
    gamma_c.noalias() += w * a.gamma_c;
    psi.noalias() += w * a.psi;
    translation.noalias() += w * a.translation;
    momentum.noalias() += w * a.momentum;
    inertia += w * a.inertia;
    mass += w * a.mass;
    theta0 += w * a.theta0;
    centroid.noalias() += w * a.centroid;
    end_position.noalias() += w * a.end_position;
  }

  // The stiffness on the manifold, then its eigenvectors: the rotation from aligned to modal
  // coordinates at p (Φ(p) = Φ̃ Y).
  const Eigen::MatrixXd stiffness = expLog(x);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(stiffness);
  MASTROM_REQUIRE(es.info() == Eigen::Success, NumericalError,
                  "rom: the eigensolver of the interpolated reduced stiffness did not converge");
  Eigen::MatrixXd y = es.eigenvectors();
  modes::normaliseColumnSigns(y);

  const Eigen::Matrix3d forward = rotate_ ? fullorder::rotationAboutZ(theta0) : Eigen::Matrix3d::Identity();
  ModalModel m;
  m.omega_rad_s = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::MatrixXd modal_damping = y.transpose() * damping * y;
  m.damping_ratio.resize(k);
  for (int j = 0; j < k; ++j)
    m.damping_ratio[j] =
        m.omega_rad_s[j] > 0 ? std::max(0.0, modal_damping(j, j)) / (2.0 * m.omega_rad_s[j]) : 0.0;
  m.rotation_participation.noalias() = y.transpose() * gamma;
  m.centrifugal_participation.noalias() = y.transpose() * gamma_c;
  m.end_rotation.noalias() = forward * psi * y;
  m.end_translation.noalias() = forward * translation * y;
  m.momentum_participation.noalias() = forward * momentum * y;
  if (coriolis_) m.coriolis.noalias() = y.transpose() * coriolis * y;
  // J and m are positive at every sample; linear extrapolation far outside could cross zero.
  m.inertia_z_kg_m2 = std::max(inertia, 1e-300);
  m.total_mass_kg = std::max(mass, 1e-300);
  m.centroid_m = forward * centroid;
  m.end_position_m = forward * end_position;
  m.reference_angle_rad = theta0;
  m.gravity_m_s2 = gravity_;
  if (stresses && stress_offsets_.size() > 0) {
    const Aligned& first = samples_.front();
    Eigen::MatrixXd sf = Eigen::MatrixXd::Zero(first.stress.rows(), first.stress.cols());
    Eigen::Matrix2Xd points = Eigen::Matrix2Xd::Zero(2, first.stress_points.cols());
    double mu = 0.0;
    for (const GridWeight& gw : weights) {
      const Aligned& a = samples_[static_cast<std::size_t>(gw.sample)];
      sf.noalias() += gw.weight * a.stress;
      points.noalias() += gw.weight * a.stress_points;
      mu += gw.weight * a.stress_damping;
    }
    ModalStress& st = m.stress;
    st.interface_offsets = stress_offsets_;
    st.modes.noalias() = sf.leftCols(k) * y;  // Φ(p) = Φ̃ Y
    st.loads = sf.middleCols(k, kStressLoadCount);
    st.preload = sf.col(k + kStressLoadCount);
    st.points = points;
    st.damping_s = std::max(0.0, mu);
  }
  return m;
}

std::unique_ptr<ModalInterpolator> makeManifoldInterpolator(
    const RomDatabase& db, const ManifoldInterpolationOptions& options) {
  return std::make_unique<ManifoldInterpolator>(db, options);
}

}  // namespace mastrom::rom
