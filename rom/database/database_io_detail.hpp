// Internals shared by the implementation files of rom/database/database_io.hpp:
// database_layout.cpp (the /samples datasets as arrays, the content checksum, the check that a
// database fits the file's layout), database_write.cpp (RomDatabase → file) and
// database_read.cpp (file → RomDatabase, verified). Writing and reading go through the same table
// and the same checksum so that what one writes the other accepts. Not part of the library's
// interface.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "rom/database/affine_reduced.hpp"
#include "rom/database/rom_database.hpp"

namespace mastrom::rom::database_io_detail {

// --- the /samples datasets: one table drives writing, reading, shape checks and the checksum -----
enum class Shape { S, SP, SK, S3, S3K, SKK };

/// What a /samples dataset holds: a sample-level array, or one field of the modal model (which the
/// model's own field list, forEachModalField, describes).
enum class FieldId {
  Parameters,
  Model,
  Alignment,
  Tracking,
  TrackingSign,
  LooFrequency,
  LooResponse
};

struct Field {
  FieldId id;
  int model_field;  ///< index in forEachModalField order (FieldId::Model only)
  const char* name;
  Shape shape;
  const char* units;
  bool integer;
};

/// Every /samples dataset, in file and checksum order: the parameters, the modal model's fields,
/// then the tracking data and the leave-one-out errors.
const std::vector<Field>& sampleFields();

struct Sizes {
  std::size_t s, p, k;
};

std::vector<std::size_t> dimsOf(Shape shape, const Sizes& n);

/// "[2, 3]": a shape as the refusal messages print it.
std::string shapeText(const std::vector<std::size_t>& d);

/// One /samples dataset in memory (row-major).
struct Array {
  const Field* field;
  std::vector<std::size_t> dims;
  std::vector<double> d;
  std::vector<int> i;
};

/// Field f of every sample, laid out as its dataset.
Array flatten(const Field& f, const RomDatabase& db, const Sizes& n);

/// Every /samples dataset of the database, in sampleFields() order.
std::vector<Array> sampleArrays(const RomDatabase& db, const Sizes& n);

/// Field a.field of every sample of db (already sized to n.s samples) from its dataset.
void assign(const Array& a, RomDatabase& db, const Sizes& n);

/// The content checksum of database_io.hpp: over the root attributes and axes of db, the /stress
/// arrays `stress` and the /samples `arrays`.
std::string checksum(const RomDatabase& db, const std::vector<Array>& arrays,
                     const std::vector<NamedArray>& stress);

/// InputError unless the database can be laid out as the file's [S, …, k] arrays.
Sizes checkWritable(const RomDatabase& db);

}  // namespace mastrom::rom::database_io_detail
