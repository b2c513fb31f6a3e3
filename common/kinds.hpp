// Enumerations that appear in the configuration, with their parse / to-string pairs
// (enum class instead of strings).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace mastrom {

/// Joint drive laws of docs/theory.md §1 ([LW24] eqs. 47, 49, 50).
enum class DriveLawKind { Trapezoidal, Cubic, Quintic, Cycloidal, Table };

/// Eigen-solver backends of docs/theory.md §3.
enum class EigenBackendKind { Slepc, Arpack, Dense };

/// Which accelerations and multipliers a full-order deployment reports (fullorder/generalized_alpha.hpp):
/// Index1 = recovered from the index-1 equations at each converged state (second order, no
/// start-up transient after drive-law jumps); Integrator = the index-3 scheme's own q̈ and λ
/// (numerically filtered; the choice for systems with excited modes far beyond the step's resolution).
enum class AccelerationOutputKind { Index1, Integrator };

/// Probability distributions of an uncertain input ([uncertainty], docs/theory.md §7.1).
enum class DistributionKind { Normal, Lognormal, Uniform, TruncatedNormal };

std::optional<AccelerationOutputKind> parseAccelerationOutputKind(std::string_view name);
std::string toString(AccelerationOutputKind kind);
std::string allowedAccelerationOutputNames();

std::optional<DriveLawKind> parseDriveLawKind(std::string_view name);
std::string toString(DriveLawKind kind);
/// Allowed names, for error messages: "trapezoidal, cubic, quintic, cycloidal".
std::string allowedDriveLawNames();

std::optional<EigenBackendKind> parseEigenBackendKind(std::string_view name);
std::string toString(EigenBackendKind kind);
std::string allowedEigenBackendNames();

std::optional<DistributionKind> parseDistributionKind(std::string_view name);
std::string toString(DistributionKind kind);
std::string allowedDistributionNames();

}  // namespace mastrom
