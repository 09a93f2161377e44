#pragma once
// Where the end-to-end tests find the executables and scenario files
// (compile definitions from tests/e2e/CMakeLists.txt).
#include <filesystem>
#include <string>

namespace dfc::testing {
inline std::filesystem::path bin_dir() { return DFC_BIN_DIR; }
inline std::filesystem::path e2e_dir() { return DFC_E2E_DIR; }
inline std::filesystem::path source_dir() { return DFC_SOURCE_DIR; }
inline std::string coupler() { return (bin_dir() / "coupler").string(); }
}  // namespace dfc::testing
