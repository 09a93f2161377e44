#include "dfc/protocol/key_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "dfc/common/errors.hpp"
#include "dfc/common/json_text.hpp"
#include "dfc/common/unique_fd.hpp"

namespace dfc::protocol {

namespace {

// A key file is ~150 bytes; anything much larger is the wrong file.
constexpr std::size_t kLargestKeyFileBytes = 4096;
constexpr std::size_t kZ85KeyCharacters = 40;

std::string system_error(const std::filesystem::path& path, const std::string& what) {
  return "key file '" + path.string() + "': " + what + ": " + std::strerror(errno);
}

std::string mode_text(mode_t mode) {
  char text[8];
  std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode & 07777));
  return text;
}

std::string read_all(int fd, const std::filesystem::path& path) {
  std::string text;
  std::array<char, 1024> chunk{};
  while (true) {
    const ssize_t n = ::read(fd, chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw UserError(system_error(path, "cannot read it"));
    if (n == 0) return text;
    text.append(chunk.data(), static_cast<std::size_t>(n));
    if (text.size() > kLargestKeyFileBytes)
      throw UserError("key file '" + path.string() + "' has more than " + std::to_string(kLargestKeyFileBytes) +
                      " bytes: it is no key file; write one with 'coupler keys FILE'");
  }
}

/// The key `name` of `document`: 40 characters of Z85 that decode to 32 bytes.
std::string z85_key(const nlohmann::json& document, const char* name, const std::filesystem::path& path) {
  std::string key;
  if (const auto it = document.find(name); it != document.end() && it->is_string()) key = it->get<std::string>();
  std::array<std::uint8_t, 32> bytes{};
  if (key.size() != kZ85KeyCharacters || zmq_z85_decode(bytes.data(), key.c_str()) == nullptr)
    throw UserError("key file '" + path.string() + "' needs '" + name + "', 40 characters of Z85 text (a 32-byte CURVE key); write a new file with 'coupler keys FILE'");
  return key;
}

}  // namespace

void write_key_file(const std::filesystem::path& path, const authentication::CurveKeyPair& keys) {
  // Removed first, then created anew with O_EXCL: the mode 0600 is the file's
  // from its first byte, and a link planted at the path is not written through.
  if (::unlink(path.c_str()) != 0 && errno != ENOENT) throw UserError(system_error(path, "cannot replace it"));
  const UniqueFd fd(::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600));
  if (!fd.valid()) throw UserError(system_error(path, "cannot create it"));
  const nlohmann::json document = {{"dfc_key_file", kKeyFileFormat}, {"public_key", keys.public_key}, {"secret_key", keys.secret_key}};
  const std::string text = document.dump() + "\n";
  if (::write(fd.get(), text.data(), text.size()) != static_cast<ssize_t>(text.size())) throw UserError(system_error(path, "cannot write it"));
}

authentication::CurveKeyPair read_key_file(const std::filesystem::path& path) {
  const UniqueFd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (!fd.valid()) throw UserError(system_error(path, "cannot open it") + "; check the path (" + std::string(authentication::kKeyFileVariable) + ", or participants.<slot>.key_file of the scenario)");
  struct stat status {};
  if (::fstat(fd.get(), &status) != 0) throw UserError(system_error(path, "cannot look at it"));
  if (!S_ISREG(status.st_mode)) throw UserError("key file '" + path.string() + "' is not a regular file; give the path of a key file");
  // The permissions are what keeps the key secret (SPEC.md §2.1): a file of
  // another user's (which root could read) is that user's key, not ours.
  if (status.st_uid != ::geteuid())
    throw UserError("key file '" + path.string() + "' belongs to another user (uid " + std::to_string(status.st_uid) +
                    "), who may know the key; use a key file of your own ('coupler keys FILE')");
  if ((status.st_mode & 077) != 0)
    throw UserError("key file '" + path.string() + "' has mode " + mode_text(status.st_mode) +
                    ": others than its owner may access it, and whoever reads it can talk to the server; make it private with 'chmod 600 " +
                    path.string() + "'");
  nlohmann::json document;
  try {
    document = parse_json_text(read_all(fd.get(), path), JsonTextLimits{.reject_duplicate_keys = true});
  } catch (const std::exception& e) {
    throw UserError("key file '" + path.string() + "' is no JSON key file (" + e.what() + "); write one with 'coupler keys FILE'");
  }
  if (!document.is_object() || document.value("dfc_key_file", 0) != kKeyFileFormat)
    throw UserError("key file '" + path.string() + "' lacks \"dfc_key_file\": " + std::to_string(kKeyFileFormat) +
                    "; it is no dfc key file (write one with 'coupler keys FILE')");
  authentication::CurveKeyPair keys{z85_key(document, "public_key", path), z85_key(document, "secret_key", path)};
  std::array<char, kZ85KeyCharacters + 1> derived{};
  if (zmq_curve_public(derived.data(), keys.secret_key.c_str()) != 0 || keys.public_key != derived.data())
    throw UserError("key file '" + path.string() + "': public_key is not the public key of secret_key; the file is damaged: write a new one with 'coupler keys FILE'");
  return keys;
}

}  // namespace dfc::protocol
