#include "rom/interpolation/interpolator.hpp"

#include "common/error.hpp"
#include "rom/interpolation/affine_interpolation.hpp"
#include "rom/interpolation/tracked_interpolation.hpp"

// ---- MANIFOLD SWITCH (the one line below): 1 = method (b) from rom/interpolation/spd_interpolation.hpp
// ---- (makeManifoldInterpolator); 0 = a build without it, where "manifold" is an InputError.
#define MASTROM_ROM_HAVE_MANIFOLD_INTERPOLATION 1
#if MASTROM_ROM_HAVE_MANIFOLD_INTERPOLATION
#include "rom/interpolation/spd_interpolation.hpp"
#endif

namespace mastrom::rom {

ModalInterpolator::~ModalInterpolator() = default;

bool interpolationMethodAvailable(InterpolationMethod method) {
  return method != InterpolationMethod::Manifold || MASTROM_ROM_HAVE_MANIFOLD_INTERPOLATION;
}

std::unique_ptr<ModalInterpolator> makeInterpolator(const RomDatabase& db,
                                                    InterpolationMethod method) {
  MASTROM_REQUIRE(db.isGrid() || method == InterpolationMethod::Rbf ||
                      method == InterpolationMethod::Affine,
                  InputError, "rom: the ", toString(method),
                  " method needs a tensor-grid database; this one has scattered samples (use "
                  "--method rbf)");
  switch (method) {
    case InterpolationMethod::Tracked:
      return std::make_unique<TrackedInterpolator>(db);
    case InterpolationMethod::Manifold:
#if MASTROM_ROM_HAVE_MANIFOLD_INTERPOLATION
      return makeManifoldInterpolator(db);
#else
      throw InputError("manifold interpolation not available in this build");
#endif
    case InterpolationMethod::Affine:
      return std::make_unique<AffineInterpolator>(db);
    case InterpolationMethod::Cubic:
      return std::make_unique<TrackedInterpolator>(db, AxisWeighting::Logarithmic, 3);
    case InterpolationMethod::Rbf:
      return TrackedInterpolator::radialBasis(db);
  }
  throw InputError("rom: unknown interpolation method");
}

}  // namespace mastrom::rom
