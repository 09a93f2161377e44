#include "dfc/coupler/run_recorder.hpp"

#include <limits>
#include <string_view>
#include <utility>

#include "dfc/protocol/monitor_units.hpp"

namespace dfc::coupler {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// For a server that declares no units: a guess from the monitor's name
/// suffix (SPEC.md §6.3 naming), stored marked as a guess.
std::string unit_guessed_from_name(const std::string& name) {
  const auto ends = [&](std::string_view suffix) { return name.ends_with(suffix); };
  if (ends("_n_s")) return protocol::unit::newton_second;
  if (ends("_s")) return protocol::unit::second;
  if (ends("_m")) return protocol::unit::metre;
  if (ends("_n")) return protocol::unit::newton;
  if (ends("_nm")) return protocol::unit::newton_metre;
  if (ends("_pa")) return protocol::unit::pascal;
  if (ends("_w")) return protocol::unit::watt;
  if (ends("_j")) return protocol::unit::joule;
  return protocol::unit::dimensionless;
}

}  // namespace

void RunRecorder::record(const std::map<std::string, double>& fixed, const std::map<std::string, nlohmann::json>& monitors_by_slot) {
  if (columns_.empty()) declare(fixed, monitors_by_slot);
  std::vector<double> row;
  for (const Source& column : columns_) {
    if (column.slot.empty()) {
      const auto it = fixed.find(column.key);
      row.push_back(it == fixed.end() ? kNaN : it->second);
      continue;
    }
    // A monitor missing from this reply, or of another shape than at the first row, is recorded as NaN.
    const auto slot = monitors_by_slot.find(column.slot);
    const nlohmann::json* value = slot == monitors_by_slot.end() || !slot->second.contains(column.key) ? nullptr : &slot->second[column.key];
    const bool fits = value != nullptr && protocol::monitor_width(*value) == column.width;
    if (column.width == 1) row.push_back(fits ? value->get<double>() : kNaN);
    else
      for (std::size_t i = 0; i < column.width; ++i) row.push_back(fits ? (*value)[i].get<double>() : kNaN);
  }
  writer_.append(row);
}

nlohmann::json RunRecorder::sources() const {
  nlohmann::json out = nlohmann::json::array();
  for (const Source& c : columns_) out.push_back({{"slot", c.slot}, {"key", c.key}, {"width", c.width}});
  return out;
}

void RunRecorder::resume(const nlohmann::json& sources) {
  for (const auto& c : sources) columns_.push_back({c.at("slot").get<std::string>(), c.at("key").get<std::string>(), c.at("width").get<std::size_t>()});
}

SeriesColumn RunRecorder::monitor_column(const std::string& slot, const std::string& name, std::size_t width) const {
  const auto declared = declared_units_.find(slot);
  if (declared != declared_units_.end() && declared->second.is_object() && declared->second.contains(name)) {
    const nlohmann::json& unit = declared->second.at(name);
    if (unit.is_string()) return {slot + "_" + name, unit.get<std::string>(), width};
  }
  return {slot + "_" + name, unit_guessed_from_name(name), width, true};
}

void RunRecorder::declare(const std::map<std::string, double>& fixed, const std::map<std::string, nlohmann::json>& monitors_by_slot) {
  // The coupler's own columns (coupled_run's `fixed`): their units are its own declaration.
  static const std::map<std::string, std::string> coupler_units = {
      {"exchange", protocol::unit::dimensionless},          {"step_dem", protocol::unit::dimensionless},
      {"step_continuum", protocol::unit::dimensionless},    {"time_s", protocol::unit::second},
      {"wall_time_s", protocol::unit::second},              {"interface_force_on_dem_x", protocol::unit::newton},
      {"interface_force_on_dem_y", protocol::unit::newton}, {"interface_force_on_dem_z", protocol::unit::newton},
      {"interface_force_on_continuum_x", protocol::unit::newton},
      {"interface_force_on_continuum_y", protocol::unit::newton},
      {"interface_force_on_continuum_z", protocol::unit::newton}};
  std::map<std::string, std::pair<Source, SeriesColumn>> by_name;  // columns in name order, as before units were declared
  for (const auto& [name, value] : fixed) {
    const auto unit = coupler_units.find(name);
    SeriesColumn column = unit != coupler_units.end() ? SeriesColumn{name, unit->second} : SeriesColumn{name, unit_guessed_from_name(name), 1, true};
    by_name.emplace(name, std::pair{Source{"", name, 1}, std::move(column)});
  }
  for (const auto& [slot, monitors] : monitors_by_slot)
    for (const auto& [name, value] : monitors.items())
      if (const std::size_t width = protocol::monitor_width(value); width > 0)
        by_name.emplace(slot + "_" + name, std::pair{Source{slot, name, width}, monitor_column(slot, name, width)});
  std::vector<SeriesColumn> columns;
  for (auto& [name, entry] : by_name) {
    columns_.push_back(std::move(entry.first));
    columns.push_back(std::move(entry.second));
  }
  writer_.declare_series(columns);
}

}  // namespace dfc::coupler
