// The mass and the natural frequencies of a design of a ROM database (docs/theory.md §1.7): what
// every design description adds to its deployment's metrics (rom/studies/design_metrics.hpp).
//
// Mass. The items' masses of (1.12) at the design's point: the database's base configuration with
// the point's values of the keys that change a mass (module.mass, the interfaces' length, radius or
// inner diameter and thickness, material.density; also per item) — no other key moves it, and a
// point that changes none of them reuses the base's.
//
// Frequencies. The lowest N natural frequencies of the mast locked at the deployed angle Θ (the end
// of the drive: θ(T) = Θ) and their estimated errors (4.15). The database holds its modes at the
// locked angle θ₀ = modes.angle_deg. Turning the locked mast about the joint axis Z maps it onto
// itself unless gravity has a component in the plane of the turn (X, Y): without one the modes at
// Θ are those at θ₀ and the deployment's own model gives them. With one, the database can give
// them only where it holds modes at Θ: over a modes.angle_deg axis that spans Θ (the model is
// then evaluated at θ₀ = Θ, a second interpolation per design), or when its θ₀ is Θ. Otherwise it
// cannot: asked for explicitly, that is an InputError naming why; by default the columns are left
// out (MetricColumns::no_frequency_reason says why).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/offline/frequency_error_estimate.hpp"
#include "rom/studies/design_metrics.hpp"

namespace mastrom::rom {

/// The frequencies a design description gets unless told otherwise.
inline constexpr int kDefaultFrequencyCount = 3;

/// How many natural frequencies, and whether the user asked (then a database that cannot give
/// them is an error) or it is the default (then they are left out).
struct FrequencyRequest {
  int count = kDefaultFrequencyCount;
  bool explicit_request = false;
  std::string option = "--frequencies";  ///< how the user spells it, for messages
};

/// The items' masses of the configuration `config` (docs/theory.md (1.12)).
fullorder::MastMass configuredMass(const Config& config);

class DesignDescriber {
public:
  /// For designs of `db` evaluated on `base` (the database's base configuration with the run's
  /// overrides), deployed to the angles `deployed_angles_deg` (one per free case: drive.angle_deg
  /// may vary). InputError (one line) for a request the database cannot meet: more frequencies
  /// than it holds, or frequencies at an angle it holds no modes at (see the header).
  DesignDescriber(const RomDatabase& db, const Config& base, const FrequencyRequest& request,
                  const std::vector<double>& deployed_angles_deg, BoxPolicy box);

  /// The columns of a description with `stress_interfaces` stress columns (and `margin`).
  MetricColumns columns(int stress_interfaces, bool margin,
                        const std::string& no_stress_reason = "") const;
  int frequencies() const { return frequencies_; }

  /// Mass and frequencies of the design at `point` (one value per database axis) deployed by free
  /// case `free_case`; `model` is the interpolated model at `point` (the deployment's).
  void describe(const ModalInterpolator& interpolator, const ModalModel& model,
                const std::vector<double>& point, std::size_t free_case, DesignValues& out) const;

  /// The mass alone.
  fullorder::MastMass massAt(const std::vector<double>& point) const;

private:
  enum class AngleSource { Invariant, AngleAxis };
  Config base_;
  std::vector<ParameterAxis> axes_;
  std::vector<int> mass_axes_;  ///< the axes whose key changes a mass
  fullorder::MastMass base_mass_;
  int frequencies_ = 0;
  std::string no_frequency_reason_;
  AngleSource source_ = AngleSource::Invariant;
  int angle_axis_ = -1;
  std::vector<double> deployed_deg_;
  std::shared_ptr<const FrequencyErrorEstimate> estimate_;
};

}  // namespace mastrom::rom
