#include "dfc/protocol/monitor_units.hpp"

#include <algorithm>

namespace dfc::protocol {

nlohmann::json shared_monitor_units() {
  return {{"unbalanced_force_ratio", unit::dimensionless},
          {"kinetic_energy_j", unit::joule},
          {"step", unit::dimensionless},
          {"interface_force_received", unit::newton},
          {"interface_force_reaction", unit::newton},
          {"interface_power_w", unit::watt}};
}

std::size_t monitor_width(const nlohmann::json& value) {
  if (value.is_number()) return 1;
  const bool vector3 = value.is_array() && value.size() == 3 && std::all_of(value.begin(), value.end(), [](const nlohmann::json& v) { return v.is_number(); });
  return vector3 ? 3 : 0;
}

std::vector<std::string> undeclared_monitors(const nlohmann::json& monitors, const nlohmann::json& declared) {
  std::vector<std::string> missing;
  if (!monitors.is_object()) return missing;
  for (const auto& [name, value] : monitors.items()) {
    const bool covered = declared.is_object() && declared.contains(name) && declared[name].is_string();
    if (!covered) missing.push_back(name);
  }
  return missing;
}

}  // namespace dfc::protocol
