#include "rom/interpolation/interpolator.hpp"

#include "common/error.hpp"
#include "common/option_names.hpp"
#include "rom/interpolation/affine_interpolation.hpp"
#include "rom/interpolation/rbf_weights.hpp"
#include "rom/interpolation/tracked_interpolation.hpp"
#include "rom/model/modulus_scaling.hpp"

// ---- MANIFOLD SWITCH (the one line below): 1 = method (b) from rom/interpolation/spd_interpolation.hpp
// ---- (makeManifoldInterpolator); 0 = a build without it, where "manifold" is an InputError.
#define MASTROM_ROM_HAVE_MANIFOLD_INTERPOLATION 1
#if MASTROM_ROM_HAVE_MANIFOLD_INTERPOLATION
#include "rom/interpolation/spd_interpolation.hpp"
#endif

namespace mastrom::rom {

ModalInterpolator::~ModalInterpolator() = default;

std::vector<ModalModel> ModalInterpolator::evaluateWithStressesAt(
    const std::vector<std::vector<double>>& points) const {
  std::vector<ModalModel> models;
  models.reserve(points.size());
  for (const std::vector<double>& p : points) models.push_back(evaluateWithStresses(p));
  return models;
}

namespace {

/// Young's modulus handled exactly (docs/theory.md §4.4 (e)): the other axes by the inner method
/// at the reference E₀, then the exact scaling of rom/model/modulus_scaling.hpp to the E asked for.
class ExactModulusInterpolator final : public ModalInterpolator {
public:
  ExactModulusInterpolator(std::unique_ptr<ModalInterpolator> inner, int axis, std::size_t axes,
                           double reference_pa)
      : inner_(std::move(inner)), axis_(axis), axes_(axes), reference_pa_(reference_pa) {}

  ModalModel evaluate(const std::vector<double>& parameters) const override {
    ModalModel m = inner_->evaluate(reduced(parameters));
    scaleYoungsModulus(m, ratio(parameters));
    return m;
  }
  ModalModel evaluateWithStresses(const std::vector<double>& parameters) const override {
    ModalModel m = inner_->evaluateWithStresses(reduced(parameters));
    scaleYoungsModulus(m, ratio(parameters));
    return m;
  }
  std::vector<ModalModel> evaluateWithStressesAt(
      const std::vector<std::vector<double>>& points) const override {
    std::vector<std::vector<double>> inner_points;
    for (const std::vector<double>& p : points) inner_points.push_back(reduced(p));
    std::vector<ModalModel> models = inner_->evaluateWithStressesAt(inner_points);
    for (std::size_t b = 0; b < points.size(); ++b) scaleYoungsModulus(models[b], ratio(points[b]));
    return models;
  }

private:
  void check(const std::vector<double>& parameters) const {
    MASTROM_REQUIRE(parameters.size() == axes_, InputError, "rom: ", parameters.size(),
                    " parameter values for a database of ", axes_, " axes");
  }
  std::vector<double> reduced(const std::vector<double>& parameters) const {
    check(parameters);
    std::vector<double> r = parameters;
    r.erase(r.begin() + axis_);
    return r;
  }
  double ratio(const std::vector<double>& parameters) const {
    return parameters[static_cast<std::size_t>(axis_)] / reference_pa_;
  }

  std::unique_ptr<ModalInterpolator> inner_;
  int axis_;
  std::size_t axes_;
  double reference_pa_;
};

}  // namespace

std::unique_ptr<ModalInterpolator> withExactModulus(const RomDatabase& db,
                                                    std::unique_ptr<ModalInterpolator> inner) {
  if (!db.exact_modulus) return inner;
  const int axis = db.exactModulusAxis();
  MASTROM_REQUIRE(axis >= 0, InputError, "rom database: Young's modulus is handled exactly but no "
                  "axis is ", kYoungsModulusKey);
  return std::make_unique<ExactModulusInterpolator>(std::move(inner), axis, db.axes.size(),
                                                    db.exact_modulus->reference_pa);
}

bool interpolationMethodAvailable(InterpolationMethod method) {
  return method != InterpolationMethod::Manifold || MASTROM_ROM_HAVE_MANIFOLD_INTERPOLATION;
}

std::vector<InterpolationMethod> interpolationMethodsFor(const RomDatabase& db) {
  // An exactly handled E leaves the choice to the sampled axes, as makeInterpolator does.
  if (db.exact_modulus) return interpolationMethodsFor(sampledDatabase(db));
  const std::size_t rbf_fewest =
      static_cast<std::size_t>(radialBasisMinimumSamples(static_cast<int>(db.axes.size())));
  std::vector<InterpolationMethod> methods;
  for (const InterpolationMethod m : allInterpolationMethods()) {
    const bool fits = m == InterpolationMethod::Affine ? db.affine.has_value()
                      : m == InterpolationMethod::Rbf  ? db.samples.size() >= rbf_fewest
                                                       : db.isGrid();
    if (fits && interpolationMethodAvailable(m)) methods.push_back(m);
  }
  return methods;
}

namespace {

/// The way out of a refused method: every method that works for `db`, and the option naming one.
std::string methodsThatWork(const RomDatabase& db) {
  std::string names;
  for (const InterpolationMethod m : interpolationMethodsFor(db))
    names += (names.empty() ? "" : ", ") + toString(m);
  return detail::concat("methods that work for it: ", names, "; choose one with ",
                        optionName(Option::Method));
}

}  // namespace

std::unique_ptr<ModalInterpolator> makeInterpolator(const RomDatabase& db,
                                                    InterpolationMethod method) {
  if (db.exact_modulus) return withExactModulus(db, makeInterpolator(sampledDatabase(db), method));
  MASTROM_REQUIRE(
      db.isGrid() || method == InterpolationMethod::Rbf || method == InterpolationMethod::Affine,
      InputError, "rom: the ", toString(method),
      " method needs a tensor-grid database; this one has scattered samples (", methodsThatWork(db),
      ")");
  MASTROM_REQUIRE(method != InterpolationMethod::Affine || db.affine.has_value(), InputError,
                  "rom: this database carries no affine terms (built over parameters that do not "
                  "all enter affinely; ",
                  methodsThatWork(db), ")");
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
