#include "dfc/common/temporary_folder.hpp"

#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "dfc/common/errors.hpp"

namespace dfc {

TemporaryFolder::TemporaryFolder(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw UserError("cannot make a temporary folder '" + pattern + "': " + std::strerror(errno) + "; check that TMPDIR names a writable folder");
  path_ = pattern;
}

TemporaryFolder::~TemporaryFolder() {
  std::error_code ignored;  // nothing to do about a folder already gone
  std::filesystem::remove_all(path_, ignored);
}

}  // namespace dfc
