// Which command lines may open a parallel region of two threads (cli/cli_common.hpp
// mayRunThreads): only those make the executable run itself again with a bounded OpenMP spin
// (cli/main.cpp), which costs a second load of it and its libraries.
#include <gtest/gtest.h>

#include <cstdlib>
#include <initializer_list>
#include <string>
#include <vector>

#include "cli/cli_common.hpp"

namespace mastrom::cli {
namespace {

bool mayRun(std::initializer_list<const char*> words) {
  std::vector<std::string> storage{"mastrom"};
  for (const char* w : words) storage.emplace_back(w);
  std::vector<char*> argv;
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  return mayRunThreads(static_cast<int>(storage.size()), argv.data());
}

/// The environment for one test: no MPI launcher, no OpenMP limit (restored after).
class ThreadArguments : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : kNames) {
      const char* value = std::getenv(name);
      saved_.emplace_back(name, value ? std::string(value) : std::string("\x01"));
      ::unsetenv(name);
    }
  }
  void TearDown() override {
    for (const auto& [name, value] : saved_) {
      if (value == "\x01")
        ::unsetenv(name.c_str());
      else
        ::setenv(name.c_str(), value.c_str(), 1);
    }
  }
  static constexpr const char* kNames[] = {"OMP_NUM_THREADS", "OMP_THREAD_LIMIT",
                                           "OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"};
  std::vector<std::pair<std::string, std::string>> saved_;
};

TEST_F(ThreadArguments, OnlySimulateOnMoreThanOneThreadMayRunThreads) {
  const bool two_cores = defaultThreadCount() > 1;  // the machine's cores decide the default
  EXPECT_EQ(mayRun({"simulate", "c.toml"}), two_cores);
  EXPECT_EQ(mayRun({"simulate", "c.toml", "--threads", "0"}), two_cores);
  EXPECT_TRUE(mayRun({"simulate", "c.toml", "--threads", "2"}));
  EXPECT_TRUE(mayRun({"simulate", "--threads=3", "c.toml"}));
  EXPECT_FALSE(mayRun({"simulate", "c.toml", "--threads", "1"}));
  EXPECT_FALSE(mayRun({"simulate", "c.toml", "--threads=1"}));
  EXPECT_FALSE(mayRun({"simulate", "c.toml", "--threads", "2", "--threads", "1"}));  // last wins
  EXPECT_FALSE(mayRun({"simulate", "--help"}));
  EXPECT_FALSE(mayRun({"--version"}));
  EXPECT_FALSE(mayRun({}));
  // Every other command runs the full order, if at all, on one thread.
  for (const char* command : {"validate", "study", "compare", "modes", "rom", "screen", "report",
                              "config"})
    EXPECT_FALSE(mayRun({command, "c.toml", "--threads", "2"})) << command;
  // A configuration file named like the command is not the command.
  EXPECT_FALSE(mayRun({"rom", "simulate"}));
}

TEST_F(ThreadArguments, OpenMpLimitsAndMpiLaunchersMeanOneThreadByDefault) {
  ::setenv("OMP_NUM_THREADS", "1", 1);
  EXPECT_EQ(defaultThreadCount(), 1);
  EXPECT_FALSE(mayRun({"simulate", "c.toml"}));
  EXPECT_TRUE(mayRun({"simulate", "c.toml", "--threads", "2"}));  // asked for explicitly
  ::unsetenv("OMP_NUM_THREADS");
  ::setenv("OMPI_COMM_WORLD_SIZE", "2", 1);
  EXPECT_EQ(defaultThreadCount(), 1);
  EXPECT_FALSE(mayRun({"simulate", "c.toml"}));
}

}  // namespace
}  // namespace mastrom::cli
