// Error types and always-on checks for mastrom.
//
// What can fail, and how each is reported:
//  * what a user can get wrong (config keys, CLI arguments, files) → InputError / IoError, thrown by
//    MASTROM_REQUIRE, always on, with a one-line message naming the key, the value and the allowed range;
//  * numerical failure (Newton divergence, eigensolver breakdown) → NumericalError, carrying context
//    (time, residuals) in its message;
//  * a library function called against its contract by other code → UsageError (never
//    std::invalid_argument or std::logic_error, so that one catch of mastrom::Error sees them all).
// Internal invariants use MASTROM_ASSERT, compiled out in release builds (NDEBUG).
#pragma once

#include <cassert>
#include <sstream>
#include <stdexcept>
#include <string>

namespace mastrom {

/// Base of every error mastrom throws on purpose; the CLI prints what() as one line and exits ≠ 0.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Bad user input: config value, CLI argument, out-of-range parameter.
class InputError : public Error {
public:
  using Error::Error;
};

/// A file that cannot be read, written, or is corrupt / foreign.
class IoError : public Error {
public:
  using Error::Error;
};

/// A numerical method that failed: divergence, singular matrix, no convergence.
class NumericalError : public Error {
public:
  using Error::Error;
};

/// A library function called against its contract (a caller's programming error, not a user's
/// input): inconsistent arguments, a missing solver session, a broken internal table.
class UsageError : public Error {
public:
  using Error::Error;
};

namespace detail {
/// Concatenate any streamable arguments into one string (for error messages).
template <typename... Args>
std::string concat(const Args&... args) {
  std::ostringstream os;
  os.precision(17);
  (os << ... << args);
  return os.str();
}
}  // namespace detail

}  // namespace mastrom

/// Always-on check of user input: throws ErrorType with the streamed message when cond is false.
#define MASTROM_REQUIRE(cond, ErrorType, ...)                               \
  do {                                                                      \
    if (!(cond)) throw ErrorType(::mastrom::detail::concat(__VA_ARGS__));   \
  } while (0)

/// Debug-only internal invariant.
#define MASTROM_ASSERT(cond) assert(cond)
