// mastrom.Config: a resolved, validated run configuration (common/config.hpp), immutable. Values
// are read by their dotted key, as written in the TOML file and on the command line's --set:
// cfg["interface.thickness"] → 0.002 (SI units, degrees only in the *_deg keys).
#include <pybind11/stl.h>
#include <toml++/toml.h>

#include <sstream>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/error.hpp"
#include "python/src/bindings.hpp"
#include "python/src/overrides.hpp"

namespace py = pybind11;

namespace mastrom::python {
namespace {

py::object toPython(const toml::node& node) {
  if (const auto* v = node.as_floating_point()) return py::float_(v->get());
  if (const auto* v = node.as_integer()) return py::int_(v->get());
  if (const auto* v = node.as_boolean()) return py::bool_(v->get());
  if (const auto* v = node.as_string()) return py::str(v->get());
  if (const auto* a = node.as_array()) {
    py::list out;
    for (const toml::node& item : *a) out.append(toPython(item));
    return std::move(out);
  }
  throw UsageError("mastrom: unexpected TOML node in a resolved configuration");
}

/// Every key of the resolved configuration, in file order, with its Python value. Derived values
/// the file leaves implicit are filled in: the mid-surface radius (also when the inner diameter is
/// given) and the principal inertia of the modules (the solid cube when not given).
std::vector<std::pair<std::string, py::object>> items(const Config& config) {
  const std::string text = toToml(config);
  const toml::table table = toml::parse(text);
  // toml++ iterates a table in key order; the file order (what a person reads in the TOML) comes
  // from the text itself: "[section]" lines and "key = value" lines.
  std::vector<std::pair<std::string, py::object>> out;
  std::istringstream lines(text);
  std::string line, section;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (line[0] == '[') {
      section = line.substr(1, line.find(']') - 1);
      continue;
    }
    const std::string key = line.substr(0, line.find_first_of(" ="));
    const toml::node* node = table.at_path(section + "." + key).node();
    if (node != nullptr) out.emplace_back(section + "." + key, toPython(*node));
  }
  const auto has = [&out](const std::string& key) {
    for (const auto& kv : out)
      if (kv.first == key) return true;
    return false;
  };
  if (!has("interface.radius"))
    out.emplace_back("interface.radius", py::float_(config.interface.radius_m));
  if (!has("module.inertia")) {
    const std::array<double, 3> I = config.module.principalInertia();
    out.emplace_back("module.inertia", py::cast(std::vector<double>(I.begin(), I.end())));
  }
  return out;
}

py::object lookup(const Config& config, const std::string& key) {
  for (auto& [k, v] : items(config))
    if (k == key) return v;
  if (key == "interface.inner_diameter")
    throw py::key_error(
        "interface.inner_diameter is not set: this configuration gives "
        "interface.radius");
  throw py::key_error(key +
                      " is not a configuration key (keys look like 'interface.thickness'; "
                      "Config.keys() lists them)");
}

std::string shortRepr(const Config& c) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "<mastrom.Config: %d modules, interface h = %.6g m, R = %.6g m, L = %.6g m, "
                "E = %.6g Pa; %s drive, %.6g deg in %.6g s>",
                c.mast.modules, c.interface.thickness_m, c.interface.radius_m, c.interface.length_m,
                c.material.youngs_modulus_pa, toString(c.drive.law).c_str(), c.drive.angle_deg,
                c.drive.duration_s);
  return buf;
}

}  // namespace

void bindConfig(py::module_& m) {
  py::class_<Config>(m, "Config",
                     R"doc(A resolved, validated run configuration (immutable).

Every key of the TOML file is optional; the defaults are the paper's Scheme 3 (README, table of
keys). Values are SI (m, kg, Pa, s, rad/s^2); only the *_deg keys are in degrees. Read a value with
cfg["section.key"]; derive a changed copy with cfg.replace({"section.key": value}).

Config() is the default configuration; Config.load(path, set=...) reads a file;
Config.from_toml(text, set=...) parses TOML text.)doc")
      .def(py::init<>(), "The default configuration (Scheme 3: 4 modules, aluminium interfaces).")
      .def_static(
          "load",
          [](const std::string& path, py::handle set) {
            return loadConfig(path, overridesFrom(set));
          },
          py::arg("path"), py::arg("set") = py::none(),
          R"doc(Read a TOML file and apply overrides, as `mastrom CMD CONFIG --set k=v ...` does.

path: the TOML file. set: None, a mapping {"section.key": value} (bool, int, float, str or a
sequence; applied in order) or a list of "section.key=value" strings. Raises InputError (a
ValueError) naming the key, the value and the allowed range; FileError (an OSError) when the file
cannot be read.)doc")
      .def_static(
          "from_toml",
          [](const std::string& text, py::handle set) {
            return applyConfigOverrides(parseConfigText(text, "<string>"), overridesFrom(set));
          },
          py::arg("text"), py::arg("set") = py::none(),
          "Parse TOML text (the format of the configuration files), then apply `set` like load.")
      .def(
          "replace",
          [](const Config& self, py::handle set) {
            return applyConfigOverrides(self, overridesFrom(set));
          },
          py::arg("set"),
          "A copy with overrides applied ({\"section.key\": value} or \"section.key=value\" "
          "strings), validated again.")
      .def(
          "to_toml", [](const Config& self) { return toToml(self); },
          "The resolved configuration as TOML text, every key present, units in comments; "
          "Config.from_toml(cfg.to_toml()) == cfg.")
      .def("__getitem__", &lookup, py::arg("key"),
           "The value of 'section.key' (float, int, str, bool or list; SI units). KeyError for an "
           "unknown key.")
      .def("__contains__",
           [](const Config& self, const std::string& key) {
             for (const auto& kv : items(self))
               if (kv.first == key) return true;
             return false;
           })
      .def(
          "keys",
          [](const Config& self) {
            py::list keys;
            for (const auto& kv : items(self)) keys.append(kv.first);
            return keys;
          },
          "Every key, 'section.key', in file order.")
      .def(
          "to_dict",
          [](const Config& self) {
            py::dict d;
            for (const auto& [k, v] : items(self)) d[py::str(k)] = v;
            return d;
          },
          "{'section.key': value} of every key (the derived radius and inertia included).")
      .def(
          "__eq__", [](const Config& a, const Config& b) { return a == b; }, py::is_operator())
      .def("__repr__", &shortRepr);
}

}  // namespace mastrom::python
