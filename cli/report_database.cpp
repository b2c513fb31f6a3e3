#include "cli/report_database.hpp"

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <vector>

#include "common/hdf5_file.hpp"
#include "common/version.hpp"
#include "rom/database/database_io.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/database/parameter_space.hpp"

namespace mastrom::cli {
namespace {

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

/// kPointsPerAxis values evenly spaced over the sampled range of `axis`.
std::vector<double> linePoints(const rom::ParameterAxis& axis) {
  const double lo = axis.values.front(), hi = axis.values.back();
  std::vector<double> points(kPointsPerAxis);
  for (int i = 0; i < kPointsPerAxis; ++i)
    points[static_cast<std::size_t>(i)] = lo + (hi - lo) * i / (kPointsPerAxis - 1);
  return points;
}

/// Frequencies [Hz] and rotation participations of the interpolated model at each point (rows).
struct Evaluated {
  Eigen::MatrixXd frequency_hz, participation;
};

Evaluated evaluateAt(const rom::ModalInterpolator& interpolator,
                     const std::vector<std::vector<double>>& points, int modes) {
  Evaluated out;
  out.frequency_hz.resize(static_cast<Eigen::Index>(points.size()), modes);
  out.participation.resize(static_cast<Eigen::Index>(points.size()), modes);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const rom::ModalModel model = interpolator.evaluate(points[i]);
    MASTROM_REQUIRE(model.modeCount() >= modes, NumericalError, "report: the interpolated ROM has ",
                    model.modeCount(), " modes, expected ", modes);
    const auto row = static_cast<Eigen::Index>(i);
    out.frequency_hz.row(row) = model.omega_rad_s.head(modes).transpose() / kTwoPi;
    out.participation.row(row) = model.rotation_participation.head(modes).transpose();
  }
  return out;
}

void writeEvaluated(h5::File& file, const std::string& group, const Evaluated& e) {
  file.writeMatrix(group + "/frequency_hz", e.frequency_hz, "Hz");
  file.writeMatrix(group + "/participation", e.participation, "kg^0.5*m");
}

}  // namespace

bool isRomDatabaseFile(const std::string& path) {
  try {
    const h5::File file = h5::File::open(path, h5::OpenMode::ReadOnly);
    return file.hasAttribute("/", "source") &&
           file.readStringAttribute("/", "source") == "rom-database";
  } catch (const std::exception&) {
    return false;
  }
}

void writeDatabaseCurves(const std::string& database_path, const std::string& out_path) {
  const rom::RomDatabase db = rom::readDatabase(database_path);
  const std::unique_ptr<rom::ModalInterpolator> interpolator =
      rom::makeInterpolator(db, db.default_method);
  const std::vector<double>& reference =
      db.samples[static_cast<std::size_t>(db.reference_sample)].parameters;
  const int modes = db.modes_per_sample;

  h5::AtomicH5Writer writer(out_path);
  h5::File& file = writer.file();
  for (std::size_t a = 0; a < db.axes.size(); ++a) {
    const std::string group = "/axis_" + std::to_string(a);
    const std::vector<double> values = linePoints(db.axes[a]);
    std::vector<std::vector<double>> points(values.size(), reference);
    for (std::size_t i = 0; i < values.size(); ++i) points[i][a] = values[i];
    file.createGroup(group);
    file.writeDoubles(group + "/values", values, rom::configKeyUnits(db.axes[a].key));
    writeEvaluated(file, group, evaluateAt(*interpolator, points, modes));
    file.setStringAttribute(group, "key", db.axes[a].key);
    file.writeDoubles(group + "/held", reference, "1");
  }
  if (db.axes.size() >= 2) {
    const std::vector<double> x = linePoints(db.axes[0]), y = linePoints(db.axes[1]);
    std::vector<std::vector<double>> points;
    points.reserve(x.size() * y.size());
    for (double xi : x)
      for (double yj : y) {
        std::vector<double> p = reference;
        p[0] = xi;
        p[1] = yj;
        points.push_back(std::move(p));
      }
    file.createGroup("/plane");
    file.writeDoubles("/plane/values_0", x, rom::configKeyUnits(db.axes[0].key));
    file.writeDoubles("/plane/values_1", y, rom::configKeyUnits(db.axes[1].key));
    writeEvaluated(file, "/plane", evaluateAt(*interpolator, points, modes));
  }
  file.setStringAttribute("/", "source", "rom-database-curves");
  file.setStringAttribute("/", "database", database_path);
  file.setStringAttribute("/", "method", rom::toString(db.default_method));
  file.setIntAttribute("/", "axes", static_cast<int>(db.axes.size()));
  file.setStringAttribute("/", "mastrom_version", kVersion);
  writer.commit();
}

}  // namespace mastrom::cli
