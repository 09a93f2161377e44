#include "dfc/protocol/progress_monitors.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "dfc/common/echo.hpp"

namespace dfc::protocol {

std::vector<ProgressMonitor> parse_progress_monitors(const nlohmann::json& info) {
  std::vector<ProgressMonitor> entries;
  if (!info.is_object() || !info.contains(progress_monitors_key)) return entries;
  const nlohmann::json& list = info[progress_monitors_key];
  const std::string where = std::string("info.") + progress_monitors_key;
  if (!list.is_array()) throw std::invalid_argument(where + " must be an array, got " + echoed(list.dump()));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& e = list[i];
    const std::string at = where + "[" + std::to_string(i) + "]";
    const auto text = [&](const char* key, bool non_empty) {
      if (!e.is_object() || !e.contains(key) || !e[key].is_string() || (non_empty && e[key].get<std::string>().empty()))
        throw std::invalid_argument(at + "." + key + " must be a" + (non_empty ? " non-empty" : "") + " string, got " +
                                    (e.is_object() && e.contains(key) ? echoed(e[key].dump()) : std::string("nothing")));
      return e[key].get<std::string>();
    };
    ProgressMonitor entry{text("monitor", true), text("label", false), 1.0, text("unit", false)};
    if (e.contains("scale")) {
      const nlohmann::json& scale = e["scale"];
      if (!scale.is_number() || !std::isfinite(scale.get<double>()) || scale.get<double>() == 0.0)
        throw std::invalid_argument(at + ".scale must be a finite non-zero number, got " + echoed(scale.dump()));
      entry.scale = scale.get<double>();
    }
    entries.push_back(std::move(entry));
  }
  return entries;
}

nlohmann::json to_json(const std::vector<ProgressMonitor>& entries) {
  nlohmann::json list = nlohmann::json::array();
  for (const ProgressMonitor& e : entries) list.push_back({{"monitor", e.monitor}, {"label", e.label}, {"scale", e.scale}, {"unit", e.unit}});
  return list;
}

std::string format_progress(const std::vector<ProgressMonitor>& entries, const nlohmann::json& monitors) {
  std::ostringstream out;
  out.precision(3);
  bool first = true;
  for (const ProgressMonitor& e : entries) {
    if (!monitors.is_object()) break;
    const auto value = monitors.find(e.monitor);
    if (value == monitors.end() || !value->is_number()) continue;
    out << (first ? "" : ", ") << e.label << (e.label.empty() ? "" : " ") << e.scale * value->get<double>() << (e.unit.empty() ? "" : " ")
        << e.unit;
    first = false;
  }
  return out.str();
}

}  // namespace dfc::protocol
