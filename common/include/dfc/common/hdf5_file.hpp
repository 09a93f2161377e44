#pragma once
// RAII wrappers over the HDF5 C API, and read-back helpers for tests and tools.
//
// Every HDF5 identifier is owned by exactly one h5::Handle, which closes it
// with the matching H5*close call; nothing here hands out an identifier that
// the caller must close. Failures throw: h5::Error (a library call failed)
// or dfc::UserError (a path that cannot be created or opened, named in the
// message). The HDF5 error stack is never printed; its innermost message is
// put into the exception instead.
//
//   auto file = h5::File::create("run.h5");
//   h5::Group ts = file.root().create_group("timeseries");
//   h5::Dataset col = ts.create_extendable_f64("time_s", 1024);
//   col.append_f64(values);
//   h5::write_attribute(col.id(), "unit", "s");
//   file.flush();
//
//   auto in = h5::File::open_read_only("run.h5");   // works while a writer holds it (after flush)
//   std::vector<double> t = h5::read_f64(in, "/timeseries/time_s");
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <hdf5.h>

namespace dfc::h5 {

/// An HDF5 library call failed for a reason other than the user's path.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Owns one HDF5 identifier. Move-only; closes on destruction (errors ignored
/// there, because destructors must not throw) or on close() (errors thrown).
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);

  Handle() noexcept = default;
  /// Takes ownership of `id` (which must be valid, > 0); `closer` is e.g. H5Dclose.
  Handle(hid_t id, Closer closer) noexcept : id_(id), closer_(closer) {}
  ~Handle();
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept;
  Handle& operator=(Handle&& other) noexcept;

  [[nodiscard]] hid_t get() const noexcept { return id_; }
  [[nodiscard]] bool valid() const noexcept { return id_ > 0; }
  /// Closes now; throws Error if HDF5 reports a failure. No-op when not valid.
  void close();

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

/// A dataset, with the operations the results writer and its readers need.
class Dataset {
 public:
  explicit Dataset(Handle handle) noexcept : handle_(std::move(handle)) {}
  [[nodiscard]] hid_t id() const noexcept { return handle_.get(); }

  /// Current extent, one entry per dimension (empty for a scalar dataset).
  [[nodiscard]] std::vector<std::int64_t> shape() const;
  /// "f64", "f32", "i64", "i32", "u8" for those native types, else "other".
  [[nodiscard]] std::string element_type_name() const;

  /// Grows an extendable dataset by whole rows and writes `values` (row after
  /// row) at the end: values.size() rows of a 1-D dataset, values.size() / width
  /// rows of an [N, width] one (a size that is not a whole number of rows throws).
  void append_f64(std::span<const double> values);
  /// Shrinks an extendable dataset to its first `rows` rows (a resumed run
  /// drops the rows written after its checkpoint). More rows than it has throws.
  void truncate_rows(std::int64_t rows);

  /// All values converted to double / int64 (HDF5 converts numeric types).
  [[nodiscard]] std::vector<double> read_f64() const;
  [[nodiscard]] std::vector<std::int64_t> read_i64() const;
  /// All values in the in-memory type `native_type` (e.g. H5T_NATIVE_INT32), as raw bytes.
  [[nodiscard]] std::vector<std::byte> read_raw(hid_t native_type) const;

 private:
  Handle handle_;
};

/// A group (the root group of a file is one too).
class Group {
 public:
  explicit Group(Handle handle) noexcept : handle_(std::move(handle)) {}
  [[nodiscard]] hid_t id() const noexcept { return handle_.get(); }

  [[nodiscard]] Group create_group(const std::string& name) const;
  [[nodiscard]] Group open_group(const std::string& path) const;
  /// The group `name`, created if it does not exist yet.
  [[nodiscard]] Group require_group(const std::string& name) const;
  /// Whether a link exists at `path` (relative to this group, or absolute),
  /// checking each intermediate component so that a missing parent is "false", not an error.
  [[nodiscard]] bool has(const std::string& path) const;
  /// Names of the direct members, in ascending name order.
  [[nodiscard]] std::vector<std::string> members() const;

  /// An initially empty f64 dataset of unlimited rows, chunked by `chunk_rows`
  /// (chunking is what lets it grow; the chunk size trades memory for I/O calls):
  /// 1-D for `width` 1, else [N, width] (e.g. 3 for a vector per row).
  /// `deflate_level` > 0 compresses each chunk with deflate (zlib) at that level.
  [[nodiscard]] Dataset create_extendable_f64(const std::string& name, hsize_t chunk_rows, hsize_t width = 1, int deflate_level = 0) const;
  /// A fixed-size dataset of `native_type` with `shape` (empty: scalar) holding `bytes`,
  /// whose size must be shape product × type size. `deflate_level` 0 stores it
  /// as given (contiguous); 1 to 9 stores it in chunks of whole rows (at most
  /// about 1 MiB each) compressed with deflate (zlib) at that level, which
  /// every HDF5 reader (h5py, ParaView) undoes unasked. A scalar or an empty
  /// dataset is stored as given whatever the level (a chunk needs an extent).
  Dataset write_dataset(const std::string& name, hid_t native_type, std::span<const std::int64_t> shape, std::span<const std::byte> bytes,
                        int deflate_level = 0) const;
  [[nodiscard]] Dataset open_dataset(const std::string& path) const;
  /// Unlinks the member `name` (a group with all it holds, or a dataset).
  void remove(const std::string& name) const;

 private:
  Handle handle_;
};

/// One open HDF5 file.
class File {
 public:
  /// Creates `path`, truncating an existing file. The file is not locked, so
  /// other programs can read it while it is written (what they see is what was
  /// last flushed); keeping two writers off one path is the caller's job.
  /// Throws UserError naming the path when it cannot be created (missing
  /// directory, no permission, held open by this process).
  [[nodiscard]] static File create(const std::filesystem::path& path);
  /// Opens `path` read-only without taking the file lock, so that a file still
  /// being written, by this or another process, can be read (what was flushed is what is seen).
  /// Throws UserError naming the path when it is missing or not an HDF5 file.
  [[nodiscard]] static File open_read_only(const std::filesystem::path& path);
  /// Opens an existing `path` for writing, unlocked like create() (a resumed
  /// run appends to its results). Throws UserError naming the path when it is
  /// missing or not a readable HDF5 file.
  [[nodiscard]] static File open_read_write(const std::filesystem::path& path);

  [[nodiscard]] hid_t id() const noexcept { return handle_.get(); }
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }
  [[nodiscard]] bool is_open() const noexcept { return handle_.valid(); }
  [[nodiscard]] Group root() const;
  /// Writes every buffer of the file to disk (H5Fflush, local scope).
  void flush();
  /// Closes the file; throws Error if HDF5 could not finish writing it.
  void close();

 private:
  File(Handle handle, std::filesystem::path path) noexcept : handle_(std::move(handle)), path_(std::move(path)) {}
  Handle handle_;
  std::filesystem::path path_;
};

// Attributes on any object (file, group or dataset identifier). Writing
// replaces an attribute of the same name. Strings are stored as scalar,
// variable-length UTF-8 so that h5py reads them back as `str`.
void write_attribute(hid_t object, const std::string& name, std::string_view value);
void write_attribute(hid_t object, const std::string& name, const char* value);
void write_attribute(hid_t object, const std::string& name, std::int64_t value);
void write_attribute(hid_t object, const std::string& name, double value);
[[nodiscard]] bool has_attribute(hid_t object, const std::string& name);
/// Deletes attribute `name` of `object` if it has one.
void remove_attribute(hid_t object, const std::string& name);
/// Reads a string attribute (variable- or fixed-length); throws Error if absent or not a string.
[[nodiscard]] std::string read_string_attribute(hid_t object, const std::string& name);
[[nodiscard]] std::int64_t read_int64_attribute(hid_t object, const std::string& name);
[[nodiscard]] double read_double_attribute(hid_t object, const std::string& name);

// Read-back helpers by absolute path ("/timeseries/time_s"), for tests and tools.
[[nodiscard]] std::vector<double> read_f64(const File& file, const std::string& dataset_path);
[[nodiscard]] std::vector<std::int64_t> read_i64(const File& file, const std::string& dataset_path);
[[nodiscard]] std::vector<std::int64_t> dataset_shape(const File& file, const std::string& dataset_path);
/// `object_path` "/" is the root group; otherwise a group or dataset.
[[nodiscard]] std::string read_string_attribute(const File& file, const std::string& object_path, const std::string& name);
[[nodiscard]] std::vector<std::string> list_members(const File& file, const std::string& group_path);
[[nodiscard]] bool exists(const File& file, const std::string& path);

}  // namespace dfc::h5
