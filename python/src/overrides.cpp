#include "python/src/overrides.hpp"

#include <charconv>
#include <cstdio>

namespace py = pybind11;

namespace mastrom::python {
namespace {

/// The shortest decimal that reads back as the same double: the spelling the command line's user
/// would type for it, so both reach the configuration through the same characters. Non-finite
/// values come out as TOML's inf/nan, which the configuration then rejects with its own message.
std::string shortestDouble(double v) {
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

/// A TOML basic string: quotes, backslashes and control characters escaped.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(u));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

std::string tomlValue(py::handle value) {
  // bool before int: Python's bool is an int. NumPy's bool_ is neither a bool nor an Integral.
  const py::module_ numbers = py::module_::import("numbers");
  if (py::isinstance<py::bool_>(value) ||
      py::isinstance(value, py::module_::import("numpy").attr("bool_")))
    return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return quoted(value.cast<std::string>());
  if (py::isinstance(value, numbers.attr("Integral")))
    return py::str(py::int_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
  if (py::isinstance(value, numbers.attr("Real"))) return shortestDouble(value.cast<double>());
  if (py::hasattr(value, "__iter__") && !py::isinstance<py::bytes>(value)) {
    std::string out = "[";
    for (const py::handle item : value) out += (out.size() > 1 ? ", " : "") + tomlValue(item);
    return out + "]";
  }
  throw py::type_error("mastrom: cannot use a value of type " +
                       py::type::of(value).attr("__name__").cast<std::string>() +
                       " in a configuration (allowed: bool, int, float, str, or a sequence)");
}

std::vector<std::string> overridesFrom(py::handle set) {
  std::vector<std::string> overrides;
  if (set.is_none()) return overrides;
  if (py::isinstance<py::str>(set))
    throw py::type_error(
        "mastrom: set= takes a mapping {\"section.key\": value} or a list of "
        "\"section.key=value\" strings, not one string");
  if (py::hasattr(set, "items")) {
    for (const py::handle item : set.attr("items")()) {
      const py::tuple kv = py::reinterpret_borrow<py::tuple>(item);
      if (!py::isinstance<py::str>(kv[0]))
        throw py::type_error("mastrom: set= keys are strings such as \"interface.thickness\"");
      overrides.push_back(kv[0].cast<std::string>() + "=" + tomlValue(kv[1]));
    }
    return overrides;
  }
  for (const py::handle item : set) {
    if (!py::isinstance<py::str>(item))
      throw py::type_error("mastrom: set= entries are \"section.key=value\" strings");
    overrides.push_back(item.cast<std::string>());
  }
  return overrides;
}

}  // namespace mastrom::python
