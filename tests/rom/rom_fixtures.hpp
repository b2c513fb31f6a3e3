// Synthetic ROM databases for the database, interpolation and screening tests: every per-mode
// quantity of reference slot j is a bilinear function of two parameters, and each sample stores
// its modes permuted and with flipped signs (recorded in its tracking), as a real build would.
// Seeded: the same data on every run and every rank.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "common/config.hpp"
#include "rom/database/rom_database.hpp"

namespace mastrom::rom::testing {

/// Per-slot coefficients of q(x, y) = c0 + c1 x + c2 y + c3 x y for every modal quantity.
struct BilinearModel {
  int modes = 4;
  Eigen::MatrixXd coefficients;  ///< (quantities × 4), see value()
  /// Quantity count: ω, ζ, Γ, Γc (k each), ψ, T, L (3k each), Coriolis (k²), J, m, c̄, p̄.
  static int quantities(int k) { return 13 * k + k * k + 8; }
  /// The modal model in reference-slot order at (x, y), normalised parameters in [0, 1].
  ModalModel value(double x, double y) const {
    const int k = modes;
    const Eigen::VectorXd q = coefficients.col(0) + x * coefficients.col(1) +
                              y * coefficients.col(2) + x * y * coefficients.col(3);
    ModalModel m;
    int o = 0;
    const auto take = [&](int n) {
      Eigen::VectorXd v = q.segment(o, n);
      o += n;
      return v;
    };
    m.omega_rad_s = take(k);
    m.damping_ratio = take(k);
    m.rotation_participation = take(k);
    m.centrifugal_participation = take(k);
    m.end_rotation = Eigen::Map<const Eigen::Matrix3Xd>(take(3 * k).data(), 3, k);
    m.end_translation = Eigen::Map<const Eigen::Matrix3Xd>(take(3 * k).data(), 3, k);
    m.momentum_participation = Eigen::Map<const Eigen::Matrix3Xd>(take(3 * k).data(), 3, k);
    m.coriolis = Eigen::Map<const Eigen::MatrixXd>(take(k * k).data(), k, k);
    m.inertia_z_kg_m2 = q[o++];
    m.total_mass_kg = q[o++];
    m.centroid_m = take(3);
    m.end_position_m = q.segment<3>(o);
    return m;
  }
};

inline BilinearModel randomBilinearModel(int k, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BilinearModel b;
  b.modes = k;
  b.coefficients =
      Eigen::MatrixXd::NullaryExpr(BilinearModel::quantities(k), 4, [&]() { return u(rng); });
  // Frequencies well separated and ascending everywhere, damping and J, m positive.
  for (int j = 0; j < k; ++j) {
    b.coefficients.row(j) << 100.0 * (j + 1), 10.0 * u(rng), 10.0 * u(rng), 5.0 * u(rng);
    b.coefficients.row(k + j) << 0.01 + 0.001 * j, 0.001 * std::abs(u(rng)),
        0.001 * std::abs(u(rng)), 0.0;
  }
  const int rigid = 13 * k + k * k;
  b.coefficients.row(rigid) << 0.3, 0.05, 0.02, 0.01;
  b.coefficients.row(rigid + 1) << 2.0, 0.2, 0.1, 0.0;
  return b;
}

/// Store `m` (slot order) as a sample: modes permuted by `perm` (sample mode perm[j] = slot j) and
/// multiplied by `sign[j]`; the tracking records exactly that.
inline RomSample scrambledSample(const ModalModel& m, const std::vector<int>& perm,
                                 const std::vector<int>& sign) {
  const int k = m.modeCount();
  RomSample s;
  ModalModel& o = s.modal;
  o = m;
  for (int j = 0; j < k; ++j) {
    const int i = perm[j];
    o.omega_rad_s[i] = m.omega_rad_s[j];
    o.damping_ratio[i] = m.damping_ratio[j];
    o.rotation_participation[i] = sign[j] * m.rotation_participation[j];
    o.centrifugal_participation[i] = sign[j] * m.centrifugal_participation[j];
    o.end_rotation.col(i) = sign[j] * m.end_rotation.col(j);
    o.end_translation.col(i) = sign[j] * m.end_translation.col(j);
    o.momentum_participation.col(i) = sign[j] * m.momentum_participation.col(j);
    for (int r = 0; r < k; ++r) o.coriolis(perm[r], i) = sign[r] * sign[j] * m.coriolis(r, j);
  }
  s.tracking = perm;
  s.tracking_sign = sign;
  s.alignment = Eigen::MatrixXd::Identity(k, k);
  return s;
}

/// A database on the grid x ∈ xs, y ∈ ys (parameters interface.thickness and module.mass, values
/// mapped to [0, 1] for the bilinear model), every sample scrambled at random.
inline RomDatabase bilinearDatabase(const BilinearModel& b, const std::vector<double>& xs,
                                    const std::vector<double>& ys, unsigned seed) {
  std::mt19937 rng(seed);
  RomDatabase db;
  Config base;
  base.mast.modules = 2;
  base.interface.elements_axial = 1;
  base.interface.elements_circumferential = 6;
  base.simulation.time_step_s = 1e-3;
  base.interface.thickness_m = xs.front();
  base.module.mass_kg = ys.front();
  db.base_config_toml = toToml(base);
  db.axes = {{"interface.thickness", xs}, {"module.mass", ys}};
  db.modes_per_sample = b.modes;
  db.default_method = InterpolationMethod::Tracked;
  db.mastrom_version = "test";
  for (std::size_t iy = 0; iy < ys.size(); ++iy) {
    for (std::size_t ix = 0; ix < xs.size(); ++ix) {
      const double x = (xs[ix] - xs.front()) / (xs.back() - xs.front());
      const double y = (ys[iy] - ys.front()) / (ys.back() - ys.front());
      std::vector<int> perm(static_cast<std::size_t>(b.modes));
      std::iota(perm.begin(), perm.end(), 0);
      std::shuffle(perm.begin(), perm.end(), rng);
      std::vector<int> sign;
      for (int j = 0; j < b.modes; ++j) sign.push_back(rng() % 2 ? 1 : -1);
      RomSample s = scrambledSample(b.value(x, y), perm, sign);
      s.parameters = {xs[ix], ys[iy]};
      s.alignment = Eigen::MatrixXd::NullaryExpr(b.modes, b.modes, [&rng]() {
        return std::uniform_real_distribution<double>(-1, 1)(rng);
      });
      s.loo_frequency_error = ix == 1 ? 0.01 * static_cast<double>(iy + 1) : -1.0;
      s.loo_response_error = ix == 1 ? 0.02 : -1.0;
      db.samples.push_back(std::move(s));
    }
  }
  db.reference_sample =
      db.sampleIndex({static_cast<int>(xs.size() - 1) / 2, static_cast<int>(ys.size() - 1) / 2});
  return db;
}

}  // namespace mastrom::rom::testing
