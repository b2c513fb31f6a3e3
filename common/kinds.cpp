#include "common/kinds.hpp"

#include <array>
#include <utility>

namespace mastrom {
namespace {
constexpr std::array<std::pair<DriveLawKind, std::string_view>, 5> kDriveNames{{
    {DriveLawKind::Trapezoidal, "trapezoidal"},
    {DriveLawKind::Cubic, "cubic"},
    {DriveLawKind::Quintic, "quintic"},
    {DriveLawKind::Cycloidal, "cycloidal"},
    {DriveLawKind::Table, "table"},
}};
constexpr std::array<std::pair<EigenBackendKind, std::string_view>, 3> kBackendNames{{
    {EigenBackendKind::Slepc, "slepc"},
    {EigenBackendKind::Arpack, "arpack"},
    {EigenBackendKind::Dense, "dense"},
}};

constexpr std::array<std::pair<AccelerationOutputKind, std::string_view>, 2> kAccelerationNames{{
    {AccelerationOutputKind::Index1, "index1"},
    {AccelerationOutputKind::Integrator, "integrator"},
}};

constexpr std::array<std::pair<DistributionKind, std::string_view>, 4> kDistributionNames{{
    {DistributionKind::Normal, "normal"},
    {DistributionKind::Lognormal, "lognormal"},
    {DistributionKind::Uniform, "uniform"},
    {DistributionKind::TruncatedNormal, "truncated_normal"},
}};

template <typename Kind, typename Table>
std::optional<Kind> parseFrom(const Table& table, std::string_view name) {
  for (const auto& [kind, text] : table)
    if (text == name) return kind;
  return std::nullopt;
}
template <typename Kind, typename Table>
std::string nameFrom(const Table& table, Kind kind) {
  for (const auto& [k, text] : table)
    if (k == kind) return std::string(text);
  return "?";
}
template <typename Table>
std::string joinNames(const Table& table) {
  std::string out;
  for (const auto& entry : table) {
    if (!out.empty()) out += ", ";
    out += entry.second;
  }
  return out;
}
}  // namespace

std::optional<DriveLawKind> parseDriveLawKind(std::string_view name) {
  return parseFrom<DriveLawKind>(kDriveNames, name);
}
std::string toString(DriveLawKind kind) { return nameFrom(kDriveNames, kind); }
std::string allowedDriveLawNames() { return joinNames(kDriveNames); }

std::optional<AccelerationOutputKind> parseAccelerationOutputKind(std::string_view name) {
  return parseFrom<AccelerationOutputKind>(kAccelerationNames, name);
}
std::string toString(AccelerationOutputKind kind) { return nameFrom(kAccelerationNames, kind); }
std::string allowedAccelerationOutputNames() { return joinNames(kAccelerationNames); }

std::optional<EigenBackendKind> parseEigenBackendKind(std::string_view name) {
  return parseFrom<EigenBackendKind>(kBackendNames, name);
}
std::string toString(EigenBackendKind kind) { return nameFrom(kBackendNames, kind); }
std::string allowedEigenBackendNames() { return joinNames(kBackendNames); }

std::optional<DistributionKind> parseDistributionKind(std::string_view name) {
  return parseFrom<DistributionKind>(kDistributionNames, name);
}
std::string toString(DistributionKind kind) { return nameFrom(kDistributionNames, kind); }
std::string allowedDistributionNames() { return joinNames(kDistributionNames); }

}  // namespace mastrom
