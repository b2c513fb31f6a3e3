// How the online stage obtains the modal model between database samples (docs/theory.md §4.4), and
// the one place its names are spelled.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mastrom::rom {

enum class InterpolationMethod {
  Tracked,   ///< (a) modal quantities interpolated after MAC tracking and sign alignment
  Manifold,  ///< (b) aligned reduced matrices interpolated on the SPD manifold, small eigensolve
  Affine,    ///< (c) exact affine terms in (h, E, ρ) at a fixed radius (rom/interpolation/affine_model.hpp)
  Cubic,     ///< (a) with local cubic Lagrange weights instead of multilinear ones (smooth data)
  Rbf,       ///< (a) with radial-basis weights: any sample layout, grid or scattered
};

/// "tracked" / "manifold" / "affine" / "cubic" / "rbf".
std::string toString(InterpolationMethod method);
std::optional<InterpolationMethod> parseInterpolationMethod(std::string_view name);
/// Every method, in the order of the names below.
const std::vector<InterpolationMethod>& allInterpolationMethods();
/// "tracked, manifold, affine, cubic, rbf" (for messages and help texts).
std::string allowedInterpolationMethodNames();

/// The method named `name`, or `fallback` when `name` is empty. Throws InputError naming `key`, the
/// value and the allowed names when `name` is not a method.
InterpolationMethod interpolationMethodOr(std::string_view name, InterpolationMethod fallback,
                                          std::string_view key);

}  // namespace mastrom::rom
