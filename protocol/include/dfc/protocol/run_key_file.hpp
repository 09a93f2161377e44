#pragma once
// RunKeyFile: the keys a supervisor (the coupler, the conformance checker)
// makes for the servers it starts (SPEC.md §2.1): a fresh key pair per run,
// written to FOLDER/keys/server.key (the folder mode 0700, the file 0600)
// and named to each server in its environment (DFC_KEY_FILE), never on its
// command line. The file is removed when this object goes away: the servers
// read it once, at their start.
#include <filesystem>

#include "dfc/protocol/authentication.hpp"

namespace dfc::protocol {

class RunKeyFile {
 public:
  /// Makes the keys and writes them under `folder` (which must exist). Throws
  /// dfc::UserError when the keys folder cannot be made private (another
  /// user's folder, a link or a file in its place).
  explicit RunKeyFile(const std::filesystem::path& folder);
  ~RunKeyFile();
  RunKeyFile(const RunKeyFile&) = delete;
  RunKeyFile& operator=(const RunKeyFile&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }
  [[nodiscard]] const authentication::CurveKeyPair& keys() const noexcept { return keys_; }
  /// "DFC_KEY_FILE=<path>", for the environment of a server started now.
  [[nodiscard]] std::string environment_entry() const;

 private:
  std::filesystem::path path_;
  authentication::CurveKeyPair keys_;
};

}  // namespace dfc::protocol
