// One scratch file per fuzzing process, shared by the database fuzz targets: each input is written
// to it once and read back through the real file-based entry points (readDatabase(path)).
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace mastrom::fuzz {

/// A per-process scratch file named after `tag`, on tmpfs when there is one; removed at exit.
/// Call it with one tag per process (the path is fixed by the first call).
inline const std::string& scratchPath(const char* tag) {
  static const std::string path = [tag] {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path dir =
        fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
    return (dir / (std::string("mastrom_fuzz_") + tag + "_" + std::to_string(::getpid()) + ".h5"))
        .string();
  }();
  static const bool cleanup_registered = [] {
    return std::atexit([] { std::remove(path.c_str()); }) == 0;
  }();
  (void)cleanup_registered;
  return path;
}

}  // namespace mastrom::fuzz
