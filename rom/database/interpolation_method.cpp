#include "rom/database/interpolation_method.hpp"

#include <iterator>

#include "common/error.hpp"

namespace mastrom::rom {
namespace {

constexpr InterpolationMethod kAllMethods[] = {
    InterpolationMethod::Tracked, InterpolationMethod::Manifold, InterpolationMethod::Affine,
    InterpolationMethod::Cubic, InterpolationMethod::Rbf};

}  // namespace

const std::vector<InterpolationMethod>& allInterpolationMethods() {
  static const std::vector<InterpolationMethod> all(std::begin(kAllMethods), std::end(kAllMethods));
  return all;
}

std::string toString(InterpolationMethod method) {
  switch (method) {
    case InterpolationMethod::Tracked:
      return "tracked";
    case InterpolationMethod::Manifold:
      return "manifold";
    case InterpolationMethod::Affine:
      return "affine";
    case InterpolationMethod::Cubic:
      return "cubic";
    case InterpolationMethod::Rbf:
      return "rbf";
  }
  return "unknown";
}

std::optional<InterpolationMethod> parseInterpolationMethod(std::string_view name) {
  for (InterpolationMethod m : kAllMethods)
    if (name == toString(m)) return m;
  return std::nullopt;
}

std::string allowedInterpolationMethodNames() {
  std::string names;
  for (InterpolationMethod m : kAllMethods) names += (names.empty() ? "" : ", ") + toString(m);
  return names;
}

InterpolationMethod interpolationMethodOr(std::string_view name, InterpolationMethod fallback,
                                          std::string_view key) {
  if (name.empty()) return fallback;
  const std::optional<InterpolationMethod> m = parseInterpolationMethod(name);
  MASTROM_REQUIRE(m.has_value(), InputError, key, " = '", name,
                  "' is not an interpolation method (allowed: ", allowedInterpolationMethodNames(),
                  ")");
  return *m;
}

}  // namespace mastrom::rom
