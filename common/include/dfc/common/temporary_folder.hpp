#pragma once
// TemporaryFolder: a folder of this process's own under the system's
// temporary folder (mkdtemp: a new, unpredictable name, mode 0700, so that
// no other user can have made it first or look inside), removed with
// everything in it when the object goes away. For what a supervisor keeps
// only while it runs: the servers' logs of `coupler check`, the key file of
// the servers it starts (protocol/SPEC.md §2.1).
#include <filesystem>
#include <string>

namespace dfc {

class TemporaryFolder {
 public:
  /// Makes "<temp>/<prefix>XXXXXX". Throws dfc::UserError if it cannot.
  explicit TemporaryFolder(const std::string& prefix);
  ~TemporaryFolder();
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace dfc
