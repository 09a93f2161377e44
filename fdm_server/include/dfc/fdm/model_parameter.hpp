#pragma once
// A parameter a plug-in model declares next to its code (CONTRIBUTING.md §6), so that
// --help and error messages come from the same table.
#include <array>
#include <cstddef>
#include <string_view>

namespace dfc::fdm {

struct ModelParameter {
  std::string_view key;      ///< JSON key inside the material object
  std::string_view unit;     ///< SI unit, "-" for dimensionless
  std::string_view meaning;  ///< one sentence, with the admissible range and the default if optional
};

/// Joins two parameter tables at compile time (a plastic model's table = the
/// elastic parameters + its own).
template <std::size_t N, std::size_t M>
constexpr std::array<ModelParameter, N + M> join_parameters(const std::array<ModelParameter, N>& first,
                                                            const std::array<ModelParameter, M>& second) {
  std::array<ModelParameter, N + M> joined{};
  for (std::size_t i = 0; i < N; ++i) joined[i] = first[i];
  for (std::size_t i = 0; i < M; ++i) joined[N + i] = second[i];
  return joined;
}

}  // namespace dfc::fdm
