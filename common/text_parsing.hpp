// Small text helpers shared by the parsers of numbers in text (`rom build --param`, `screen --grid`,
// drive tables): trimming, a strict number parse, and the shortest text of a double.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace mastrom {

/// `s` without leading and trailing blanks and tabs.
inline std::string trimBlanks(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

/// The pieces of `text` between the separators, as they are (not trimmed); one piece when there
/// is no separator.
/// Shortest text of a double that reads back bit-exactly (std::to_chars), for messages and files.
inline std::string shortestText(double v) {
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

inline std::vector<std::string> splitAt(const std::string& text, char separator) {
  std::vector<std::string> parts;
  for (std::size_t start = 0;;) {
    const std::size_t at = text.find(separator, start);
    parts.push_back(text.substr(start, at == std::string::npos ? at : at - start));
    if (at == std::string::npos) break;
    start = at + 1;
  }
  return parts;
}

/// Strict number: the whole (trimmed) text is one finite number.
inline bool parseStrictNumber(const std::string& text, double& out) {
  const std::string t = trimBlanks(text);
  if (t.empty()) return false;
  char* end = nullptr;
  out = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && std::isfinite(out);
}

}  // namespace mastrom
