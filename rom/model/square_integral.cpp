// ∫ r² dt of the continuous ROM response by the Gramian of the free vibration (see the header and
// docs/theory.md §4.2a).
#include "rom/model/square_integral.hpp"

#include <Eigen/LU>

#include "common/error.hpp"

namespace mastrom::rom {

namespace {

/// The Sylvester block X of mode pair (i, j): A_iᵀX + X A_j = −c_iᵀc_j, with A = [0 1; −ω² −2ζω]
/// and c = ψ_z [−ω², −2ζω] (r = c y for the free part y = [y, ẏ]: ÿ = −ω²y − 2ζωẏ). Solvable when
/// no two eigenvalues add to zero, which a positive damping of every mode ensures (real parts
/// < 0). Solved in the energy coordinates [ωy, ẏ], where A = [0 ω; −ω −2ζω] and c = ψ_z [−ω, −2ζω]
/// have entries of one scale (in [y, ẏ] the 4 × 4 system mixes 1 and ω² ≈ 10⁹ and lost six
/// digits), then X = diag(ω_i, 1) X' diag(ω_j, 1). Column-major vec: vec(A_iᵀX) = (I ⊗ A_iᵀ) vec X,
/// vec(X A_j) = (A_jᵀ ⊗ I) vec X.
Eigen::Matrix2d sylvesterBlock(double omega_i, double d_i, double psi_i, double omega_j, double d_j,
                               double psi_j) {
  Eigen::Matrix2d a_i, a_j;
  a_i << 0.0, omega_i, -omega_i, -d_i;
  a_j << 0.0, omega_j, -omega_j, -d_j;
  const Eigen::RowVector2d c_i = psi_i * Eigen::RowVector2d(-omega_i, -d_i);
  const Eigen::RowVector2d c_j = psi_j * Eigen::RowVector2d(-omega_j, -d_j);
  const Eigen::Matrix2d rhs = -c_i.transpose() * c_j;
  Eigen::Matrix4d system = Eigen::Matrix4d::Zero();
  const Eigen::Matrix2d a_i_t = a_i.transpose();
  system.block<2, 2>(0, 0) += a_i_t;
  system.block<2, 2>(2, 2) += a_i_t;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) system.block<2, 2>(2 * r, 2 * c).diagonal().array() += a_j(c, r);
  const Eigen::Vector4d vec_rhs(rhs(0, 0), rhs(1, 0), rhs(0, 1), rhs(1, 1));
  const Eigen::Vector4d x = system.fullPivLu().solve(vec_rhs);
  Eigen::Matrix2d out;
  out << omega_i * x[0] * omega_j, omega_i * x[2], x[1] * omega_j, x[3];
  return out;
}

}  // namespace

bool SquareIntegral::supported(const ModalModel& m, const ModalStepping& ms) {
  if (ms.coriolis || ms.modes == 0) return false;
  return (m.omega_rad_s.array() > 0.0).all() && (m.damping_ratio.array() > 0.0).all() &&
         m.omega_rad_s.allFinite() && m.damping_ratio.allFinite();
}

SquareIntegral::SquareIntegral(const ModalModel& m, const ModalStepping& ms) : modes_(ms.modes) {
  MASTROM_REQUIRE(supported(m, ms), InputError,
                  "rom: the exact RMS integral needs every mode damped (omega > 0, zeta > 0) and "
                  "no Coriolis coupling");
  const int k = modes_;
  const Eigen::ArrayXd& stiffness = ms.stiffness;  // ω²
  const Eigen::ArrayXd& damping = ms.damping;      // 2ζω
  const Eigen::VectorXd psi = m.end_rotation.row(2).transpose();
  w_.resize(2 * k, 2 * k);
  for (int i = 0; i < k; ++i) {
    for (int j = i; j < k; ++j) {
      const Eigen::Matrix2d x = sylvesterBlock(m.omega_rad_s[i], damping[i], psi[i],
                                               m.omega_rad_s[j], damping[j], psi[j]);
      w_(i, j) = x(0, 0);
      w_(i, k + j) = x(0, 1);
      w_(k + i, j) = x(1, 0);
      w_(k + i, k + j) = x(1, 1);
      // W is symmetric (the right-hand side is): block (j, i) = Xᵀ.
      w_(j, i) = x(0, 0);
      w_(k + j, i) = x(0, 1);
      w_(j, k + i) = x(1, 0);
      w_(k + j, k + i) = x(1, 1);
    }
  }
  // The forcing f = Σ_s s g_s with the scalars (θ̈, θ̇², g_x, g_y) of forcingScalars and
  // g = (−Γ, −Γ_c, L_x, L_y); the particular part of a piece is P = Σ_s s a_s + ṡ b_s with
  // a = [g/ω²; 0] and b = [−2ζω g/ω⁴; g/ω²] (p = f/ω² − 2ζω ḟ/ω⁴, ṗ = ḟ/ω²).
  Eigen::MatrixXd basis(2 * k, 2 * kScalars);
  const Eigen::ArrayXd g[kScalars] = {-ms.gamma, -ms.gamma_c, ms.momentum_x, ms.momentum_y};
  for (int s = 0; s < kScalars; ++s) {
    basis.col(s).head(k) = (g[s] / stiffness).matrix();
    basis.col(s).tail(k).setZero();
    basis.col(kScalars + s).head(k) = (-damping * g[s] / stiffness.square()).matrix();
    basis.col(kScalars + s).tail(k) = (g[s] / stiffness).matrix();
  }
  const Eigen::MatrixXd h = basis.transpose() * w_;
  basis_ = basis;
  h_eta_ = h.leftCols(k);
  h_rate_ = h.rightCols(k);
  gram_ = h * basis;
}

double SquareIntegral::weightedProducts(const Vector8& weight, const Eigen::VectorXd& eta,
                                        const Eigen::VectorXd& eta_dot) const {
  double sum = 0.0;
  for (int r = 0; r < 2 * kScalars; ++r) {
    if (weight[r] == 0.0) continue;
    sum += weight[r] * (h_eta_.row(r).dot(eta.transpose()) + h_rate_.row(r).dot(eta_dot.transpose()));
  }
  return sum;
}

double SquareIntegral::quadratic(const Vector8& c) const {
  double sum = 0.0;
  for (int r = 0; r < 2 * kScalars; ++r) {
    if (c[r] == 0.0) continue;
    double row = 0.0;
    for (int q = 0; q < 2 * kScalars; ++q) row += gram_(r, q) * c[q];
    sum += c[r] * row;
  }
  return sum;
}

// Inline: as a call it returned the vector through memory written by scalar stores, and piece()
// read it back with 16-byte loads, which cannot be forwarded from those stores — two stalls per
// step, about half of piece()'s time in perf.
inline SquareIntegral::Vector8 SquareIntegral::coefficients(
    const stepping_detail::ForcingScalars& s, const stepping_detail::ForcingScalars& slope) {
  Vector8 c;
  c << s.acc, s.rate2, s.gx, s.gy, slope.acc, slope.rate2, slope.gx, slope.gy;
  return c;
}

double SquareIntegral::freeEnergy(const Eigen::VectorXd& eta,
                                  const Eigen::VectorXd& eta_dot) const {
  const int k = modes_;
  return eta.dot(w_.topLeftCorner(k, k) * eta) + 2.0 * eta.dot(w_.topRightCorner(k, k) * eta_dot) +
         eta_dot.dot(w_.bottomRightCorner(k, k) * eta_dot);
}

void SquareIntegral::start(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot) {
  eta_start_ = eta;
  rate_start_ = eta_dot;
  integral_ = 0.0;
  pending_ = false;
}

double SquareIntegral::freeEnergyAfter(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                                       const Vector8& c) const {
  // Y of the free part y = x − [a b] c.
  const Eigen::VectorXd p = basis_ * c;
  return freeEnergy(eta - p.head(modes_), eta_dot - p.tail(modes_));
}

void SquareIntegral::piece(double h_s, const stepping_detail::ForcingScalars& s0,
                           const stepping_detail::ForcingScalars& s1, const Eigen::VectorXd& eta,
                           const Eigen::VectorXd& eta_dot) {
  // ∫ over a piece = Y(y(0)) − Y(y(h)) with the free part y = x − P (4.5). Summed over the pieces,
  // the free parts telescope except where the particular part P changes between two pieces
  // (a jump of a forcing scalar or of its slope): there y jumps by −δ, δ = [a b] Δc, and
  //     Y(y − δ) − Y(y) = −2 Δcᵀ(H x − G c_end) + Δcᵀ G Δc,   H = [a b]ᵀW, G = [a b]ᵀW[a b],
  // with c_end the previous piece's end coefficients. Working with y, not x, keeps every term of
  // the size of the vibration: in x the quasi-static parts (large when r is small, as under a
  // smooth drive law) cancelled, and lost up to 3 % of such an RMS.
  if (h_s != last_h_) {  // a division per step was a tenth of this function's time
    last_h_ = h_s;
    inv_h_ = 1.0 / h_s;
  }
  const double inv_h = inv_h_;
  stepping_detail::ForcingScalars slope;
  slope.acc = (s1.acc - s0.acc) * inv_h;
  slope.rate2 = (s1.rate2 - s0.rate2) * inv_h;
  slope.gx = (s1.gx - s0.gx) * inv_h;
  slope.gy = (s1.gy - s0.gy) * inv_h;
  const Vector8 c0 = coefficients(s0, slope);
  if (!pending_) {
    integral_ = freeEnergyAfter(eta_start_, rate_start_, c0);
  } else {
    const Vector8 jump = c0 - pending_end_;
    if (!jump.isZero(0.0)) {
      integral_ += -2.0 * (weightedProducts(jump, eta, eta_dot) - jump.dot(gram_ * pending_end_)) +
                   quadratic(jump);
    }
  }
  pending_end_ = coefficients(s1, slope);
  pending_ = true;
}

double SquareIntegral::finish(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot) {
  if (pending_) integral_ -= freeEnergyAfter(eta, eta_dot, pending_end_);
  pending_ = false;
  return integral_;
}

}  // namespace mastrom::rom
