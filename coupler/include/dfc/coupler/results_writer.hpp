#pragma once
// ResultsWriter: the one HDF5 file a run produces (docs/outputs.md), plus its XDMF
// sidecar for ParaView.
//
// Layout ("format" = "dfc-results-1"):
//   /                      attributes scenario, versions (JSON text), created_utc, format, and any set_attribute()
//   /timeseries/<column>   f64, extendable and chunked: 1-D for a number per row, [N, 3] for
//                          an [x, y, z] per row; attribute "unit", and "unit_source"
//                          ("guessed from the name") where the unit is not the solver's
//                          declaration; the group's attribute "columns" lists the column
//                          order as a JSON array
//   /snapshots/<role>/<NNNNNN>/<array>
//                          one group per snapshot (attributes step, time, kind), one dataset
//                          per array with the array's dtype and shape
//   /xdmf/polyvertex_<n>   0..n-1 (i64): connectivity the sidecar uses to show n particles as vertices
//
// Rows are buffered and written in blocks (one HDF5 extend per block, not per
// row); flush() writes them, updates the sidecar and flushes the file, after
// which other programs (h5::File::open_read_only, h5py, ParaView) can read it
// while the run goes on: the file is not locked, so they see the last flush.
// close() also writes the sidecar; the destructor closes without throwing.
//
//   ResultsWriter out("run.h5", scenario, versions);
//   out.declare_series({"time_s", "pile_force_n"}, {{"time_s", "s"}, {"pile_force_n", "N"}});
//   out.append({0.0, 12.5});
//   out.write_snapshot("dem", step, time, "particles", arrays);
//   out.set_attribute("summary", summary.dump());
//   out.close();
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/protocol/array.hpp"

namespace dfc::coupler {

/// One time-series column: `width` numbers per row (1: a scalar; 3: a vector).
struct SeriesColumn {
  std::string name;
  std::string unit;           ///< attribute "unit"; empty: none stored
  std::size_t width = 1;
  bool unit_guessed = false;  ///< the unit is a guess, not a declaration: marked so in the file
};

class ResultsWriter {
 public:
  /// Value of the root attribute "format".
  static constexpr const char* format_name = "dfc-results-1";

  /// Creates (truncates) `path` and writes the root attributes. Throws
  /// dfc::UserError naming the path when it cannot be created.
  ResultsWriter(std::filesystem::path path, const nlohmann::json& scenario, const nlohmann::json& versions);
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;
  ResultsWriter(ResultsWriter&&) noexcept;
  ResultsWriter& operator=(ResultsWriter&&) noexcept;

  /// Fixes the time-series columns (once). Names must be unique, non-empty and
  /// free of '/'; `units` may give a unit for any of them (stored as attribute "unit")
  /// and must not name unknown columns. Throws std::invalid_argument / std::logic_error.
  void declare_series(const std::vector<std::string>& columns, const std::map<std::string, std::string>& units);
  /// The same for columns of any width; a unit is stored where it is not empty.
  void declare_series(const std::vector<SeriesColumn>& columns);
  /// Appends one row: the values of every column in declared order, `width` of
  /// each; its size must equal the sum of the widths (std::invalid_argument otherwise).
  void append(const std::vector<double>& row);
  /// Number of rows appended so far (written or still buffered).
  [[nodiscard]] std::int64_t row_count() const noexcept;

  /// Stores `arrays` as /snapshots/<role>/<next 6-digit index>/ with attributes
  /// step, time and kind. Array names must be unique and free of '/', and each
  /// array's byte count must match its dtype and shape (std::invalid_argument).
  void write_snapshot(const std::string& role, std::int64_t step, double time, const std::string& kind,
                      std::span<const dfc::protocol::Array> arrays);

  /// The names of `role`'s walls in the order of wall_facet_wall's index:
  /// the attribute "wall_names" (JSON list) of /snapshots/<role> and the
  /// Information "wall_index" of the sidecar's <role>_walls collection.
  void name_walls(const std::string& role, const std::vector<std::string>& names);

  /// Root attribute `name` holding JSON text (e.g. "summary"); replaces an earlier value.
  void set_attribute(const std::string& name, const std::string& json_text);

  /// Where the file stands after a flush(): the rows, the columns and the
  /// snapshots, as JSON. A checkpoint stores it; reopen() continues from it.
  [[nodiscard]] nlohmann::json resume_point();
  /// Reopens `path`, which this class wrote, and continues it from
  /// `resume_point` (a resumed run, docs/checkpoints.md): rows and snapshots
  /// written after it are removed, and so are the root attributes summary,
  /// failure and interrupted of the process that stopped. Throws UserError
  /// naming the path when the file cannot be opened or does not hold them.
  [[nodiscard]] static ResultsWriter reopen(std::filesystem::path path, const nlohmann::json& resume_point);

  /// Writes buffered rows, brings the sidecar up to date and flushes the file to disk.
  void flush();
  /// flush(), write the XDMF sidecar, close the file. Idempotent; later writes throw std::logic_error.
  void close();
  [[nodiscard]] bool is_open() const noexcept;

  [[nodiscard]] const std::filesystem::path& path() const noexcept;
  /// `path` with its extension replaced by ".xdmf".
  [[nodiscard]] std::filesystem::path xdmf_path() const;

 private:
  ResultsWriter() = default;
  struct State;
  State& open_state(const char* operation) const;
  std::unique_ptr<State> state_;
};

}  // namespace dfc::coupler
