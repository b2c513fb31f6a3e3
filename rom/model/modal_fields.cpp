// Generic field operations of the modal model (see modal_fields.hpp).
#include "rom/model/modal_fields.hpp"

#include "common/error.hpp"

namespace mastrom::rom {
namespace {

template <class Matrix>
std::size_t fillRowMajor(Matrix& x, Eigen::Index rows, Eigen::Index cols, const double* data) {
  x.resize(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r)
    for (Eigen::Index c = 0; c < cols; ++c) x(r, c) = data[r * cols + c];
  return static_cast<std::size_t>(rows * cols);
}

void requireShape(bool ok, ModalFieldShape shape) {
  MASTROM_REQUIRE(ok, UsageError, "modal field: shape ", static_cast<int>(shape),
                  " does not match the field's type");
}

}  // namespace

std::vector<std::size_t> modalFieldDims(ModalFieldShape shape, std::size_t k) {
  switch (shape) {
    case ModalFieldShape::Scalar:
      return {};
    case ModalFieldShape::Vector3:
      return {3};
    case ModalFieldShape::PerMode:
      return {k};
    case ModalFieldShape::Vector3PerMode:
      return {3, k};
    case ModalFieldShape::ModeByMode:
      return {k, k};
  }
  return {};
}

std::size_t modalFieldSize(ModalFieldShape shape, std::size_t k) {
  std::size_t n = 1;
  for (std::size_t d : modalFieldDims(shape, k)) n *= d;
  return n;
}

std::size_t readRowMajor(Eigen::Vector3d& x, ModalFieldShape shape, Eigen::Index,
                         const double* data) {
  requireShape(shape == ModalFieldShape::Vector3, shape);
  for (int i = 0; i < 3; ++i) x[i] = data[i];
  return 3;
}

std::size_t readRowMajor(Eigen::VectorXd& x, ModalFieldShape shape, Eigen::Index k,
                         const double* data) {
  requireShape(shape == ModalFieldShape::PerMode, shape);
  x.resize(k);
  for (Eigen::Index i = 0; i < k; ++i) x[i] = data[i];
  return static_cast<std::size_t>(k);
}

std::size_t readRowMajor(Eigen::Matrix3Xd& x, ModalFieldShape shape, Eigen::Index k,
                         const double* data) {
  requireShape(shape == ModalFieldShape::Vector3PerMode, shape);
  return fillRowMajor(x, 3, k, data);
}

std::size_t readRowMajor(Eigen::MatrixXd& x, ModalFieldShape shape, Eigen::Index k,
                         const double* data) {
  requireShape(shape == ModalFieldShape::ModeByMode, shape);
  return fillRowMajor(x, k, k, data);
}

std::vector<ModalFieldInfo> modalFieldList() {
  std::vector<ModalFieldInfo> list;
  const ModalModel probe;
  forEachModalField(probe, [&](const ModalFieldInfo& info, const auto&) { list.push_back(info); });
  return list;
}

}  // namespace mastrom::rom
