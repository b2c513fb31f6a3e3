// `mastrom rom eval DB [--set k=v]… [--method M] [--extrapolate] [-o FILE.h5]`: one deployment
// from the ROM (docs/theory.md §4; docs/user_guide.md §3). Prints the design, the error estimates,
// the metrics and stresses like `simulate`; with -o writes the docs/user_guide.md §5 layout with
// source "rom", its series stepped block by block into the file (cli/rom_eval_output.hpp), so
// memory does not grow with the horizon. Registered with `rom build` in cli/cmd_rom.cpp.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace mastrom::cli {

struct EvalArguments {
  std::string database;
  std::vector<std::string> overrides;
  std::string method;
  bool extrapolate = false;
  std::string output;
  bool quiet = false;
  bool no_stresses = false;
  bool stress_history = false;
  bool allow_large = false;
  std::optional<int> frequencies;
};

/// Run `rom eval` (exit codes through the error types, cli/main.cpp).
void runEval(const EvalArguments& args);

}  // namespace mastrom::cli
