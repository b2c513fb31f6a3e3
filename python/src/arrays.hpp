// NumPy arrays out of the library's containers. Long time series are handed over without a copy:
// the container moves into a capsule that the arrays keep alive (a 8 s deployment at 0.1 ms is
// 80 001 samples × 25 columns, whose copy would cost as much as the ROM deployment itself).
// Small results (modes, metrics) are copied. Every array is float64 unless stated otherwise.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "fullorder/deployment_result.hpp"

namespace mastrom::python {

/// Copy of a vector: shape (n,).
pybind11::array_t<double> copyVector(const Eigen::Ref<const Eigen::VectorXd>& v);
/// Copy of a matrix, C order: shape (rows, cols).
pybind11::array_t<double> copyMatrix(const Eigen::Ref<const Eigen::MatrixXd>& m);
/// Copy of row-major data: shape (rows, cols).
pybind11::array_t<double> copyRows(const std::vector<double>& data, std::size_t rows,
                                   std::size_t cols);

/// The scalar metrics of a deployment as a dict of floats (settled as bool), keys as in the files'
/// /metrics group.
pybind11::dict metricsDict(const fullorder::DeploymentMetrics& metrics);

/// The series as a dict of arrays keyed like the datasets of a deployment file without the leading
/// slash: "time" (N,), "drive/angle", "drive/rate", "drive/acceleration" (N,),
/// "end/angular_acceleration" (N, 3), "end/relative_angular_acceleration" (N,), "end/position",
/// "end/acceleration", "joint/force" (N, 3), "joint/torque" (N,), "solver/newton_iterations" (N,)
/// int32, "solver/constraint_residual" (N,). The arrays share one moved-in copy of the series.
pybind11::dict seriesDict(fullorder::DeploymentSeries series);

}  // namespace mastrom::python
