// Values as text, for messages and for toToml() (see config_detail.hpp).
#include "common/config_detail.hpp"


#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <system_error>
#include <tuple>

#include "common/drive_table.hpp"
#include "common/error.hpp"
#include "common/text_parsing.hpp"


namespace mastrom::config_detail {

// ---------------------------------------------------------------------------------------------
// Formatting of values, for messages and for toToml().

/// Shortest text that reads back to the same double (std::to_chars round-trip guarantee).
std::string formatDouble(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

/// A double as a TOML float literal: "2700" would read back as an integer, so write "2700.0".
std::string tomlFloat(double v) {
  std::string s = formatDouble(v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string tomlString(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char esc[8];
          std::snprintf(esc, sizeof esc, "\\u%04x", static_cast<unsigned>(c));
          out += esc;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

/// Six significant digits, for derived values shown in comments.
std::string formatShort(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string tomlVec3(const std::array<double, 3>& v) {
  return "[" + tomlFloat(v[0]) + ", " + tomlFloat(v[1]) + ", " + tomlFloat(v[2]) + "]";
}

std::string formatVec3(const std::array<double, 3>& v) {
  return "[" + formatDouble(v[0]) + ", " + formatDouble(v[1]) + ", " + formatDouble(v[2]) + "]";
}

/// Any TOML node as one line of TOML-like text (the "value" part of an error message).
std::string formatNode(const toml::node& node) {
  if (const auto* s = node.as_string()) return tomlString(s->get());
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* f = node.as_floating_point()) return tomlFloat(f->get());  // "4.0", not "4"
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* a = node.as_array()) {
    std::string out = "[";
    for (std::size_t k = 0; k < a->size(); ++k) out += (k ? ", " : "") + formatNode(*a->get(k));
    return out + "]";
  }
  if (const auto* t = node.as_table()) {
    std::string out = "{";
    bool first = true;
    for (auto&& [key, value] : *t) {
      out += (first ? "" : ", ") + std::string(key.str()) + " = " + formatNode(value);
      first = false;
    }
    return out + "}";
  }
  std::ostringstream os;  // dates and times: toml++ prints them in TOML syntax
  node.visit([&os](const auto& concrete) { os << concrete; });
  return os.str();
}

std::string joinKeys(const std::vector<std::string>& keys) {
  std::string out;
  for (const std::string& k : keys) out += (out.empty() ? "" : ", ") + k;
  return out;
}

std::string allowedSections() {
  std::vector<std::string> names(kSections.begin(), kSections.end());
  return joinKeys(names);
}

}  // namespace mastrom::config_detail
