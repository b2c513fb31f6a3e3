// Enumerations that appear in the configuration, with their parse / to-string pairs
// (shared/STYLE.md habit 8: enum class instead of strings).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace mastrom {

/// Joint drive laws of shared/DESIGN.md §1 (paper P-47, P-49, P-50).
enum class DriveLawKind { Trapezoidal, Cubic, Quintic, Cycloidal };

/// Eigen-solver backends of shared/DESIGN.md §3.
enum class EigenBackendKind { Slepc, Arpack, Dense };

std::optional<DriveLawKind> parseDriveLawKind(std::string_view name);
std::string toString(DriveLawKind kind);
/// Allowed names, for error messages: "trapezoidal, cubic, quintic, cycloidal".
std::string allowedDriveLawNames();

std::optional<EigenBackendKind> parseEigenBackendKind(std::string_view name);
std::string toString(EigenBackendKind kind);
std::string allowedEigenBackendNames();

}  // namespace mastrom
