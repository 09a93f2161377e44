#pragma once
// One column of a run's time series, and the path of a run's last snapshot,
// read back from its results file.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "dfc/common/hdf5_file.hpp"

namespace dfc::testing {
inline std::vector<double> series(const std::filesystem::path& results, const std::string& column) {
  return h5::read_f64(h5::File::open_read_only(results), "/timeseries/" + column);
}

/// "/snapshots/<role>/<last>" (snapshot groups sort by their zero-padded index).
inline std::string last_snapshot(const h5::File& file, const std::string& role) {
  auto names = h5::list_members(file, "/snapshots/" + role);
  std::sort(names.begin(), names.end());
  return "/snapshots/" + role + "/" + names.back();
}
}  // namespace dfc::testing
