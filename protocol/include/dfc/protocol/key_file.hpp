#pragma once
// The key file of a server (SPEC.md §2.1): the server's CURVE key pair as
// JSON, readable by its owner alone. Unix permissions are what keep the
// secret: whoever can read the file can talk to the server, so the reader
// refuses a file that others may read or write, as ssh does for its keys.
//
//   {"dfc_key_file": 1, "public_key": "<40 Z85 characters>", "secret_key": "<40 Z85 characters>"}
#include <filesystem>

#include "dfc/protocol/authentication.hpp"

namespace dfc::protocol {

/// The value of "dfc_key_file": the format's version.
inline constexpr int kKeyFileFormat = 1;

/// Writes `keys` to a new file at `path` with mode 0600 (an existing file
/// there is replaced, never written through: a link is not followed).
/// Throws dfc::UserError naming the path.
void write_key_file(const std::filesystem::path& path, const authentication::CurveKeyPair& keys);

/// Reads the key pair at `path`. Throws dfc::UserError whose sentence names
/// the path, what is wrong and the fix: a missing or unreadable file, one
/// that belongs to another user or that group or others may access
/// ("chmod 600"), or one whose content is not
/// a key file (the keys are not Z85 text of 32 bytes, or do not belong together).
[[nodiscard]] authentication::CurveKeyPair read_key_file(const std::filesystem::path& path);

}  // namespace dfc::protocol
