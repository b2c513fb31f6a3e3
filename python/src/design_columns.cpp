#include "python/src/design_columns.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <string>

#include "python/src/arrays.hpp"

namespace py = pybind11;

namespace mastrom::python {
namespace {

/// One design column from a Python value: a str or a sequence of str (names), else numbers.
/// Scalars are kept as one value and broadcast later.
rom::DesignColumn designColumn(const std::string& key, py::handle value) {
  rom::DesignColumn c;
  c.key = key;
  if (py::isinstance<py::str>(value)) {
    c.names.push_back(value.cast<std::string>());
    return c;
  }
  const py::array a = py::array::ensure(value);
  if (a && (a.dtype().kind() == 'U' || a.dtype().kind() == 'O' || a.dtype().kind() == 'S')) {
    for (const py::handle item : value) {
      if (!py::isinstance<py::str>(item))
        throw py::type_error("RomDatabase.screen: " + key +
                             ": a column is either numbers or names (str), not a mix");
      c.names.push_back(item.cast<std::string>());
    }
    return c;
  }
  const auto numbers =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!numbers || numbers.ndim() > 1)
    throw py::type_error("RomDatabase.screen: " + key +
                         ": expected a number, a 1-D array of numbers, or names (str)");
  c.values.assign(numbers.data(), numbers.data() + numbers.size());
  return c;
}

std::size_t lengthOf(const rom::DesignColumn& c) {
  return c.names.empty() ? c.values.size() : c.names.size();
}

}  // namespace

std::vector<rom::DesignColumn> designColumns(py::handle designs) {
  if (!py::hasattr(designs, "items"))
    throw py::type_error("RomDatabase.screen: designs takes a mapping {\"key\": array}");
  std::vector<rom::DesignColumn> columns;
  std::vector<bool> scalar;
  for (const py::handle item : designs.attr("items")()) {
    const py::tuple kv = py::reinterpret_borrow<py::tuple>(item);
    columns.push_back(designColumn(kv[0].cast<std::string>(), kv[1]));
    scalar.push_back(py::isinstance<py::str>(kv[1]) || py::array::ensure(kv[1]).ndim() == 0);
  }
  // NumPy-style broadcasting of scalars against the arrays (which must agree in length).
  std::size_t n = 1;
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (!scalar[c]) {
      n = lengthOf(columns[c]);
      break;
    }
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (!scalar[c]) continue;
    if (columns[c].names.empty())
      columns[c].values.assign(n, columns[c].values.front());
    else
      columns[c].names.assign(n, columns[c].names.front());
  }
  return columns;
}

py::dict screenTableDict(const std::vector<rom::DesignColumn>& columns,
                         const rom::DesignScreenTable& table) {
  py::dict out;
  for (const rom::DesignColumn& c : columns) {
    if (c.names.empty())
      out[py::str(c.key)] = copyVector(Eigen::Map<const Eigen::VectorXd>(
          c.values.data(), static_cast<Eigen::Index>(c.values.size())));
    else
      out[py::str(c.key)] = py::array(py::cast(c.names));
  }
  const std::size_t q = table.metric_names.size();
  const auto rows = static_cast<py::ssize_t>(table.designs);
  for (std::size_t j = 0; j < q; ++j) {
    const bool flag = table.metric_names[j] == "settled";
    py::array column =
        flag ? py::array(py::array_t<bool>(rows)) : py::array(py::array_t<double>(rows));
    for (py::ssize_t i = 0; i < rows; ++i) {
      const double v = table.metrics[static_cast<std::size_t>(i) * q + j];
      if (flag)
        static_cast<bool*>(column.mutable_data())[i] = v != 0.0;
      else
        static_cast<double*>(column.mutable_data())[i] = v;
    }
    out[py::str(table.metric_names[j])] = column;
  }
  return out;
}

}  // namespace mastrom::python
