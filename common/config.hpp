// The run configuration of mastrom: TOML text → small validated structs (docs/user_guide.md §4).
//
// One struct per TOML section; every member carries its SI unit in its name and its default from
// docs/theory.md §1 (the values the paper does not give are assumptions, listed in README.md).
// Every key is optional. Input enters the program here, so every check is always on: an unknown
// section or key, a wrong type, a non-finite number or a non-physical value throws InputError with
// one line that names the key, the value and the allowed range. Degrees
// appear only in keys a person types (`angle_deg`); the *_rad() helpers give radians.
//
// Precedence: defaults < file < `--set section.key=value` overrides < derived values (the
// mid-surface radius from inner_diameter, the solid-cube inertia, T and Θ of a drive table), then
// validate(). Per-item tables [module.K] and [interface.K] (`--set module.K.key=value`) override
// single keys of [module] / [interface] for item K, numbered from the base.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/kinds.hpp"

namespace mastrom {

/// [mast]
struct MastConfig {
  int modules = 4;  ///< n ≥ 2 rigid modules in series; n − 1 interfaces (Scheme 1/2/3 = 2/3/4)
};

/// [module] — the properties of every module; [module.K] overrides them for module K.
struct ModuleConfig {
  double side_m = 0.10;   ///< d: cube side, also the NCF axis length (assumption, docs/theory.md §1)
  double mass_kg = 0.50;  ///< m (assumption, docs/theory.md §1)
  /// Principal centroidal inertia (Ixx, Iyy, Izz) in the module frame [kg·m²]; empty = solid cube.
  std::optional<std::array<double, 3>> inertia_kg_m2;
  /// Centroid relative to the cube's centre, in the module frame [m] (a payload off the axis).
  std::array<double, 3> centroid_offset_m{0.0, 0.0, 0.0};

  /// The inertia that will be used: the given one, or a uniform solid cube, m d²/6 about each axis.
  std::array<double, 3> principalInertia() const;
};

/// [interface] — every interface (a cylindrical shell of mid-surface radius R); [interface.K]
/// overrides it for interface K, the one joining module K to module K + 1.
struct InterfaceConfig {
  double length_m = 0.05;      ///< L (assumption, docs/theory.md §1)
  double radius_m = 0.041;     ///< R: mid-surface radius; derived when inner_diameter_m is given
  double thickness_m = 0.002;  ///< h
  /// D_in when the user chose to give the inner diameter (exclusive with radius): R = (D_in + h)/2.
  /// Kept so that the resolved file keeps the user's parametrisation (R then moves with h).
  std::optional<double> inner_diameter_m;
  int elements_axial = 2;            ///< N_axial ≥ 1
  int elements_circumferential = 8;  ///< N_circ ≥ 3 (periodic ring)
};

/// [module.K]: the keys given for one module; an unset key takes the value of [module].
struct ModuleItemConfig {
  std::optional<double> side_m;
  std::optional<double> mass_kg;
  std::optional<std::array<double, 3>> inertia_kg_m2;
  std::optional<std::array<double, 3>> centroid_offset_m;
};

/// [interface.K]: the keys given for one interface; an unset key takes the value of [interface].
/// radius and inner_diameter are exclusive here too; radius is then derived from the item's values.
struct InterfaceItemConfig {
  std::optional<double> length_m;
  std::optional<double> radius_m;
  std::optional<double> thickness_m;
  std::optional<double> inner_diameter_m;
  std::optional<int> elements_axial;
  std::optional<int> elements_circumferential;
};

/// [material] — the shell material (aluminium alloy, assumption, docs/theory.md §1).
struct MaterialConfig {
  double youngs_modulus_pa = 70e9;  ///< E
  double poisson_ratio = 0.33;      ///< ν ∈ (−1, 0.5)
  double density_kg_m3 = 2700.0;    ///< ρ
  double damping_s = 1e-5;  ///< μ: Kelvin–Voigt strain-rate coefficient, stress = D(ε + μ ε̇)
  /// Yield (or allowable) stress for the margin of safety yield / peak von Mises − 1 [Pa];
  /// empty: no margin is computed.
  std::optional<double> yield_strength_pa;
};

/// [drive] — the prescribed base-joint rotation θ(t) from 0 to Θ over [0, T], held after T.
struct DriveConfig {
  DriveLawKind law = DriveLawKind::Trapezoidal;
  double angle_deg = 90.0;  ///< Θ ∈ (0, 360]
  double duration_s = 6.1;  ///< T
  double ramp_s = 0.1;      ///< t_r: acceleration/deceleration time (trapezoidal law only)
  /// law = "table": the CSV file of the profile (time [s], angle [deg]; common/drive_table.hpp),
  /// made absolute against the configuration file's directory when read. The table then gives T
  /// (its last time) and Θ (its last angle): duration and angle_deg are derived from it.
  std::string table;
  std::vector<double> table_time_s;     ///< the table's rows as read (law = "table")
  std::vector<double> table_angle_rad;

  double angleRad() const;
};

/// [simulation] — the full-order integrator (generalized-α, docs/theory.md §5).
struct SimulationConfig {
  double end_time_s = 8.0;
  /// Adaptive steps: the first step and the first steps after each drive breakpoint; fixed steps
  /// (adaptive = false): the step.
  double time_step_s = 1e-5;
  /// Error-controlled variable steps (docs/theory.md §5.3); false: fixed steps of time_step.
  bool adaptive = true;
  /// Relative local error per step of the modules' accelerations (adaptive steps).
  double tolerance = 1e-5;
  double min_time_step_s = 1e-6;  ///< adaptive steps never fall below this
  double max_time_step_s = 1e-3;  ///< nor exceed this
  double rho_inf = 0.9;  ///< spectral radius at infinity ρ∞ ∈ [0, 1]
  std::array<double, 3> gravity_m_s2{0.0, 0.0, 0.0};  ///< global frame
  /// Reported accelerations and multipliers (common/kinds.hpp AccelerationOutputKind).
  AccelerationOutputKind accelerations = AccelerationOutputKind::Index1;
};

/// [modes] — modal analysis about a locked joint angle θ0 (docs/theory.md §3).
struct ModesConfig {
  int count = 10;
  double angle_deg = 0.0;  ///< θ0 ∈ [0, 360]
  EigenBackendKind backend = EigenBackendKind::Slepc;

  double angleRad() const;
};

/// [output]
struct OutputConfig {
  std::string file = "out.h5";
  int every = 1;  ///< fixed steps only: write every n-th time step
  /// Adaptive steps: the outputs are interpolated onto t = k · step [s] (and the end). Unset: the
  /// commands that write time series choose it from the response (docs/theory.md §5.4a,
  /// rom/model/output_resolution.hpp); elsewhere kFallbackOutputStepS.
  std::optional<double> step_s;
};

/// The output step [s] where output.step is unset and nothing chooses one from the response: the
/// reference deployments of database builds and screens, and the estimates made before a choice.
inline constexpr double kFallbackOutputStepS = 1e-4;

/// [uncertainty."KEY"] — the distribution of one uncertain input KEY (a floating-point key of
/// [module], [interface], [material] or [modes], or of one item: "module.2.mass"), every parameter
/// in KEY's own SI unit (docs/theory.md §7.1). Which parameters a distribution takes:
///   normal: mean, std;  lognormal: mean, std (of the value itself, not of its logarithm);
///   uniform: lower, upper;  truncated_normal: mean, std (of the normal before truncation),
///   lower, upper.
/// The nominal value of KEY elsewhere in the file is not used by `mastrom uq`.
struct UncertainInput {
  DistributionKind distribution = DistributionKind::Normal;
  std::optional<double> mean;
  std::optional<double> std_dev;  ///< TOML key `std`
  std::optional<double> lower;
  std::optional<double> upper;
};
bool operator==(const UncertainInput& a, const UncertainInput& b);

/// The whole configuration. Default-constructed = docs/theory.md §1 defaults (Scheme 3).
struct Config {
  MastConfig mast;
  ModuleConfig module;
  InterfaceConfig interface;
  MaterialConfig material;
  DriveConfig drive;
  SimulationConfig simulation;
  ModesConfig modes;
  OutputConfig output;
  std::map<int, ModuleItemConfig> module_items;        ///< [module.K], K = 1 … mast.modules
  std::map<int, InterfaceItemConfig> interface_items;  ///< [interface.K], K = 1 … modules − 1
  /// [uncertainty."KEY"]: the uncertain inputs by key (independent); empty for a plain run.
  std::map<std::string, UncertainInput> uncertainty;

  /// Module k (1 = the driven one): [module] with [module.k]'s keys on top.
  ModuleConfig moduleItem(int k) const;
  /// Interface k (joins module k to k + 1): [interface] with [interface.k]'s keys on top, the
  /// radius derived again when the inner diameter is the parametrisation.
  InterfaceConfig interfaceItem(int k) const;
};

/// The spacing of the output instants [s]: output.step with adaptive steps (kFallbackOutputStepS
/// when unset), else simulation.time_step · output.every. The full order and the ROM both sample
/// there.
double outputInterval(const Config& config);

bool operator==(const ModuleItemConfig& a, const ModuleItemConfig& b);
bool operator==(const InterfaceItemConfig& a, const InterfaceItemConfig& b);
bool operator==(const Config& a, const Config& b);
inline bool operator!=(const Config& a, const Config& b) { return !(a == b); }

/// Parse TOML text (source_name is used in syntax-error messages), apply derived values, validate.
/// @throws InputError on a syntax error, an unknown key, a wrong type or an out-of-range value.
Config parseConfigText(std::string_view toml, std::string_view source_name);

/// Read the TOML file at path, apply the overrides ("section.key=value", the value written as a
/// TOML value — numbers, booleans, arrays, quoted or bare strings) on top, derive and validate.
/// Overriding radius drops an inner_diameter given in the file and vice versa (the command line
/// wins); giving both in the file, or both as overrides, is an error.
/// @throws IoError if the file cannot be read; InputError for everything parseConfigText rejects
///         and for a malformed override.
Config loadConfig(const std::string& path, const std::vector<std::string>& overrides);

/// A resolved configuration with `--set`-style overrides applied on top (same semantics and errors
/// as loadConfig's overrides), derived and validated again.
Config applyConfigOverrides(const Config& base, const std::vector<std::string>& overrides);

/// The resolved configuration as TOML, every key present, with units in comments.
/// parseConfigText(toToml(c), …) == c exactly (doubles are written in shortest round-trip form).
std::string toToml(const Config& config);

/// Check every range and cross-key relation; throws InputError naming the first bad key.
void validate(const Config& config);

}  // namespace mastrom
