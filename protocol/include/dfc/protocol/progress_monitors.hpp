#pragma once
// Progress monitors (SPEC.md §4.2, protocol 1.5): the few monitors a server
// wants shown on the coupler's progress line and in its final summary, and
// how, declared in configure's `info.progress_monitors`. The coupler then
// knows nothing of piles or platens: what a run reports while it runs is the
// server's to say.
//
//   info[protocol::progress_monitors_key] = to_json({{"pile_displacement_m", "pile", 1e3, "mm"},
//                                                   {"pile_force_n", "force", 1.0, "N"}});
//   ...
//   format_progress(parse_progress_monitors(info), monitors)  // "pile 3.02 mm, force 93.6 N"

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dfc::protocol {

/// The key of configure's `info` object that lists the progress monitors.
inline constexpr const char* progress_monitors_key = "progress_monitors";

/// One entry: show number monitor `monitor` as "label value·scale unit".
struct ProgressMonitor {
  std::string monitor;  ///< a number monitor of the server (§6.3)
  std::string label;    ///< a short word shown before the value
  double scale = 1.0;   ///< the SI value times this is shown (1e3: m shown in mm)
  std::string unit;     ///< the unit of the shown value, for people (e.g. "mm")
};

/// The entries of `info.progress_monitors` in order; none when absent. Throws
/// std::invalid_argument naming the entry when it is not an array of objects
/// {monitor: non-empty string, label: string, scale: finite non-zero number,
/// unit: string}.
[[nodiscard]] std::vector<ProgressMonitor> parse_progress_monitors(const nlohmann::json& info);

/// The JSON array `parse_progress_monitors` reads.
[[nodiscard]] nlohmann::json to_json(const std::vector<ProgressMonitor>& entries);

/// "label value unit, label value unit" for the entries `monitors` holds as
/// numbers (3 significant digits); an entry whose monitor is missing or null
/// is left out.
[[nodiscard]] std::string format_progress(const std::vector<ProgressMonitor>& entries, const nlohmann::json& monitors);

}  // namespace dfc::protocol
