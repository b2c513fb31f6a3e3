// [uncertainty."KEY"] (common/config.hpp UncertainInput, docs/user_guide.md §4): each distribution
// read with its parameters, written back exactly, changed with --set, and one test per rejected
// input (the one-line message names the key, the value and the rule).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/error.hpp"

namespace mastrom {
namespace {

const char* kFourInputs = R"(
[uncertainty."interface.thickness"]
distribution = "normal"
mean = 1.5e-3
std = 5e-5

[uncertainty."material.youngs_modulus"]
distribution = "lognormal"
mean = 70e9
std = 2e9

[uncertainty."module.2.mass"]
distribution = "uniform"
lower = 0.45
upper = 0.55

[uncertainty."material.density"]
distribution = "truncated_normal"
mean = 2700.0
std = 50.0
lower = 2600.0
upper = 2800.0
)";

/// The message of the InputError that parsing `text` (with `overrides`) throws; "" if none.
std::string errorOf(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    (void)applyConfigOverrides(parseConfigText(text, "test.toml"), overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(UncertaintyConfig, ReadsEveryDistribution) {
  const Config c = parseConfigText(kFourInputs, "test.toml");
  ASSERT_EQ(c.uncertainty.size(), 4u);
  const UncertainInput& h = c.uncertainty.at("interface.thickness");
  EXPECT_EQ(h.distribution, DistributionKind::Normal);
  EXPECT_EQ(*h.mean, 1.5e-3);
  EXPECT_EQ(*h.std_dev, 5e-5);
  EXPECT_FALSE(h.lower.has_value());
  EXPECT_EQ(c.uncertainty.at("material.youngs_modulus").distribution, DistributionKind::Lognormal);
  EXPECT_EQ(*c.uncertainty.at("module.2.mass").upper, 0.55);
  EXPECT_EQ(c.uncertainty.at("material.density").distribution, DistributionKind::TruncatedNormal);
  EXPECT_TRUE(parseConfigText("", "empty.toml").uncertainty.empty());
}

TEST(UncertaintyConfig, WrittenBackExactly) {
  const Config c = parseConfigText(kFourInputs, "test.toml");
  EXPECT_EQ(parseConfigText(toToml(c), "round trip"), c);
  // A plain configuration's text has no [uncertainty] table at all.
  EXPECT_EQ(toToml(Config{}).find("uncertainty"), std::string::npos);
}

TEST(UncertaintyConfig, SetChangesAddsAndReplacesInputs) {
  const Config base = parseConfigText(kFourInputs, "test.toml");
  const Config c =
      applyConfigOverrides(base, {"uncertainty.interface.thickness.std=1e-4",
                                  "uncertainty.interface.2.length.distribution=uniform",
                                  "uncertainty.interface.2.length.lower=0.04",
                                  "uncertainty.interface.2.length.upper=0.06",
                                  // A new distribution drops the file's parameters of the old one.
                                  "uncertainty.material.youngs_modulus.distribution=uniform",
                                  "uncertainty.material.youngs_modulus.lower=65e9",
                                  "uncertainty.material.youngs_modulus.upper=75e9"});
  EXPECT_EQ(*c.uncertainty.at("interface.thickness").std_dev, 1e-4);
  EXPECT_EQ(*c.uncertainty.at("interface.2.length").lower, 0.04);
  const UncertainInput& e = c.uncertainty.at("material.youngs_modulus");
  EXPECT_EQ(e.distribution, DistributionKind::Uniform);
  EXPECT_FALSE(e.mean.has_value());
  EXPECT_EQ(*e.upper, 75e9);
}

struct Rejected {
  std::string text;
  std::vector<std::string> overrides;
  std::vector<std::string> message_parts;
};

TEST(UncertaintyConfig, RejectsBadInputsWithOneLine) {
  const std::string normal = "[uncertainty.\"interface.thickness\"]\ndistribution = \"normal\"\n";
  const std::vector<Rejected> cases = {
      {normal + "mean = 1e-3\n",
       {},
       {"uncertainty.interface.thickness.std is missing", "mean, std"}},
      {normal + "mean = 1e-3\nstd = -1e-5\n",
       {},
       {"uncertainty.interface.thickness.std = -1e-05", "std > 0"}},
      {normal + "mean = 1e-3\nstd = 1e-5\nlower = 0.0\n",
       {},
       {"uncertainty.interface.thickness.lower = 0", "not a parameter", "normal"}},
      {normal + "mean = 1e-3\nstd = 1e-5\nwidth = 2\n",
       {},
       {"unknown key uncertainty.interface.thickness.width",
        "distribution, mean, std, lower, upper"}},
      {"[uncertainty.\"interface.thickness\"]\ndistribution = \"gauss\"\n",
       {},
       {"uncertainty.interface.thickness.distribution = \"gauss\"",
        "normal, lognormal, uniform, truncated_normal"}},
      {"[uncertainty.\"interface.thickness\"]\nmean = 1.0\n",
       {},
       {"uncertainty.interface.thickness.distribution is missing"}},
      {"[uncertainty.\"material.youngs_modulus\"]\ndistribution = \"lognormal\"\nmean = -7e10\n"
       "std = 1e9\n",
       {},
       {"uncertainty.material.youngs_modulus.mean = -7e+10", "mean > 0"}},
      {"[uncertainty.\"module.mass\"]\ndistribution = \"uniform\"\nlower = 0.6\nupper = 0.5\n",
       {},
       {"uncertainty.module.mass.upper = 0.5", "upper > lower = 0.6"}},
      {"[uncertainty.\"module.mass\"]\ndistribution = \"truncated_normal\"\nmean = 0.5\n"
       "std = 0.01\nlower = 0.7\nupper = 0.8\n",
       {},
       {"uncertainty.module.mass = [0.7, 0.8]", "mean +- 8 std = [0.42, 0.58]"}},
      {"[uncertainty.\"drive.duration\"]\ndistribution = \"uniform\"\nlower = 5.0\nupper = 6.0\n",
       {},
       {"drive.duration is not a key a ROM database can vary"}},
      {"[uncertainty]\n\"interface.thickness\" = 0.001\n",
       {},
       {"uncertainty.interface.thickness = 0.001", "expected a table"}},
      {normal + "mean = 1e-3\nstd = 1e-5\n",
       {"uncertainty.interface.thickness.std=inf"},
       {"uncertainty.interface.thickness.std = inf", "not a finite number"}},
  };
  for (const Rejected& r : cases) {
    const std::string message = errorOf(r.text, r.overrides);
    ASSERT_FALSE(message.empty()) << r.text;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& part : r.message_parts)
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
}

}  // namespace
}  // namespace mastrom
