// The resource budget (common/resource_budget.hpp): a refusal is one line naming the keys that
// drive the estimate with their values, what is needed and what is available; --allow-large turns
// it into the note a large run prints first; an ordinary run prints nothing; the machine's
// available memory is read.
#include <gtest/gtest.h>

#include <string>

#include "common/error.hpp"
#include "common/resource_budget.hpp"

namespace mastrom {
namespace {

ResourceEstimate estimate(double memory, double result) {
  ResourceEstimate e;
  e.command = "simulate";
  e.memory_bytes = memory;
  e.result_bytes = result;
  e.memory_drivers = {{"mast.modules", "100000"}};
  e.memory_detail = "2.28e+07 DOFs";
  e.result_drivers = {{"simulation.end_time", "1e9"}, {"output.step", "0.0001"}};
  e.result_detail = "1e+13 output samples";
  return e;
}

ResourceLimits limits() {
  ResourceLimits l;
  l.available_memory_bytes = 20e9;
  l.free_disk_bytes = 80e9;
  return l;
}

std::string refusal(const ResourceEstimate& e) {
  try {
    checkResources(e, limits(), false);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(ResourceBudget, MemoryBeyondTheAvailableIsRefusedInOneLineNamingTheKeys) {
  const std::string m = refusal(estimate(96e9, 1e6));
  EXPECT_EQ(m,
            "simulate would need about 96 GB of memory (mast.modules = 100000: 2.28e+07 DOFs), "
            "more than the 20 GB available (MemAvailable); reduce them, or pass --allow-large to "
            "run anyway");
}

TEST(ResourceBudget, AResultBeyondTheFreeDiskIsRefused) {
  const std::string m = refusal(estimate(1e8, 1.9e15));
  EXPECT_EQ(m,
            "simulate would write about 1.9 PB (simulation.end_time = 1e9, output.step = 0.0001: "
            "1e+13 output samples), more than the 80 GB free on the output's file system; reduce "
            "them, or pass --allow-large to run anyway");
}

TEST(ResourceBudget, LargeButFeasibleRunsSaySoAndSmallOnesSayNothing) {
  EXPECT_EQ(checkResources(estimate(1e8, 1e8), limits(), false), "");
  EXPECT_EQ(checkResources(estimate(1e8, 3.2e9), limits(), false),
            "note: result ≈ 3.2 GB (simulation.end_time = 1e9, output.step = 0.0001: 1e+13 output "
            "samples); 20 GB available");
  EXPECT_NE(checkResources(estimate(6e9, 1e6), limits(), false).find("memory ≈ 6.0 GB"),
            std::string::npos);
  // --allow-large: past the limit, the run goes on and says so.
  const std::string note = checkResources(estimate(96e9, 1e6), limits(), true);
  EXPECT_NE(note.find("memory ≈ 96 GB"), std::string::npos);
  EXPECT_NE(note.find("past the limit: --allow-large"), std::string::npos);
}

TEST(ResourceBudget, UnknownLimitsAreNotChecked) {
  EXPECT_EQ(checkResources(estimate(1e15, 1e6), ResourceLimits{}, false), "");
}

TEST(ResourceBudget, TheMachineReportsAvailableMemory) {
  const std::optional<double> available = availableMemoryBytes();
  ASSERT_TRUE(available.has_value());  // Linux: /proc/meminfo
  EXPECT_GT(*available, 1e7);
  EXPECT_EQ(formatBytes(812e3), "812 kB");
  EXPECT_EQ(formatBytes(3.2e9), "3.2 GB");
}

}  // namespace
}  // namespace mastrom
