// TOML text → table, safely: a byte scan that keeps toml++ away from text it would mishandle, and
// toml++'s parse errors as InputError with the source, line and column.
#include "common/config_detail.hpp"

#include <algorithm>
#include <string>

#include "common/error.hpp"

namespace mastrom::config_detail {

/// Offset of the first non-ASCII byte outside strings and comments, or npos. TOML 1.0 allows
/// non-ASCII text only inside strings and comments (bare keys, numbers, booleans and dates are
/// ASCII), so such a byte is always a syntax error — but toml++ 3.3.0 (Debian 12) reaches
/// __builtin_unreachable() on it wherever it skips whitespace (is_non_ascii_horizontal_whitespace,
/// code points U+00A1…U+0499 and others; upstream marzer/tomlplusplus#190), i.e. undefined
/// behaviour instead of an error. Found by fuzz/fuzz_config.cpp with UBSan ("a = 1 §"). The scan
/// follows TOML's lexical structure: # comments to the end of the line, "basic" strings with
/// backslash escapes, 'literal' strings and their triple-quoted multi-line forms. A quote opens a
/// string only where TOML lets a key or value start (after = [ , { . or at a line start): toml++
/// does not read `-9.8"""…` as a number and a string, and must not meet the text after it.
std::size_t firstBareNonAscii(std::string_view s) {
  enum class State { Normal, Comment, Basic, Literal, MultiBasic, MultiLiteral };
  State state = State::Normal;
  char previous = '\n';  // last significant character in the Normal state
  const auto at = [&s](std::size_t i, const char* three) { return s.compare(i, 3, three) == 0; };
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    switch (state) {
      case State::Normal: {
        if (static_cast<unsigned char>(c) >= 0x80) return i;
        if (c == ' ' || c == '\t' || c == '\r') break;
        const bool can_open = previous == '\n' || previous == '=' || previous == '[' ||
                              previous == ',' || previous == '{' || previous == '.';
        previous = c;
        if (c == '#') {
          state = State::Comment;
        } else if (!can_open) {
          break;
        } else if (at(i, "\"\"\"")) {
          state = State::MultiBasic;
          i += 2;
        } else if (at(i, "'''")) {
          state = State::MultiLiteral;
          i += 2;
        } else if (c == '"') {
          state = State::Basic;
        } else if (c == '\'') {
          state = State::Literal;
        }
        break;
      }
      case State::Comment:
        if (c == '\n') {
          state = State::Normal;
          previous = '\n';
        }
        break;
      case State::Basic:
        if (c == '\\')
          ++i;  // the escaped character cannot close the string
        else if (c == '"' || c == '\n')
          state = State::Normal;
        break;
      case State::Literal:
        if (c == '\'' || c == '\n') state = State::Normal;
        break;
      case State::MultiBasic:
        if (c == '\\') {
          ++i;
        } else if (at(i, "\"\"\"")) {
          state = State::Normal;
          i += 2;
        }
        break;
      case State::MultiLiteral:
        if (at(i, "'''")) {
          state = State::Normal;
          i += 2;
        }
        break;
    }
  }
  return std::string_view::npos;
}

toml::table parseToml(std::string_view text, std::string_view source_name) {
  if (const std::size_t bad = firstBareNonAscii(text); bad != std::string_view::npos) {
    const std::string_view before = text.substr(0, bad);
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
    const std::size_t line_start = before.rfind('\n');
    const std::size_t column =
        bad - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
    throw InputError(detail::concat(kPrefix, source_name, ":", line, ":", column,
                                    ": TOML syntax error: a non-ASCII character outside a string "
                                    "or comment (keys and non-string values are ASCII)"));
  }
  try {
    return toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    std::string what(e.description());
    for (char& ch : what)
      if (ch == '\n' || ch == '\r') ch = ' ';
    throw InputError(detail::concat(kPrefix, source_name, ":", e.source().begin.line, ":",
                                    e.source().begin.column, ": TOML syntax error: ", what));
  }
}

}  // namespace mastrom::config_detail
