// The online stage of the ROM (docs/theory.md §4.4): a modal model anywhere in the database's box,
// from the samples. Interchangeable methods behind one interface:
//  (a) Tracked  — the per-mode quantities (ω, ζ, Γ, Γ_c, ψ, …) interpolated multilinearly on the
//      tensor grid after MAC tracking and sign alignment (rom/interpolation/tracked_interpolation.hpp);
//  (b) Manifold — aligned reduced matrices interpolated on the SPD manifold, then a small dense
//      eigenproblem (rom/interpolation/spd_interpolation.hpp);
//  (d) Rbf — the quantities of (a) with radial-basis weights over samples anywhere in the box
//      (rom/interpolation/rbf_weights.hpp): the method of scattered databases;
//  (c) Affine — no interpolation: the exact affine terms in (h, E, ρ) stored with the database
//      (rom/interpolation/affine_interpolation.hpp); only for a database that carries them.
// An interpolator extrapolates linearly outside the box; whether that is allowed is the caller's
// decision (rom/database/parameter_space.hpp requireInsideBox).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rom/model/modal_model.hpp"
#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

class ModalInterpolator {
public:
  virtual ~ModalInterpolator();
  /// The modal model at `parameters` (one value per database axis, in axis order), modes in
  /// ascending frequency. Throws InputError when the number of values is wrong or one is not
  /// finite.
  virtual ModalModel evaluate(const std::vector<double>& parameters) const = 0;
  /// The same with the interfaces' modal stresses (ModalModel::stress, docs/theory.md §6.5)
  /// interpolated with the same weights, tracking and alignment as the per-mode quantities — an
  /// extra cost of O(samples in the stencil × stress rows × modes), so only on request. Empty
  /// stresses when the database carries none (affine: when its terms were built without the
  /// basis's stress rows).
  virtual ModalModel evaluateWithStresses(const std::vector<double>& parameters) const {
    return evaluate(parameters);
  }
  /// evaluateWithStresses at each of `points`, the same models bit for bit. An interpolator whose
  /// stress rows are weighted sums over the same samples at every point reads each sample's rows
  /// once for all the points (a screen's batch of designs) instead of once per point.
  virtual std::vector<ModalModel> evaluateWithStressesAt(
      const std::vector<std::vector<double>>& points) const;
};

/// An interpolator over `db` (which it copies what it needs from: `db` may be destroyed after).
/// Throws InputError for an inconsistent database, or for a method this build does not provide.
std::unique_ptr<ModalInterpolator> makeInterpolator(const RomDatabase& db,
                                                    InterpolationMethod method);

/// `inner`, an interpolator over sampledDatabase(db), made an interpolator over `db`'s axes by the
/// exact scaling in Young's modulus (docs/theory.md (4.12)); `inner` itself when `db` handles no
/// axis exactly. makeInterpolator does this for every method; this is for an interpolator built
/// otherwise (e.g. TrackedInterpolator::radialBasis with a quadratic tail).
std::unique_ptr<ModalInterpolator> withExactModulus(const RomDatabase& db,
                                                    std::unique_ptr<ModalInterpolator> inner);

/// True when makeInterpolator can build `method` in this build.
bool interpolationMethodAvailable(InterpolationMethod method);

/// The methods makeInterpolator can build over `db` in this build, in the order of
/// allInterpolationMethods(): the grid methods on a tensor grid, rbf on any samples (at least
/// p + 2 of them), affine where the database carries its terms (docs/theory.md §4.4).
std::vector<InterpolationMethod> interpolationMethodsFor(const RomDatabase& db);

}  // namespace mastrom::rom
