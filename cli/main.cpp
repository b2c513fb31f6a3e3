// The `mastrom` executable: parses the command line with CLI11, hands over to one subcommand, and
// turns every failure into exactly one line on stderr, `mastrom: error: <message>`, and an exit
// code: 2 for bad input or files (and command-line mistakes), 3 for numerical failure, 1 otherwise.
#include <exception>
#include <iostream>
#include <string>

#include "cli/cli_common.hpp"
#include "common/error.hpp"

namespace {

using RegisterFunction = void (*)(CLI::App&);

/// Every subcommand, in the order `mastrom --help` lists them.
constexpr RegisterFunction kCommands[] = {
    mastrom::cli::registerConfigCommand,
    mastrom::cli::registerSimulateCommand,
    mastrom::cli::registerModesCommand,
    mastrom::cli::registerRomCommand,
    mastrom::cli::registerScreenCommand,
    mastrom::cli::registerValidateCommand,
    mastrom::cli::registerCompareCommand,
    mastrom::cli::registerReportCommand,
};

int fail(int code, std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  std::cerr << "mastrom: error: " << message << std::endl;
  return code;
}

std::string commandNames(CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mastrom::cli;
  CLI::App app{"mastrom: deployment dynamics and modal reduced-order model of a modular rover mast",
               "mastrom"};
  app.set_version_flag("--version", "mastrom " + std::string(mastrom::kVersion));
  app.require_subcommand(1);
  for (const RegisterFunction add : kCommands) add(app);
  // Set after the subcommands exist, so that they do not inherit it.
  app.footer(
      "Run 'mastrom COMMAND --help' for the options of one command.");

  try {
    app.parse(argc, argv);  // runs the chosen subcommand's callback
    return kExitOk;
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty()) {
      return fail(kExitInput, std::string("unknown command '") + argv[1] +
                                  "': available: " + commandNames(app) + " (run 'mastrom --help')");
    }
    return fail(kExitInput, std::string(e.what()) + " (run 'mastrom --help')");
  } catch (const mastrom::InputError& e) {
    return fail(kExitInput, e.what());
  } catch (const mastrom::IoError& e) {
    return fail(kExitInput, e.what());
  } catch (const mastrom::NumericalError& e) {
    return fail(kExitNumerical, e.what());
  } catch (const mastrom::Error& e) {
    return fail(kExitFailure, e.what());
  } catch (const std::exception& e) {
    return fail(kExitFailure, e.what());
  } catch (...) {
    return fail(kExitFailure, "unknown exception");
  }
}
