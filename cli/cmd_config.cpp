// `mastrom config CONFIG [--set k=v]…`: print the resolved configuration — every key, after the
// file, the overrides and the derived values — as TOML that mastrom reads back unchanged. It is
// "show what will run": the same text is stored in every output file (docs/user_guide.md §5).
#include <iostream>
#include <memory>

#include "cli/cli_common.hpp"

namespace mastrom::cli {

void registerConfigCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "config",
      "Validate a configuration and print it resolved (defaults, overrides and derived "
      "values filled in) as TOML");
  auto args = std::make_shared<ConfigArguments>();
  addConfigArguments(*command, *args);
  command->callback([args]() {
    const Config config = loadConfig(*args);
    std::cout << "# mastrom " << kVersion << ": resolved configuration of " << args->path << "\n";
    for (const std::string& o : args->overrides) std::cout << "# --set " << o << "\n";
    std::cout << toToml(config) << std::flush;
  });
}

}  // namespace mastrom::cli
