#include "common/option_names.hpp"

#include <atomic>

namespace mastrom {
namespace {

struct Names {
  Option option;
  const char* command_line;
  const char* python;  // the keyword argument of the calls in python/src that take it
};

// One row per Option, in its order.
constexpr Names kNames[] = {
    {Option::Set, "--set", "set="},
    {Option::Param, "--param", "params"},
    {Option::Extrapolate, "--extrapolate", "extrapolate=True"},
    {Option::Method, "--method", "method="},
    {Option::Tolerance, "--tolerance", "tolerance"},
    {Option::MaxSamples, "--max-samples", "max_samples"},
    {Option::Modes, "--modes", "modes="},
    {Option::Backend, "--backend", "backend="},
};

constexpr bool rowsInOptionOrder() {
  for (int i = 0; i < static_cast<int>(sizeof kNames / sizeof kNames[0]); ++i)
    if (static_cast<int>(kNames[i].option) != i) return false;
  return true;
}
static_assert(rowsInOptionOrder(), "kNames: one row per Option, in its order");

std::atomic<FrontEnd> current{FrontEnd::CommandLine};

}  // namespace

void useFrontEnd(FrontEnd front_end) { current.store(front_end, std::memory_order_relaxed); }

const char* optionName(Option option) {
  const Names& names = kNames[static_cast<int>(option)];
  return current.load(std::memory_order_relaxed) == FrontEnd::Python ? names.python
                                                                     : names.command_line;
}

}  // namespace mastrom
