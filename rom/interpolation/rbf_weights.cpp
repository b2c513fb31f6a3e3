// Polyharmonic-spline weights over scattered samples (see rbf_weights.hpp).
#include "rom/interpolation/rbf_weights.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::rom {
namespace {

/// φ(r) = r³.
double kernel(double r) { return r * r * r; }

bool logarithmicAxis(const ParameterAxis& a) { return a.values.front() > 0.0; }

/// Terms of the polynomial tail of degree 1 or 2 in p variables.
Eigen::Index tailSize(Eigen::Index p, int degree) {
  return degree == 1 ? p + 1 : (p + 1) * (p + 2) / 2;
}

}  // namespace

int radialBasisMinimumSamples(int parameters, int tail_degree) {
  return static_cast<int>(tailSize(parameters, tail_degree)) + 1;
}

Eigen::VectorXd boxCoordinates(const std::vector<ParameterAxis>& axes,
                               const std::vector<double>& parameters) {
  MASTROM_REQUIRE(parameters.size() == axes.size(), InputError, "rom: ", parameters.size(),
                  " parameter values for ", axes.size(), " database axes");
  Eigen::VectorXd u(static_cast<Eigen::Index>(axes.size()));
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const ParameterAxis& axis = axes[a];
    MASTROM_REQUIRE(axis.values.size() >= 2 && axis.values.back() > axis.values.front(),
                    InputError, "rom database: axis ", axis.key, " spans no range");
    const double x = parameters[a], lo = axis.values.front(), hi = axis.values.back();
    MASTROM_REQUIRE(std::isfinite(x), InputError, "rom: ", axis.key, " = ", x, " is not finite");
    const auto i = static_cast<Eigen::Index>(a);
    if (logarithmicAxis(axis)) {
      MASTROM_REQUIRE(x > 0.0, InputError, "rom: ", axis.key, " = ", x,
                      " must be > 0 (logarithmic coordinates on an axis of positive values)");
      u[i] = std::log(x / lo) / std::log(hi / lo);
    } else {
      u[i] = (x - lo) / (hi - lo);
    }
  }
  return u;
}

std::vector<double> boxPoint(const std::vector<ParameterAxis>& axes, const Eigen::VectorXd& u) {
  std::vector<double> p(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const double lo = axes[a].values.front(), hi = axes[a].values.back();
    const double t = u[static_cast<Eigen::Index>(a)];
    // The ends exactly: a design's corner is the box's corner, bit for bit.
    p[a] = t == 0.0   ? lo
           : t == 1.0 ? hi
           : logarithmicAxis(axes[a]) ? lo * std::pow(hi / lo, t)
                                      : lo + t * (hi - lo);
  }
  return p;
}

RadialBasisWeights::RadialBasisWeights(const std::vector<ParameterAxis>& axes,
                                       const std::vector<std::vector<double>>& points,
                                       int tail_degree)
    : axes_(axes), points_(points), tail_degree_(tail_degree) {
  const auto n = static_cast<Eigen::Index>(points.size());
  const auto p = static_cast<Eigen::Index>(axes.size());
  MASTROM_REQUIRE(p >= 1, InputError, "rom database: no parameter axes");
  MASTROM_REQUIRE(tail_degree == 1 || tail_degree == 2, InputError,
                  "rom: radial-basis tail degree ", tail_degree, " (1 or 2)");
  const Eigen::Index q = tailSize(p, tail_degree);
  const int fewest = radialBasisMinimumSamples(static_cast<int>(p), tail_degree);
  MASTROM_REQUIRE(n >= fewest, InputError, "rom: radial-basis interpolation over ", p,
                  " parameters needs at least ", fewest, " samples, the database has ", n);
  u_.resize(p, n);
  for (Eigen::Index s = 0; s < n; ++s)
    u_.col(s) = boxCoordinates(axes, points[static_cast<std::size_t>(s)]);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n + q, n + q);
  Eigen::MatrixXd tail(n, q);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < j; ++i) {
      const double r = (u_.col(i) - u_.col(j)).norm();
      MASTROM_REQUIRE(r > 1e-12, InputError, "rom database: samples ", i, " and ", j,
                      " coincide (radial-basis interpolation needs distinct samples)");
      m(i, j) = m(j, i) = kernel(r);
    }
    tail.row(j) = tailOf(u_.col(j)).transpose();
  }
  m.topRightCorner(n, q) = tail;
  m.bottomLeftCorner(q, n) = tail.transpose();
  MASTROM_REQUIRE(Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(tail).rank() == q, InputError,
                  "rom database: the samples do not determine the polynomial tail (they lie on ",
                  tail_degree == 1 ? "one hyperplane" : "one quadric",
                  " of the box; radial-basis interpolation needs them to span every direction)");
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(m);
  inverse_ = lu.inverse();
  MASTROM_REQUIRE(inverse_.allFinite(), NumericalError,
                  "rom: the radial-basis system of the samples is singular");
}

Eigen::VectorXd RadialBasisWeights::tailOf(const Eigen::VectorXd& u) const {
  const Eigen::Index p = u.size();
  Eigen::VectorXd t(tailSize(p, tail_degree_));
  t[0] = 1.0;
  t.segment(1, p) = u;
  if (tail_degree_ == 2) {
    Eigen::Index k = p + 1;
    for (Eigen::Index a = 0; a < p; ++a)
      for (Eigen::Index b = a; b < p; ++b) t[k++] = u[a] * u[b];
  }
  return t;
}

Eigen::VectorXd RadialBasisWeights::rightHandSide(const Eigen::VectorXd& u) const {
  const Eigen::Index n = u_.cols();
  Eigen::VectorXd beta(inverse_.rows());
  for (Eigen::Index s = 0; s < n; ++s) beta[s] = kernel((u - u_.col(s)).norm());
  beta.tail(beta.size() - n) = tailOf(u);
  return beta;
}

std::vector<GridWeight> RadialBasisWeights::weights(const std::vector<double>& parameters) const {
  const Eigen::VectorXd u = boxCoordinates(axes_, parameters);
  for (std::size_t s = 0; s < points_.size(); ++s)
    if (points_[s] == parameters) return {GridWeight{static_cast<int>(s), 1.0}};
  const Eigen::Index n = u_.cols();
  // M⁻¹ is symmetric: the weights are its first N rows times β.
  const Eigen::VectorXd w = inverse_.topRows(n) * rightHandSide(u);
  std::vector<GridWeight> out(static_cast<std::size_t>(n));
  for (Eigen::Index s = 0; s < n; ++s) out[static_cast<std::size_t>(s)] = {static_cast<int>(s), w[s]};
  return out;
}

double RadialBasisWeights::powerFunction(const std::vector<double>& parameters) const {
  const Eigen::VectorXd beta = rightHandSide(boxCoordinates(axes_, parameters));
  // −βᵀM⁻¹β is ≥ 0 in exact arithmetic; round-off leaves a tiny negative at a sample.
  return std::sqrt(std::max(0.0, -beta.dot(inverse_ * beta)));
}

Eigen::VectorXd RadialBasisWeights::powerFunctions(
    const std::vector<std::vector<double>>& points) const {
  const Eigen::Index m = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd beta(inverse_.rows(), m);
  for (Eigen::Index j = 0; j < m; ++j)
    beta.col(j) = rightHandSide(boxCoordinates(axes_, points[static_cast<std::size_t>(j)]));
  Eigen::MatrixXd product(inverse_.rows(), m);
  product.noalias() = inverse_ * beta;
  Eigen::VectorXd power(m);
  for (Eigen::Index j = 0; j < m; ++j)
    power[j] = std::sqrt(std::max(0.0, -beta.col(j).dot(product.col(j))));
  return power;
}

double RadialBasisWeights::leaveOneOutPower(int k) const {
  return 1.0 / std::sqrt(inverse_(k, k));
}

Eigen::MatrixXd RadialBasisWeights::leaveOneOutErrors(const Eigen::MatrixXd& data) const {
  const Eigen::Index n = u_.cols();
  MASTROM_REQUIRE(data.rows() == n, InputError, "rom: leave-one-out data has ", data.rows(),
                  " rows for ", n, " samples");
  // c = (M⁻¹)_{1..N,1..N} f (the tail's right-hand side is 0), e_k = c_k / (M⁻¹)_kk.
  Eigen::MatrixXd c = inverse_.topLeftCorner(n, n) * data;
  for (Eigen::Index k = 0; k < n; ++k) c.row(k) /= inverse_(k, k);
  return c;
}

int RadialBasisWeights::nearestSample(const std::vector<double>& parameters) const {
  const Eigen::VectorXd u = boxCoordinates(axes_, parameters);
  Eigen::Index best = 0;
  (u_.colwise() - u).colwise().squaredNorm().minCoeff(&best);
  return static_cast<int>(best);
}

}  // namespace mastrom::rom
