#include "dfc/common/version.hpp"

#include <cstdint>
#include <cstdio>

#ifndef DFC_PROJECT_VERSION
#error "DFC_PROJECT_VERSION must be defined by the build"
#endif

namespace dfc {

std::string_view project_version() noexcept { return DFC_PROJECT_VERSION; }

std::string fnv1a64_hex(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV offset basis
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;  // FNV prime
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace dfc
