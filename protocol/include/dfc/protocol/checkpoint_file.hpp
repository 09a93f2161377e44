#pragma once
// A server's checkpoint file (SPEC.md §4.7): who wrote it, for which section,
// at which step, and the solver's state bytes, with a checksum.
//
// Layout: the 8 bytes "DFCCKPT1", a byte-order mark (u32 0x01020304), the
// header as JSON text, the state bytes, and the FNV-1a hash of the state
// (each text and byte run preceded by its u64 length; state_archive.hpp).
// The file is written under a temporary name and renamed, so a process killed
// while writing leaves the previous file or none, never half of one.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace dfc::protocol {

struct CheckpointHeader {
  std::string solver_name;
  std::string solver_version;
  std::string scenario_hash;  ///< configured.scenario_hash of the session that wrote it (SPEC.md §4.2)
  std::int64_t step = 0;      ///< the server's step count when it was written
};

struct CheckpointFile {
  CheckpointHeader header;
  std::string state;
};

/// Throws ProtocolError(bad_checkpoint) naming the path when it cannot be written.
void write_checkpoint_file(const std::filesystem::path& path, const CheckpointHeader& header, std::string_view state);
/// Throws ProtocolError(bad_checkpoint) naming the path when it is missing,
/// unreadable, truncated or damaged.
[[nodiscard]] CheckpointFile read_checkpoint_file(const std::filesystem::path& path);
/// Empty when a file with header `written` may be restored into a session
/// with `current`; else a sentence naming what differs (solver, its version,
/// or the section the session was configured with).
[[nodiscard]] std::string checkpoint_mismatch(const CheckpointHeader& written, const CheckpointHeader& current);

}  // namespace dfc::protocol
