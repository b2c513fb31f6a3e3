#include "common/text_file.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/error.hpp"

namespace mastrom {

void writeTextFileAtomically(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp." + std::to_string(static_cast<long>(::getpid()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    MASTROM_REQUIRE(out.good(), IoError, "cannot write '", path, "' (temporary '", temporary,
                    "' cannot be created)");
    out << text;
    out.close();
    if (!out.good()) {
      std::remove(temporary.c_str());
      throw IoError(detail::concat("writing '", temporary, "' failed"));
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::remove(temporary.c_str());
    throw IoError(detail::concat("cannot rename '", temporary, "' to '", path, "': ", ec.message()));
  }
}

}  // namespace mastrom
