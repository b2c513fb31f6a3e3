// Small text helpers shared by the command-line parameter parsers (`rom build --param`,
// `screen --grid`): trimming and a strict number parse.
#pragma once

#include <cmath>
#include <cstdlib>
#include <string>

namespace mastrom::rom {

/// `s` without leading and trailing blanks and tabs.
inline std::string trimBlanks(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

/// Strict number: the whole (trimmed) text is one finite number.
inline bool parseStrictNumber(const std::string& text, double& out) {
  const std::string t = trimBlanks(text);
  if (t.empty()) return false;
  char* end = nullptr;
  out = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && std::isfinite(out);
}

}  // namespace mastrom::rom
