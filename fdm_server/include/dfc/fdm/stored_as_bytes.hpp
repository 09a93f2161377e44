#pragma once
// Eigen's fixed-size vectors are plain arrays of doubles without being
// trivially copyable: checkpoints (dfc/common/state_archive.hpp) store them as bytes.
#include <array>

#include "dfc/common/state_archive.hpp"
#include "dfc/fdm/types.hpp"

template <>
inline constexpr bool dfc::stored_as_bytes<dfc::fdm::Vec3> = true;
template <>
inline constexpr bool dfc::stored_as_bytes<std::array<dfc::fdm::Vec3, 4>> = true;

static_assert(sizeof(dfc::fdm::Vec3) == 3 * sizeof(double), "Vec3 is stored as three doubles");
