#pragma once
// Version of the project (from CMake) shared by every executable.
#include <string>
#include <string_view>

namespace dfc {
[[nodiscard]] std::string_view project_version() noexcept;
/// FNV-1a 64-bit hash of `bytes` as 16 lowercase hex digits (SPEC.md §4.2: scenario hash).
[[nodiscard]] std::string fnv1a64_hex(std::string_view bytes);
}  // namespace dfc
