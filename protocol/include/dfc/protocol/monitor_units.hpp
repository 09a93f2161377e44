#pragma once
// Monitor units (SPEC.md §6.3, protocol 1.2): a server declares the SI unit of
// every monitor it sends in configure's `info.monitor_units`, so the coupler
// labels results from the source instead of guessing from a name's suffix.
//
//   nlohmann::json info = {{"dt_suggested", dt}, {"dt_max", dt}};
//   nlohmann::json units = protocol::shared_monitor_units();
//   units["pile_force_n"] = protocol::unit::newton;
//   info[protocol::monitor_units_key] = units;

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/common/unit_names.hpp"

namespace dfc::protocol {

/// The key of configure's `info` object that holds {monitor name: unit}.
inline constexpr const char* monitor_units_key = "monitor_units";

/// Unit strings SPEC.md §6.3 uses (dfc/common/unit_names.hpp).
namespace unit = dfc::unit;

/// Numbers a monitor value holds: 1 for a number, 3 for [x, y, z] (SPEC.md
/// §6.3), 0 for anything else (not a valid monitor value).
[[nodiscard]] std::size_t monitor_width(const nlohmann::json& value);

/// Units of the monitors SPEC.md §6.3 defines for every server (unbalanced
/// force ratio, kinetic energy, step count, interface force and power); a
/// server adds its own monitors to this object. Declaring a monitor that is
/// not sent (e.g. interface monitors of an uncoupled session) is allowed.
[[nodiscard]] nlohmann::json shared_monitor_units();

/// Names in `monitors` (a monitors object) that `declared` (an
/// info.monitor_units object, or null when the server declared none) gives no
/// unit string; empty when the declaration covers every monitor.
[[nodiscard]] std::vector<std::string> undeclared_monitors(const nlohmann::json& monitors, const nlohmann::json& declared);

}  // namespace dfc::protocol
