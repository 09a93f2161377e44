#pragma once
// RunRecorder: the run's time series — the coupler's own columns and every
// monitor of every slot, each labelled with the unit its source declares
// (SPEC.md §6.3). A monitor that is a number is a 1-D column; an [x, y, z]
// one an [N, 3] column. The columns are fixed by the first row; a monitor
// missing from a later reply, or of another shape, is recorded as NaN.
//
//   RunRecorder recorder(writer, {{"dem", dem_info["monitor_units"]}});
//   recorder.record({{"time_s", t}, ...}, {{"dem", dem_monitors}});
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/coupler/results_writer.hpp"

namespace dfc::coupler {

class RunRecorder {
 public:
  /// `declared_units`: per slot, configure's info.monitor_units (null for a
  /// server that declares none, e.g. one speaking protocol 1.1).
  RunRecorder(ResultsWriter& writer, std::map<std::string, nlohmann::json> declared_units)
      : writer_(writer), declared_units_(std::move(declared_units)) {}

  /// Appends one row: `fixed` the coupler's own values by column name, `monitors_by_slot` each slot's monitors.
  void record(const std::map<std::string, double>& fixed, const std::map<std::string, nlohmann::json>& monitors_by_slot);

  /// Where each column comes from, for a checkpoint (empty before the first row).
  [[nodiscard]] nlohmann::json sources() const;
  /// A resumed run: the columns the results file already declares.
  void resume(const nlohmann::json& sources);

 private:
  /// Where a column's values come from: `fixed[key]` when `slot` is empty, else the slot's monitor `key`.
  struct Source {
    std::string slot;
    std::string key;
    std::size_t width = 1;
  };

  /// The unit of `slot`'s monitor `name` as its server declared it, else a guess from the name.
  [[nodiscard]] SeriesColumn monitor_column(const std::string& slot, const std::string& name, std::size_t width) const;
  void declare(const std::map<std::string, double>& fixed, const std::map<std::string, nlohmann::json>& monitors_by_slot);

  ResultsWriter& writer_;
  std::map<std::string, nlohmann::json> declared_units_;
  std::vector<Source> columns_;
};

}  // namespace dfc::coupler
