// [uncertainty."KEY"]: the ranges of each input's distribution parameters and the section's TOML
// text (docs/theory.md §7.1). Reading (types only) is in config_from_table.cpp with the other
// sections; whether KEY is a parameter of a given ROM database is checked where a database is at
// hand (rom/studies/uncertainty_study.cpp), since the configuration does not know one.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "common/config_detail.hpp"
#include "common/error.hpp"
#include "common/text_parsing.hpp"

namespace mastrom::config_detail {
namespace {

/// The sections whose floating-point keys a ROM database may vary
/// (rom/database/parameter_space.hpp).
bool isParameterKeyForm(const std::string& key) {
  const std::vector<std::string> parts = splitAt(key, '.');
  for (const std::string& p : parts)
    if (p.empty()) return false;
  const std::string& section = parts.front();
  const bool item_section = section == "module" || section == "interface";
  if (parts.size() == 2) return item_section || section == "material" || section == "modes";
  return parts.size() == 3 && item_section && isItemNumber(parts[1]);
}

struct Parameter {
  const char* name;
  const std::optional<double>* value;
};

}  // namespace

void validateUncertainty(const std::map<std::string, UncertainInput>& inputs) {
  for (const auto& [key, in] : inputs) {
    const std::string at = "uncertainty." + key;
    if (!isParameterKeyForm(key)) {
      throw InputError(detail::concat(
          kPrefix, "[uncertainty.", tomlString(key), "]: ", key,
          " is not a key a ROM database can vary: allowed: a floating-point key of [module], "
          "[interface], [material] or [modes], or of one item (e.g. interface.thickness, "
          "module.2.mass, material.youngs_modulus)"));
    }
    const std::string dist = toString(in.distribution);
    const bool normal_like = in.distribution != DistributionKind::Uniform;
    const bool bounded = in.distribution == DistributionKind::Uniform ||
                         in.distribution == DistributionKind::TruncatedNormal;
    const Parameter params[] = {
        {"mean", &in.mean}, {"std", &in.std_dev}, {"lower", &in.lower}, {"upper", &in.upper}};
    for (const Parameter& p : params) {
      const std::string name = p.name;
      const bool wanted = (name == "mean" || name == "std") ? normal_like : bounded;
      if (wanted && !p.value->has_value()) {
        throw InputError(detail::concat(kPrefix, at, ".", name, " is missing: distribution = \"",
                                        dist, "\" needs ", normal_like ? "mean, std" : "",
                                        normal_like && bounded ? ", " : "",
                                        bounded ? "lower, upper" : "", " (units of ", key, ")"));
      }
      if (!wanted && p.value->has_value()) {
        throw InputError(detail::concat(kPrefix, at, ".", name, " = ", formatDouble(**p.value),
                                        " is not a parameter of distribution = \"", dist,
                                        "\": it takes ", normal_like ? "mean, std" : "",
                                        normal_like && bounded ? ", " : "",
                                        bounded ? "lower, upper" : ""));
      }
      if (wanted && !std::isfinite(**p.value)) {
        throw InputError(detail::concat(kPrefix, at, ".", name, " = ", formatDouble(**p.value),
                                        " is not a finite number"));
      }
    }
    const auto outOfRange = [&at](const char* name, double v, const std::string& rule) {
      return InputError(detail::concat(kPrefix, at, ".", name, " = ", formatDouble(v),
                                       " is out of range: must satisfy ", rule));
    };
    if (normal_like && !(*in.std_dev > 0)) throw outOfRange("std", *in.std_dev, "std > 0");
    if (in.distribution == DistributionKind::Lognormal && !(*in.mean > 0))
      throw outOfRange("mean", *in.mean, "mean > 0 (a lognormal value is positive)");
    if (bounded && !(*in.lower < *in.upper))
      throw outOfRange("upper", *in.upper,
                       detail::concat("upper > lower = ", formatDouble(*in.lower)));
    // A truncation interval far in one tail of the normal has no probability to sample in double
    // precision (Φ(b) − Φ(a) rounds to 0); 8 standard deviations keep Φ's tails resolved.
    if (in.distribution == DistributionKind::TruncatedNormal) {
      const double lo = *in.mean - 8.0 * *in.std_dev, hi = *in.mean + 8.0 * *in.std_dev;
      if (*in.upper <= lo || *in.lower >= hi) {
        throw InputError(detail::concat(
            kPrefix, at, " = [", formatDouble(*in.lower), ", ", formatDouble(*in.upper),
            "] is out of range: the truncation interval must meet mean +- 8 std = [",
            formatDouble(lo), ", ", formatDouble(hi), "]"));
      }
    }
  }
}

std::string uncertaintyToml(const std::map<std::string, UncertainInput>& inputs) {
  std::ostringstream os;
  for (const auto& [key, in] : inputs) {
    os << "\n[uncertainty." << tomlString(key) << "]\n"
       << "distribution = " << tomlString(toString(in.distribution)) << "  # "
       << allowedDistributionNames() << "\n";
    const Parameter params[] = {
        {"mean", &in.mean}, {"std", &in.std_dev}, {"lower", &in.lower}, {"upper", &in.upper}};
    for (const Parameter& p : params)
      if (p.value->has_value()) os << p.name << " = " << tomlFloat(**p.value) << "\n";
  }
  return os.str();
}

}  // namespace mastrom::config_detail
