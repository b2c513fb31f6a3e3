// How a library message names an option its user gave through a front end: the command line's
// flag (`--extrapolate`) or the Python call's keyword argument (`extrapolate=True`). The library
// phrases the message and asks here for the option's name, so a Python user never reads a flag
// they cannot pass. The command line and the Python module never share a process, so the
// front end is chosen once per process — by the Python module on import — before any other thread
// runs; until then (the CLI, the tests) the command line's names are used.
#pragma once

namespace mastrom {

/// The options library messages point to.
enum class Option {
  Set,          ///< overrides of configuration keys
  Param,        ///< a database axis of a build
  Extrapolate,  ///< allow points outside a database's sampled box
  Method,       ///< the interpolation method
  Tolerance,    ///< an adaptive build's target error
  MaxSamples,   ///< an adaptive build's budget
  Modes,        ///< the mode count of a build
  Backend,      ///< the eigensolver backend of a build
};

enum class FrontEnd { CommandLine, Python };

/// The front end whose names messages use from now on: call once, before other threads start.
void useFrontEnd(FrontEnd front_end);

/// The text a message puts where it names `option`, in the current front end's terms:
/// "--set" / "set=", "--param" / "params", "--extrapolate" / "extrapolate=True", "--method" /
/// "method=", "--tolerance" / "tolerance", "--max-samples" / "max_samples", "--modes" / "modes=",
/// "--backend" / "backend=".
const char* optionName(Option option);

}  // namespace mastrom
