// Small text files written atomically: the text goes to "<path>.tmp.<pid>" in the same directory
// and is renamed over `path` when complete, so a crash never leaves a truncated file under the
// final name (the same rule as h5::AtomicH5Writer for HDF5 results).
#pragma once

#include <string>

namespace mastrom {

/// Write `text` to `path` atomically. IoError naming the path on failure (nothing is left behind).
void writeTextFileAtomically(const std::string& path, const std::string& text);

}  // namespace mastrom
