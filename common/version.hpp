// The mastrom version written into every output file (docs/user_guide.md §5, root attribute
// `mastrom_version`). It must equal `project(mastrom VERSION …)` in the top-level CMakeLists.txt;
// tests/common/test_hdf5_file.cpp checks that the two agree.
#pragma once

#include <string_view>

namespace mastrom {

/// Semantic version of this build of mastrom.
inline constexpr std::string_view kVersion = "0.1.0";

}  // namespace mastrom
