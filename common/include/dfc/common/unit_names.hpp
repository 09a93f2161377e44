#pragma once
// Unit strings of monitors and results (protocol/SPEC.md §6.3); one spelling
// each so that readers can compare them. Here, not in the protocol library,
// so that the solvers' libraries can declare their monitors' units without it.
namespace dfc::unit {
inline constexpr const char* dimensionless = "1";
inline constexpr const char* second = "s";
inline constexpr const char* metre = "m";
inline constexpr const char* newton = "N";
inline constexpr const char* newton_metre = "N m";
inline constexpr const char* newton_second = "N s";
inline constexpr const char* pascal = "Pa";
inline constexpr const char* joule = "J";
inline constexpr const char* watt = "W";
}  // namespace dfc::unit
