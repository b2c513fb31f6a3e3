// libFuzzer target for the ROM database's structural layer (rom/database/database_io.hpp and the
// interpolators behind it; docs/theory.md §4.3–4.4, docs/user_guide.md §5).
//
// Byte mutations of a database file (fuzz_rom_database.cpp) almost never survive the content
// checksum, so they never reach what the reader and the interpolators check after it. This target
// works one level up: the input is a list of edits of the decoded content of a small valid
// database (axis values, parameters, per-mode values, tracking, signs, alignment, counts). The
// edited database goes the way a crafted file with a recomputed checksum would: writeDatabase
// (refusing with InputError is allowed), readDatabase (must then accept it and return the same
// values), makeInterpolator and evaluate for both methods at a fuzzed point (InputError and
// NumericalError are allowed). Any other exception, a crash or a sanitizer report is a finding.
#include <fuzzer/FuzzedDataProvider.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "rom/database/database_io.hpp"
#include "scratch_file.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/model/modal_fields.hpp"
#include "rom_fixtures.hpp"

namespace {

using mastrom::rom::RomDatabase;

const std::string& scratchPath() { return mastrom::fuzz::scratchPath("rom_content"); }

/// The same small database as the file fuzzer's seed (fuzz/make_seed_database.cpp): 2 × 2 samples,
/// 2 modes each.
const RomDatabase& seed() {
  static const RomDatabase db = mastrom::rom::testing::bilinearDatabase(
      mastrom::rom::testing::randomBilinearModel(2, 7), {1e-3, 2e-3}, {0.4, 0.6}, 11);
  return db;
}

template <typename T>
T& pick(FuzzedDataProvider& in, std::vector<T>& v) {
  return v[in.ConsumeIntegralInRange<std::size_t>(0, v.size() - 1)];
}

/// The number of fields of the modal model.
const int kModelFields = static_cast<int>(mastrom::rom::modalFieldList().size());

/// Set entry `entry` (modulo the size) of a field to x.
void setEntry(double& member, std::size_t, double x) { member = x; }
template <class Derived>
void setEntry(Eigen::DenseBase<Derived>& member, std::size_t entry, double x) {
  if (member.size() == 0) return;
  const auto i = static_cast<Eigen::Index>(entry % static_cast<std::size_t>(member.size()));
  member(i % member.rows(), i / member.rows()) = x;
}

/// One edit of the decoded content, chosen and parametrised by the input.
void edit(FuzzedDataProvider& in, RomDatabase& db) {
  mastrom::rom::RomSample& s = pick(in, db.samples);
  mastrom::rom::ModalModel& m = s.modal;
  const auto k = static_cast<Eigen::Index>(m.modeCount());
  const auto j = in.ConsumeIntegralInRange<Eigen::Index>(0, k - 1);
  const auto r = in.ConsumeIntegralInRange<Eigen::Index>(0, k - 1);
  const double x = in.ConsumeFloatingPoint<double>();
  const int n = in.ConsumeIntegral<int>();
  switch (in.ConsumeIntegralInRange<int>(0, 8)) {
    case 0:
      pick(in, db.axes).values.at(0) = x;
      break;
    case 1:
      pick(in, pick(in, db.axes).values) = x;
      break;
    case 2:
      pick(in, s.parameters) = x;
      break;
    case 3: {  // any entry of any field of the modal model (rom/model/modal_model.hpp)
      const int field = in.ConsumeIntegralInRange<int>(0, kModelFields - 1);
      const auto entry = in.ConsumeIntegral<std::size_t>();
      int index = 0;
      mastrom::rom::forEachModalField(m, [&](const mastrom::rom::ModalFieldInfo&, auto& member) {
        if (index++ == field) setEntry(member, entry, x);
      });
      break;
    }
    case 4:
      s.alignment(r, j) = x;
      break;
    case 5:
      s.tracking[static_cast<std::size_t>(j)] = n;
      break;
    case 6:
      s.tracking_sign[static_cast<std::size_t>(j)] = n;
      break;
    case 7:
      db.reference_sample = n;
      break;
    case 8:
      s.loo_frequency_error = x;
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace mastrom;
  FuzzedDataProvider in(data, size);
  RomDatabase db = seed();
  const int edits = in.ConsumeIntegralInRange<int>(1, 4);
  for (int e = 0; e < edits; ++e) edit(in, db);
  const std::vector<double> point{in.ConsumeFloatingPoint<double>(),
                                  in.ConsumeFloatingPoint<double>()};

  try {
    rom::writeDatabase(scratchPath(), db);
  } catch (const InputError&) {
    return 0;  // the writer refused the content: nothing reaches a file
  }
  const RomDatabase back = rom::readDatabase(scratchPath());  // IoError here is a finding
  if (rom::databaseChecksum(back) != rom::databaseChecksum(db)) std::abort();
  for (const auto method :
       {rom::InterpolationMethod::Tracked, rom::InterpolationMethod::Manifold}) {
    try {
      rom::makeInterpolator(back, method)->evaluate(point);
    } catch (const InputError&) {
    } catch (const NumericalError&) {
    }
  }
  return 0;
}
