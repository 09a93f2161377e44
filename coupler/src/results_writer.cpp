#include "dfc/coupler/results_writer.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <exception>
#include <iostream>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "dfc/common/errors.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "dfc/common/json_text.hpp"
#include "dfc/coupler/xdmf_writer.hpp"

namespace dfc::coupler {

namespace {

// Rows are written in blocks of this many: one extend + write per column per
// block instead of per row, which matters when a run records every step.
constexpr std::size_t rows_per_block = 256;
// Chunk length of the time-series datasets (8 KiB of doubles): big enough for
// efficient I/O, small enough that a short run's file stays small.
constexpr hsize_t series_chunk_rows = 1024;
// Deflate level of the snapshot datasets (h5::Group::write_dataset chunks
// them) and of the time series (chunks of series_chunk_rows). Level 1: on the bonded pile and demo runs' snapshots it stores
// 54-55 % of the raw bytes, and levels 4 to 9 only 1-2 % less for up to
// five times the time (docs/looking_at_a_run.md §4); byte shuffling gained
// between -0.5 % and 3 %, not worth a second filter readers must have.
constexpr int snapshot_deflate_level = 1;

std::string utc_now_iso8601() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

hid_t native_type(protocol::DType dtype) {
  switch (dtype) {
    case protocol::DType::f64: return H5T_NATIVE_DOUBLE;
    case protocol::DType::f32: return H5T_NATIVE_FLOAT;
    case protocol::DType::i64: return H5T_NATIVE_INT64;
    case protocol::DType::i32: return H5T_NATIVE_INT32;
    case protocol::DType::u8: return H5T_NATIVE_UINT8;
  }
  throw std::invalid_argument("unknown array dtype");
}

std::size_t byte_size(protocol::DType dtype) {
  switch (dtype) {
    case protocol::DType::f64:
    case protocol::DType::i64: return 8;
    case protocol::DType::f32:
    case protocol::DType::i32: return 4;
    case protocol::DType::u8: return 1;
  }
  return 0;
}

// HDF5 link names: '/' separates path components and '.' alone means "this
// group", so neither can appear in a name we create from caller input.
void require_plain_name(const std::string& name, const std::string& what) {
  if (name.empty() || name == "." || name.find('/') != std::string::npos)
    throw std::invalid_argument(what + " '" + name + "' must be a non-empty name without '/'");
}

void validate_arrays(std::span<const protocol::Array> arrays) {
  std::set<std::string> names;
  for (const protocol::Array& array : arrays) {
    require_plain_name(array.name, "snapshot array name");
    if (!names.insert(array.name).second) throw std::invalid_argument("snapshot array '" + array.name + "' appears twice");
    std::size_t count = 1;
    for (const std::int64_t d : array.shape) {
      if (d < 0) throw std::invalid_argument("snapshot array '" + array.name + "' has a negative dimension");
      count *= static_cast<std::size_t>(d);
    }
    if (array.bytes.size() != count * byte_size(array.dtype))
      throw std::invalid_argument("snapshot array '" + array.name + "' holds " + std::to_string(array.bytes.size()) +
                                  " bytes but its dtype and shape need " + std::to_string(count * byte_size(array.dtype)));
  }
}

std::string six_digits(std::int64_t index) {
  char buffer[24];
  std::snprintf(buffer, sizeof buffer, "%06lld", static_cast<long long>(index));
  return buffer;
}

}  // namespace

struct ResultsWriter::State {
  State(std::filesystem::path p, h5::File f) : path(std::move(p)), file(std::move(f)) {}

  std::filesystem::path path;
  h5::File file;
  bool closed = false;

  // Time series.
  bool declared = false;
  std::vector<std::string> columns;
  std::vector<std::size_t> widths;  ///< numbers per row, per column
  std::size_t row_width = 0;        ///< sum of widths: the size of an appended row
  std::vector<h5::Dataset> column_datasets;
  std::vector<std::vector<double>> pending;  ///< per column, rows not yet written
  std::int64_t rows = 0;

  // Snapshots: per-role counter, and the catalogue the sidecar is written from
  // (kept in memory so the sidecar never has to read the file back).
  std::map<std::string, std::int64_t> snapshot_count;
  std::vector<XdmfSnapshot> catalogue;
  bool sidecar_stale = true;
  std::set<std::int64_t> polyvertex_counts;  ///< point counts whose Polyvertex connectivity is stored
  WallNames wall_names;

  // The sidecar's Polyvertex topologies read 0..n-1 from the file; one dataset
  // per distinct point count (usually one per run: particle counts rarely change).
  void ensure_polyvertex_connectivity(std::int64_t points) {
    if (!polyvertex_counts.insert(points).second) return;
    std::vector<std::int64_t> indices(static_cast<std::size_t>(points));
    for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<std::int64_t>(i);
    const std::string location = polyvertex_connectivity_path(points);  // "/<group>/<name>"
    const std::size_t slash = location.find_last_of('/');
    const h5::Group group = file.root().require_group(location.substr(1, slash - 1));
    const std::int64_t shape[] = {points};
    (void)group.write_dataset(location.substr(slash + 1), H5T_NATIVE_INT64, shape, std::as_bytes(std::span(indices)), snapshot_deflate_level);
  }

  void write_pending_rows() {
    if (pending.empty() || pending.front().empty()) return;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      column_datasets[c].append_f64(pending[c]);
      pending[c].clear();
    }
  }

  void write_sidecar(const std::filesystem::path& xdmf) {
    if (!sidecar_stale) return;
    write_xdmf(xdmf, path.filename().string(), catalogue, wall_names);
    sidecar_stale = false;
  }
};

ResultsWriter::ResultsWriter(std::filesystem::path path, const nlohmann::json& scenario, const nlohmann::json& versions) {
  if (path.extension() == ".xdmf")
    throw UserError("results file '" + path.string() + "' must not end in .xdmf: that name is taken by its XDMF sidecar; use .h5.");
  h5::File file = h5::File::create(path);
  state_ = std::make_unique<State>(std::move(path), std::move(file));
  const h5::Group root = state_->file.root();
  h5::write_attribute(root.id(), "scenario", readable_json(scenario));
  h5::write_attribute(root.id(), "versions", versions.dump(2));
  h5::write_attribute(root.id(), "created_utc", utc_now_iso8601());
  h5::write_attribute(root.id(), "format", format_name);
  (void)root.create_group("snapshots");
}

ResultsWriter::~ResultsWriter() {
  try {
    close();
  } catch (const std::exception& e) {
    // A destructor must not throw; the caller who cares calls close() and sees the error.
    std::cerr << "warning: results file " << (state_ ? state_->path.string() : std::string("?"))
              << " was not closed cleanly: " << e.what() << '\n';
  }
}

ResultsWriter::ResultsWriter(ResultsWriter&&) noexcept = default;

ResultsWriter& ResultsWriter::operator=(ResultsWriter&& other) noexcept {
  if (this != &other) {
    try {
      close();
    } catch (const std::exception& e) {
      std::cerr << "warning: results file " << state_->path.string() << " was not closed cleanly: " << e.what() << '\n';
    }
    state_ = std::move(other.state_);
  }
  return *this;
}

ResultsWriter::State& ResultsWriter::open_state(const char* operation) const {
  if (!state_) throw std::logic_error(std::string("ResultsWriter::") + operation + " called on a moved-from writer");
  if (state_->closed)
    throw std::logic_error(std::string("ResultsWriter::") + operation + " called after close() of " + state_->path.string());
  return *state_;
}

void ResultsWriter::declare_series(const std::vector<std::string>& columns, const std::map<std::string, std::string>& units) {
  const std::set<std::string> names(columns.begin(), columns.end());
  for (const auto& [column, unit] : units) {
    if (!names.contains(column)) throw std::invalid_argument("unit given for undeclared time-series column '" + column + "'");
  }
  std::vector<SeriesColumn> scalars;
  for (const std::string& column : columns) {
    const auto unit = units.find(column);
    scalars.push_back({column, unit == units.end() ? std::string() : unit->second});
  }
  declare_series(scalars);
}

void ResultsWriter::declare_series(const std::vector<SeriesColumn>& columns) {
  State& s = open_state("declare_series");
  if (s.declared) throw std::logic_error("ResultsWriter::declare_series called twice; the column set is fixed once per run");
  if (columns.empty()) throw std::invalid_argument("ResultsWriter::declare_series needs at least one column");
  std::set<std::string> seen;
  for (const SeriesColumn& column : columns) {
    require_plain_name(column.name, "time-series column");
    if (!seen.insert(column.name).second) throw std::invalid_argument("time-series column '" + column.name + "' is declared twice");
    if (column.width == 0) throw std::invalid_argument("time-series column '" + column.name + "' has width 0");
  }

  const h5::Group group = s.file.root().create_group("timeseries");
  std::vector<std::string> names;
  for (const SeriesColumn& column : columns) {
    h5::Dataset dataset = group.create_extendable_f64(column.name, series_chunk_rows, column.width, snapshot_deflate_level);
    if (!column.unit.empty()) h5::write_attribute(dataset.id(), "unit", column.unit);
    if (column.unit_guessed) h5::write_attribute(dataset.id(), "unit_source", std::string("guessed from the name"));
    s.column_datasets.push_back(std::move(dataset));
    names.push_back(column.name);
    s.widths.push_back(column.width);
    s.row_width += column.width;
  }
  // HDF5 lists members by name; the declared order is kept here for readers that want it.
  h5::write_attribute(group.id(), "columns", nlohmann::json(names).dump());
  s.columns = std::move(names);
  s.pending.assign(columns.size(), {});
  for (std::size_t c = 0; c < columns.size(); ++c) s.pending[c].reserve(rows_per_block * s.widths[c]);
  s.declared = true;
}

void ResultsWriter::append(const std::vector<double>& row) {
  State& s = open_state("append");
  if (!s.declared) throw std::logic_error("ResultsWriter::append called before declare_series");
  if (row.size() != s.row_width)
    throw std::invalid_argument("ResultsWriter::append: row has " + std::to_string(row.size()) + " values but the " +
                                std::to_string(s.columns.size()) + " declared columns take " + std::to_string(s.row_width));
  auto next = row.begin();
  for (std::size_t c = 0; c < s.columns.size(); ++c) {
    const auto end = next + static_cast<std::ptrdiff_t>(s.widths[c]);
    s.pending[c].insert(s.pending[c].end(), next, end);
    next = end;
  }
  ++s.rows;
  if (s.pending.front().size() >= rows_per_block * s.widths.front()) s.write_pending_rows();
}

std::int64_t ResultsWriter::row_count() const noexcept { return state_ ? state_->rows : 0; }

void ResultsWriter::write_snapshot(const std::string& role, std::int64_t step, double time, const std::string& kind,
                                   std::span<const protocol::Array> arrays) {
  State& s = open_state("write_snapshot");
  require_plain_name(role, "snapshot role");
  if (kind.empty()) throw std::invalid_argument("snapshot kind must not be empty");
  // Check everything before creating the group, so a bad array leaves no half snapshot behind.
  validate_arrays(arrays);

  const h5::Group snapshots = s.file.root().open_group("snapshots");
  const h5::Group role_group = snapshots.require_group(role);
  std::int64_t& index = s.snapshot_count[role];
  const std::string name = six_digits(index);
  const h5::Group group = role_group.create_group(name);
  h5::write_attribute(group.id(), "step", step);
  h5::write_attribute(group.id(), "time", time);
  h5::write_attribute(group.id(), "kind", kind);

  XdmfSnapshot entry{role, "/snapshots/" + role + "/" + name, step, time, kind, {}};
  for (const protocol::Array& array : arrays) {
    (void)group.write_dataset(array.name, native_type(array.dtype), array.shape, array.bytes, snapshot_deflate_level);
    entry.arrays.push_back({array.name, array.dtype, array.shape});
  }
  if (const std::optional<std::int64_t> points = polyvertex_point_count(entry)) s.ensure_polyvertex_connectivity(*points);
  if (const std::optional<std::int64_t> bonds = bond_point_count(entry)) s.ensure_polyvertex_connectivity(*bonds);
  ++index;
  s.catalogue.push_back(std::move(entry));
  s.sidecar_stale = true;
}

void ResultsWriter::name_walls(const std::string& role, const std::vector<std::string>& names) {
  State& s = open_state("name_walls");
  require_plain_name(role, "snapshot role");
  const h5::Group group = s.file.root().open_group("snapshots").require_group(role);
  h5::remove_attribute(group.id(), "wall_names");  // a resumed run names them again
  h5::write_attribute(group.id(), "wall_names", nlohmann::json(names).dump());
  s.wall_names[role] = names;
  s.sidecar_stale = true;
}

nlohmann::json ResultsWriter::resume_point() {
  flush();
  const State& s = *state_;
  nlohmann::json columns = nlohmann::json::array();
  for (std::size_t c = 0; c < s.columns.size(); ++c) columns.push_back({{"name", s.columns[c]}, {"width", s.widths[c]}});
  nlohmann::json catalogue = nlohmann::json::array();
  for (const XdmfSnapshot& entry : s.catalogue) {
    nlohmann::json arrays = nlohmann::json::array();
    for (const XdmfArrayInfo& a : entry.arrays) arrays.push_back({{"name", a.name}, {"dtype", protocol::dtype_name(a.dtype)}, {"shape", a.shape}});
    catalogue.push_back({{"role", entry.role}, {"group", entry.group_path}, {"step", entry.step}, {"time", entry.time}, {"kind", entry.kind},
                         {"arrays", arrays}});
  }
  return {{"rows", s.rows},
          {"declared", s.declared},
          {"columns", columns},
          {"snapshots", s.snapshot_count},
          {"catalogue", catalogue},
          {"polyvertex_counts", s.polyvertex_counts}};
}

ResultsWriter ResultsWriter::reopen(std::filesystem::path path, const nlohmann::json& resume_point) {
  ResultsWriter writer;
  h5::File file = h5::File::open_read_write(path);
  writer.state_ = std::make_unique<State>(std::move(path), std::move(file));
  State& s = *writer.state_;
  try {
    const h5::Group root = s.file.root();
    for (const char* attribute : {"summary", "failure", "interrupted"}) h5::remove_attribute(root.id(), attribute);
    s.rows = resume_point.at("rows").get<std::int64_t>();
    s.declared = resume_point.at("declared").get<bool>();
    if (s.declared) {
      const h5::Group series = root.open_group("timeseries");
      for (const auto& column : resume_point.at("columns")) {
        s.columns.push_back(column.at("name").get<std::string>());
        s.widths.push_back(column.at("width").get<std::size_t>());
        s.row_width += s.widths.back();
        s.column_datasets.push_back(series.open_dataset(s.columns.back()));
        s.column_datasets.back().truncate_rows(s.rows);  // rows after the checkpoint go
      }
      s.pending.assign(s.columns.size(), {});
    }
    s.snapshot_count = resume_point.at("snapshots").get<std::map<std::string, std::int64_t>>();
    const h5::Group snapshots = root.open_group("snapshots");
    for (const std::string& role : snapshots.members()) {
      const h5::Group group = snapshots.open_group(role);
      const auto kept = s.snapshot_count.find(role);
      for (const std::string& name : group.members())  // snapshots after the checkpoint go
        if (kept == s.snapshot_count.end() || std::stoll(name) >= kept->second) group.remove(name);
    }
    for (const auto& entry : resume_point.at("catalogue")) {
      XdmfSnapshot snapshot{entry.at("role").get<std::string>(), entry.at("group").get<std::string>(), entry.at("step").get<std::int64_t>(),
                            entry.at("time").get<double>(), entry.at("kind").get<std::string>(), {}};
      for (const auto& a : entry.at("arrays")) {
        const auto dtype = protocol::dtype_from_name(a.at("dtype").get<std::string>());
        if (!dtype) throw std::invalid_argument("unknown dtype " + a.at("dtype").dump());
        snapshot.arrays.push_back({a.at("name").get<std::string>(), *dtype, a.at("shape").get<std::vector<std::int64_t>>()});
      }
      s.catalogue.push_back(std::move(snapshot));
    }
    s.polyvertex_counts = resume_point.at("polyvertex_counts").get<std::set<std::int64_t>>();
    std::set<std::string> kept_connectivity;
    for (const std::int64_t points : s.polyvertex_counts) kept_connectivity.insert(polyvertex_connectivity_path(points));
    if (root.has("xdmf"))  // connectivity first stored after the checkpoint goes, so it can be written again
      for (const std::string& name : root.open_group("xdmf").members())
        if (!kept_connectivity.contains("/xdmf/" + name)) root.open_group("xdmf").remove(name);
    s.sidecar_stale = true;
    writer.flush();
  } catch (const UserError&) {
    throw;
  } catch (const std::exception& e) {
    throw UserError("cannot continue results file '" + s.path.string() + "' from its checkpoint: " + e.what() +
                    "; the file may have been damaged when the run was killed: start the run again, or resume into a copy of the file");
  }
  return writer;
}

void ResultsWriter::set_attribute(const std::string& name, const std::string& json_text) {
  State& s = open_state("set_attribute");
  if (name.empty()) throw std::invalid_argument("ResultsWriter::set_attribute needs a name");
  h5::write_attribute(s.file.root().id(), name, json_text);
}

void ResultsWriter::flush() {
  State& s = open_state("flush");
  s.write_pending_rows();
  s.file.flush();
  // Keeping the sidecar current means a run that dies later still opens in ParaView.
  s.write_sidecar(xdmf_path());
}

void ResultsWriter::close() {
  if (!state_ || state_->closed) return;
  State& s = *state_;
  s.closed = true;  // whatever fails below, the writer is finished; a second close() is a no-op
  std::exception_ptr first_error;
  const auto attempt = [&first_error](auto&& step) {
    try {
      step();
    } catch (...) {
      if (!first_error) first_error = std::current_exception();
    }
  };
  attempt([&] { s.write_pending_rows(); });
  attempt([&] { s.file.flush(); });
  attempt([&] { s.write_sidecar(xdmf_path()); });
  s.column_datasets.clear();  // datasets must be released before the file for H5Fclose to close it for real
  attempt([&] { s.file.close(); });
  if (first_error) std::rethrow_exception(first_error);
}

bool ResultsWriter::is_open() const noexcept { return state_ && !state_->closed; }

const std::filesystem::path& ResultsWriter::path() const noexcept {
  static const std::filesystem::path none;
  return state_ ? state_->path : none;
}

std::filesystem::path ResultsWriter::xdmf_path() const { return std::filesystem::path(path()).replace_extension(".xdmf"); }

}  // namespace dfc::coupler
