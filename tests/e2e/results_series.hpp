#pragma once
// One column of a run's time series, read back from its results file.
#include <filesystem>
#include <string>
#include <vector>

#include "dfc/common/hdf5_file.hpp"

namespace dfc::testing {
inline std::vector<double> series(const std::filesystem::path& results, const std::string& column) {
  return h5::read_f64(h5::File::open_read_only(results), "/timeseries/" + column);
}
}  // namespace dfc::testing
