#include "dfc/protocol/run_key_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "dfc/common/errors.hpp"
#include "dfc/protocol/key_file.hpp"

namespace dfc::protocol {

namespace {

/// FOLDER/keys, private to this user: made with mode 0700, or, left by an
/// earlier run (a resumed one), checked to be this user's folder and set to 0700.
std::filesystem::path private_keys_folder(const std::filesystem::path& folder) {
  const std::filesystem::path keys = folder / "keys";
  const auto fail = [&](const std::string& why) {
    return UserError("cannot make the private key folder '" + keys.string() + "': " + why);
  };
  if (::mkdir(keys.c_str(), 0700) != 0 && errno != EEXIST) throw fail(std::strerror(errno));
  struct stat status {};
  if (::lstat(keys.c_str(), &status) != 0) throw fail(std::strerror(errno));
  if (!S_ISDIR(status.st_mode)) throw fail("something other than a folder is there (a link or a file); remove it");
  if (status.st_uid != ::geteuid()) throw fail("it belongs to another user; remove it or choose another output folder");
  if (::chmod(keys.c_str(), 0700) != 0) throw fail(std::strerror(errno));
  return keys;
}

}  // namespace

RunKeyFile::RunKeyFile(const std::filesystem::path& folder)
    : path_(private_keys_folder(folder) / "server.key"), keys_(authentication::generate_key_pair()) {
  write_key_file(path_, keys_);
}

RunKeyFile::~RunKeyFile() {
  std::error_code ignored;  // a file already gone is what we want
  std::filesystem::remove(path_, ignored);
  std::filesystem::remove(path_.parent_path(), ignored);  // only if empty
}

std::string RunKeyFile::environment_entry() const { return std::string(authentication::kKeyFileVariable) + "=" + path_.string(); }

}  // namespace dfc::protocol
