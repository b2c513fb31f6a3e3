// The ROM's parameter space in terms of configuration keys (docs/theory.md §4.3, §5.1): which keys
// may span a database axis, how `KEY=LO:HI:N` is read, and how a point of the space and the "free"
// keys of a deployment (drive law, timing) are applied to the database's base configuration.
//
// Roles of a configuration key for the ROM:
//  * database parameter — a continuous physical key the modal model depends on and that a build may
//    sample: any floating-point key of [module], [interface], [material], the same keys of one
//    item (module.K.mass, interface.K.thickness, …), and modes.angle_deg when gravity is on
//    (without gravity θ0 only rotates the modes rigidly). Integer keys (module count,
//    mesh) change the model's topology and cannot be interpolated;
//  * free key — what one deployment chooses without touching the modes: every [drive] key,
//    simulation.end_time / time_step / rho_inf / accelerations, every [output] key;
//  * fixed — everything else (gravity, the mesh, …): the database holds it at its base value, and a
//    ROM evaluation that asks for another value is an error.
//
// Configurations are modified the way the command line does it (`--set section.key=value`, the
// value written as TOML), then re-read and re-validated by common/config.hpp, so a parameter value
// is accepted or rejected by exactly the rules of the configuration itself.
#pragma once

#include <string>
#include <vector>

#include "common/config.hpp"
#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

enum class KeyRole { DatabaseParameter, Free, Fixed };

/// Role of "section.key" (see the header). Does not check that the key exists.
KeyRole keyRole(const std::string& key, const Config& base);

/// "section.key=value" with the value in shortest round-trip form (reads back bit-exactly).
std::string formatOverride(const std::string& key, double value);

/// The configuration with `overrides` ("section.key=value", as for --set) applied on top of `base`,
/// re-validated. Overriding interface.radius drops inner_diameter and vice versa, as on the command
/// line. Throws InputError (the configuration's own message) for an unknown key, a wrong type or a
/// value out of range.
Config applyOverrides(const Config& base, const std::vector<std::string>& overrides);

/// The value of a floating-point key of `config` (e.g. "interface.thickness"). InputError when the
/// key does not exist, is not a floating-point key (an integer, a name, an array), or is absent in
/// this config (interface.inner_diameter when the config gives the radius).
double configValue(const Config& config, const std::string& key);

/// Parse one `--param KEY=LO:HI:N` against the base configuration: N ≥ 2 values evenly spaced from
/// LO to HI inclusive (the last one exactly HI), LO < HI, all finite. KEY must be a database
/// parameter (see the header) and both LO and HI must give a valid configuration. Every error is an
/// InputError with one line naming the argument and what is wrong.
/// With AxisForm::Range the text is `KEY=LO:HI` and the axis holds the range {LO, HI} (the box of
/// a scattered database, rom/database/rom_database.hpp), checked alike.
enum class AxisForm { Grid, Range };
ParameterAxis parseParameterAxis(const std::string& text, const Config& base,
                                 AxisForm form = AxisForm::Grid);

/// The base configuration a database over `axes` is built from: `base`, switched to the
/// parametrisation the axes use (interface.inner_diameter vs interface.radius, same geometry).
/// Throws InputError for axes that repeat a key or give both radius and inner_diameter.
Config databaseBaseConfig(const Config& base, const std::vector<ParameterAxis>& axes);

/// The overrides that put a configuration at `parameters` (one value per axis).
std::vector<std::string> parameterOverrides(const std::vector<ParameterAxis>& axes,
                                            const std::vector<double>& parameters);

/// The database point of a configuration: configValue() of every axis key.
std::vector<double> parameterPoint(const RomDatabase& db, const Config& config);

/// The configuration of one ROM evaluation: the database's base configuration with `overrides`
/// applied. Each override key must be a database parameter or a free key; a fixed key is an
/// InputError naming the key and the database's parameters.
Config evaluationConfig(const RomDatabase& db, const std::vector<std::string>& overrides);

/// How to treat a point outside the sampled box.
enum class BoxPolicy { Refuse, Extrapolate };

/// InputError naming the first axis whose value lies outside its sampled range (with the range),
/// unless policy is Extrapolate.
void requireInsideBox(const RomDatabase& db, const std::vector<double>& parameters,
                      BoxPolicy policy);

/// SI unit of a configuration key, for dataset attributes ("m", "Pa", "deg", "1", …).
std::string configKeyUnits(const std::string& key);

}  // namespace mastrom::rom
