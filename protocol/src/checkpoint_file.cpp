#include "dfc/protocol/checkpoint_file.hpp"

#include <algorithm>
#include <fstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "dfc/common/state_archive.hpp"
#include "dfc/common/version.hpp"
#include "dfc/common/work_progress.hpp"
#include "dfc/protocol/error_code.hpp"

namespace dfc::protocol {

namespace {
constexpr std::string_view kMagic = "DFCCKPT1";
// A large model's state is gigabytes: it moves to and from the disk in
// chunks, the heartbeat's work counter moving per chunk (SPEC.md §9.1).
constexpr std::size_t kChunkBytes = std::size_t{64} << 20;
constexpr std::uint32_t kByteOrderMark = 0x01020304;

[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& why) {
  throw ProtocolError(ErrorCode::bad_checkpoint, "checkpoint file '" + path.string() + "' " + why);
}
}  // namespace

void write_checkpoint_file(const std::filesystem::path& path, const CheckpointHeader& header, std::string_view state) {
  if (path.empty() || !path.has_filename()) refuse(path, "is not a file name; send a path such as DIR/dem.checkpoint");
  StateWriter out;
  out.value(kByteOrderMark);
  const nlohmann::json text = {{"solver", {{"name", header.solver_name}, {"version", header.solver_version}}},
                               {"scenario_hash", header.scenario_hash},
                               {"step", header.step}};
  out.string(text.dump());
  out.string(state);
  out.string(fnv1a64_hex(state));
  const std::string bytes = out.take();
  std::filesystem::path partial = path;
  partial += ".partial";
  {
    std::ofstream file(partial, std::ios::binary | std::ios::trunc);
    file.write(kMagic.data(), std::streamsize(kMagic.size()));
    for (std::size_t start = 0; start < bytes.size() && file; start += kChunkBytes) {
      file.write(bytes.data() + start, std::streamsize(std::min(kChunkBytes, bytes.size() - start)));
      work_progress::advance();
    }
    file.close();
    if (!file) refuse(path, "cannot be written (is its folder there and writable, is the disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(partial, path, ec);
  if (ec) refuse(path, "cannot be put in place: " + ec.message());
}

CheckpointFile read_checkpoint_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) refuse(path, "does not exist or is not a file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  std::string bytes(ec ? 0 : std::size_t(size), '\0');
  std::ifstream file(path, std::ios::binary);
  for (std::size_t start = 0; !ec && file && start < bytes.size(); start += kChunkBytes) {
    file.read(bytes.data() + start, std::streamsize(std::min(kChunkBytes, bytes.size() - start)));
    work_progress::advance();
  }
  if (ec || !file) refuse(path, "cannot be read");
  if (bytes.compare(0, kMagic.size(), kMagic) != 0) refuse(path, "is not a dfc checkpoint (it does not start with " + std::string(kMagic) + ")");
  CheckpointFile result;
  try {
    StateReader in(std::string_view(bytes).substr(kMagic.size()), "checkpoint file '" + path.string() + "'");
    if (in.value<std::uint32_t>() != kByteOrderMark) refuse(path, "was written on a machine of another byte order");
    const nlohmann::json header = nlohmann::json::parse(in.string());
    result.header.solver_name = header.at("solver").at("name").get<std::string>();
    result.header.solver_version = header.at("solver").at("version").get<std::string>();
    result.header.scenario_hash = header.at("scenario_hash").get<std::string>();
    result.header.step = header.at("step").get<std::int64_t>();
    result.state = in.string();
    if (in.string() != fnv1a64_hex(result.state)) refuse(path, "is damaged: its state does not match its checksum");
    in.finish();
  } catch (const StateFormatError& e) {
    throw ProtocolError(ErrorCode::bad_checkpoint, e.what());
  } catch (const nlohmann::json::exception& e) {
    refuse(path, std::string("has a damaged header: ") + e.what());
  }
  return result;
}

std::string checkpoint_mismatch(const CheckpointHeader& written, const CheckpointHeader& current) {
  if (written.solver_name != current.solver_name)
    return "it was written by " + written.solver_name + ", not by " + current.solver_name + "; restore it into the solver that wrote it";
  if (written.solver_version != current.solver_version)
    return "it was written by " + written.solver_name + " " + written.solver_version + " but this is version " + current.solver_version +
           "; a restart is exact only with the same build: resume with that version or start the run again";
  if (written.scenario_hash != current.scenario_hash)
    return "it was written for a section with hash " + written.scenario_hash + " but this session was configured with hash " +
           current.scenario_hash + ": the scenario section changed; resume with the section the run started with";
  return {};
}

}  // namespace dfc::protocol
