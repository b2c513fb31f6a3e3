#include "cli/cli_common.hpp"

namespace mastrom::cli {

void addConfigArguments(CLI::App& command, ConfigArguments& args) {
  command.add_option("CONFIG", args.path, "TOML configuration file (docs: README.md)")->required();
  // One value per --set, so that `--set a=1 CONFIG` never swallows CONFIG.
  command
      .add_option("--set", args.overrides,
                  "Override one key, e.g. --set interface.thickness=0.001 (repeatable; applied "
                  "after the file, in order)")
      ->type_name("SECTION.KEY=VALUE")
      ->allow_extra_args(false);
}

Config loadConfig(const ConfigArguments& args) {
  return ::mastrom::loadConfig(args.path, args.overrides);
}

}  // namespace mastrom::cli
