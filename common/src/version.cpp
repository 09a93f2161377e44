#include "dfc/common/version.hpp"

#include <cstdint>
#include <cstdio>

#include "dfc/common/work_progress.hpp"

#ifndef DFC_PROJECT_VERSION
#error "DFC_PROJECT_VERSION must be defined by the build"
#endif

namespace dfc {

std::string_view project_version() noexcept { return DFC_PROJECT_VERSION; }

std::string fnv1a64_hex(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV offset basis
  // A checkpoint's state runs to gigabytes, hashed at about 1 GB/s: the
  // heartbeat's work counter moves per chunk (SPEC.md §9.1).
  constexpr std::size_t kChunk = std::size_t{16} << 20;
  for (std::size_t start = 0; start < bytes.size(); start += kChunk) {
    for (const char c : bytes.substr(start, kChunk)) {
      hash ^= static_cast<unsigned char>(c);
      hash *= 0x100000001b3ULL;  // FNV prime
    }
    work_progress::advance();
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace dfc
