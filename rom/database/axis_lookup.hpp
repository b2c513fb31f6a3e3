// Finding a database's parameter axes by key: what every study (screen, uq, optimize) needs to
// map the keys a user names onto the axes of the box.
#pragma once

#include <string>

#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

/// The index of the axis whose key is `key`, or −1 when the database does not vary it.
inline int axisIndex(const RomDatabase& db, const std::string& key) {
  for (std::size_t a = 0; a < db.axes.size(); ++a)
    if (db.axes[a].key == key) return static_cast<int>(a);
  return -1;
}

/// The axes' keys, comma-separated (for messages that list what a database varies).
inline std::string axisKeys(const RomDatabase& db) {
  std::string keys;
  for (const ParameterAxis& a : db.axes) keys += (keys.empty() ? "" : ", ") + a.key;
  return keys;
}

}  // namespace mastrom::rom
