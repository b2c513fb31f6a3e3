// Method (c) of docs/theory.md §4.4 behind the ModalInterpolator interface: a database whose axes
// are all among interface.thickness (fixed radius), material.youngs_modulus and material.density
// carries the exact affine terms (RomDatabase::affine); evaluating is AffineModalModel::evaluate at
// (h, E, ρ), the parameters not on an axis taken at their one value in the affine model's box (the
// database's base configuration). Nothing is interpolated: the error is the truncation to the
// stored basis alone (rom/interpolation/affine_model.hpp), at every point of the box.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "rom/interpolation/affine_model.hpp"
#include "rom/interpolation/interpolator.hpp"

namespace mastrom::rom {

/// True when a database over these axes can carry the affine terms: every key is
/// interface.thickness (not with an inner-diameter parametrisation, where R moves with h),
/// material.youngs_modulus or material.density, no interface differs from [interface] and
/// gravity is off. `why` receives the reason when
/// not.
bool affineApplicable(const Config& base, const std::vector<ParameterAxis>& axes,
                      std::string* why = nullptr);

class AffineInterpolator final : public ModalInterpolator {
public:
  /// Throws InputError when the database carries no affine terms, or an axis is not one of the
  /// three affine parameters.
  explicit AffineInterpolator(const RomDatabase& db);
  /// Throws InputError for a wrong number of values, or a point outside the affine model's box
  /// (the affine terms are exact inside it; no extrapolation).
  ModalModel evaluate(const std::vector<double>& parameters) const override;
  /// With the interfaces' modal stresses (docs/theory.md §6.5) when the database carries them: the
  /// stress per mode exactly, from the basis's stress rows (AffineModalModel::stressModes); the
  /// static-correction and preload stresses, which are not modal, interpolated from the samples
  /// with the cubic method's weights.
  ModalModel evaluateWithStresses(const std::vector<double>& parameters) const override;

private:
  /// (h, E, ρ) of a point given on the database's axes.
  std::array<double, 3> affineValues(const std::vector<double>& parameters) const;

  AffineModalModel model_;
  /// The samples' stresses where both they and the affine terms carry them; else null.
  std::unique_ptr<ModalInterpolator> sampled_stress_;
  std::array<int, 3> axis_of_{{-1, -1, -1}};  ///< axis index of h, E, ρ (−1 = fixed)
  std::array<double, 3> fixed_{{0.0, 0.0, 0.0}};
};

}  // namespace mastrom::rom
