// Generic operations on the fields of a ModalModel (rom/model/modal_model.hpp, forEachModalField): their
// sizes, and their values as flat row-major runs of doubles — what the database file, its checksum
// and the MPI gather of a build exchange. One implementation per field *type*, so a new field
// needs no edit here.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "rom/model/modal_model.hpp"

namespace mastrom::rom {

/// The dimensions of one sample's field with k modes ({} for a scalar), row-major.
std::vector<std::size_t> modalFieldDims(ModalFieldShape shape, std::size_t k);

/// Number of values of one sample's field with k modes.
std::size_t modalFieldSize(ModalFieldShape shape, std::size_t k);

/// Append the field's values, row-major (a k-vector as one row).
inline void appendRowMajor(std::vector<double>& out, double x) { out.push_back(x); }
template <class Derived>
void appendRowMajor(std::vector<double>& out, const Eigen::DenseBase<Derived>& x) {
  for (Eigen::Index r = 0; r < x.rows(); ++r)
    for (Eigen::Index c = 0; c < x.cols(); ++c) out.push_back(x(r, c));
}

/// Resize the field to its shape for k modes and fill it from `data`, row-major; returns the number
/// of values read (modalFieldSize).
inline std::size_t readRowMajor(double& x, ModalFieldShape, Eigen::Index, const double* data) {
  x = data[0];
  return 1;
}
std::size_t readRowMajor(Eigen::Vector3d& x, ModalFieldShape shape, Eigen::Index k,
                         const double* data);
std::size_t readRowMajor(Eigen::VectorXd& x, ModalFieldShape shape, Eigen::Index k,
                         const double* data);
std::size_t readRowMajor(Eigen::Matrix3Xd& x, ModalFieldShape shape, Eigen::Index k,
                         const double* data);
std::size_t readRowMajor(Eigen::MatrixXd& x, ModalFieldShape shape, Eigen::Index k,
                         const double* data);

/// The names and shapes of the model's fields, in forEachModalField order.
std::vector<ModalFieldInfo> modalFieldList();

}  // namespace mastrom::rom
