#include "dfc/common/hdf5_file.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <utility>

#include "dfc/common/errors.hpp"

namespace dfc::h5 {

namespace {

// HDF5 prints its error stack to stderr by default; we report through
// exceptions instead, so the automatic printing is switched off once, before
// the first call that can fail.
void silence_error_printing() {
  static const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

// The innermost description on the current HDF5 error stack (the most
// specific reason, e.g. "... errno = 13, error message = 'Permission denied'"),
// then clears the stack so the next failure starts fresh.
std::string take_error_detail() {
  std::string detail;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* err, void* out) -> herr_t {
        if (n == 0 && err != nullptr && err->desc != nullptr) static_cast<std::string*>(out)->assign(err->desc);
        return 0;
      },
      &detail);
  H5Eclear2(H5E_DEFAULT);
  return detail;
}

[[noreturn]] void fail(const std::string& what) {
  const std::string detail = take_error_detail();
  throw Error(detail.empty() ? what : what + " (HDF5: " + detail + ")");
}

hid_t check(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void check(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

Handle make_handle(hid_t id, Handle::Closer closer, const std::string& what) {
  return Handle(check(id, what), closer);
}

std::string object_name(hid_t object) {
  const ssize_t length = H5Iget_name(object, nullptr, 0);
  if (length <= 0) return "?";
  std::string name(static_cast<std::size_t>(length) + 1, '\0');
  H5Iget_name(object, name.data(), name.size());
  name.resize(static_cast<std::size_t>(length));
  return name;
}

Handle dataspace_of(hid_t dataset) { return make_handle(H5Dget_space(dataset), H5Sclose, "cannot read the dataspace of dataset " + object_name(dataset)); }

std::vector<hsize_t> extent_of(hid_t space) {
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) fail("cannot read the rank of a dataspace");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) check(H5Sget_simple_extent_dims(space, dims.data(), nullptr), "cannot read the extent of a dataspace");
  return dims;
}

std::size_t element_count(hid_t dataset) {
  const Handle space = dataspace_of(dataset);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) fail("cannot count the elements of dataset " + object_name(dataset));
  return static_cast<std::size_t>(n);
}

template <class T>
std::vector<T> read_all(hid_t dataset, hid_t native_type) {
  std::vector<T> values(element_count(dataset));
  if (!values.empty())
    check(H5Dread(dataset, native_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "cannot read dataset " + object_name(dataset));
  return values;
}

// A file-access property list that does not take the POSIX file lock. HDF5
// 1.10 locks by default, which would stop anyone (h5py, ParaView, our own
// readers) from opening a results file while the run that writes it goes on;
// and HDF5 refuses to open a file twice in one process with different locking
// settings, so writer and reader both go without.
Handle unlocked_fapl() {
  Handle fapl = make_handle(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create a file-access property list");
#if (H5_VERSION_GE(1, 10, 7) && !H5_VERSION_GE(1, 12, 0)) || H5_VERSION_GE(1, 12, 1)
  check(H5Pset_file_locking(fapl.get(), false, true), "cannot disable HDF5 file locking");
#endif
  return fapl;
}

Handle utf8_string_type() {
  Handle type = make_handle(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create a string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), "cannot make a variable-length string type");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "cannot set UTF-8 on a string type");
  return type;
}

Handle open_attribute(hid_t object, const std::string& name) {
  return make_handle(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose,
                     "cannot open attribute '" + name + "' of " + object_name(object));
}

// Creates attribute `name` (replacing one of the same name) as a scalar of `file_type`.
Handle create_scalar_attribute(hid_t object, const std::string& name, hid_t file_type) {
  silence_error_printing();
  const htri_t present = H5Aexists(object, name.c_str());
  if (present < 0) fail("cannot query attribute '" + name + "' of " + object_name(object));
  if (present > 0) check(H5Adelete(object, name.c_str()), "cannot replace attribute '" + name + "' of " + object_name(object));
  const Handle space = make_handle(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a scalar dataspace");
  return make_handle(H5Acreate2(object, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                     "cannot create attribute '" + name + "' on " + object_name(object));
}

template <class T>
void write_numeric_attribute(hid_t object, const std::string& name, hid_t native_type, T value) {
  const Handle attribute = create_scalar_attribute(object, name, native_type);
  check(H5Awrite(attribute.get(), native_type, &value), "cannot write attribute '" + name + "' of " + object_name(object));
}

template <class T>
T read_numeric_attribute(hid_t object, const std::string& name, hid_t native_type) {
  silence_error_printing();
  const Handle attribute = open_attribute(object, name);
  T value{};
  check(H5Aread(attribute.get(), native_type, &value), "cannot read attribute '" + name + "' of " + object_name(object));
  return value;
}

Handle open_object(const File& file, const std::string& path) {
  silence_error_printing();
  return make_handle(H5Oopen(file.id(), path.c_str(), H5P_DEFAULT), H5Oclose,
                     "cannot open '" + path + "' in " + file.path().string());
}

}  // namespace

// Handle ----------------------------------------------------------------------

Handle::~Handle() {
  if (valid() && closer_ != nullptr) closer_(id_);
}

Handle::Handle(Handle&& other) noexcept
    : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(std::exchange(other.closer_, nullptr)) {}

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    if (valid() && closer_ != nullptr) closer_(id_);
    id_ = std::exchange(other.id_, H5I_INVALID_HID);
    closer_ = std::exchange(other.closer_, nullptr);
  }
  return *this;
}

void Handle::close() {
  if (!valid()) return;
  const hid_t id = std::exchange(id_, H5I_INVALID_HID);
  const Closer closer = std::exchange(closer_, nullptr);
  if (closer != nullptr) check(closer(id), "cannot close an HDF5 object");
}

// Dataset ---------------------------------------------------------------------

std::vector<std::int64_t> Dataset::shape() const {
  const Handle space = dataspace_of(id());
  std::vector<std::int64_t> out;
  for (const hsize_t d : extent_of(space.get())) out.push_back(static_cast<std::int64_t>(d));
  return out;
}

std::string Dataset::element_type_name() const {
  const Handle type = make_handle(H5Dget_type(id()), H5Tclose, "cannot read the type of dataset " + object_name(id()));
  const std::pair<hid_t, const char*> known[] = {{H5T_NATIVE_DOUBLE, "f64"}, {H5T_NATIVE_FLOAT, "f32"}, {H5T_NATIVE_INT64, "i64"},
                                                 {H5T_NATIVE_INT32, "i32"},  {H5T_NATIVE_UINT8, "u8"}};
  for (const auto& [native, name] : known) {
    if (H5Tequal(type.get(), native) > 0) return name;
  }
  return "other";
}

void Dataset::append_f64(std::span<const double> values) {
  if (values.empty()) return;
  const Handle old_space = dataspace_of(id());
  const int rank = H5Sget_simple_extent_ndims(old_space.get());
  if (rank != 1 && rank != 2) throw Error("append_f64: dataset " + object_name(id()) + " is neither 1-D nor 2-D");
  // Fixed-size [rows, width] (width 1 and unused for a 1-D dataset).
  std::array<hsize_t, 2> extent{0, 1};
  check(H5Sget_simple_extent_dims(old_space.get(), extent.data(), nullptr), "cannot read the extent of dataset " + object_name(id()));
  const hsize_t width = extent[1];
  if (width == 0 || values.size() % width != 0)
    throw Error("append_f64: " + std::to_string(values.size()) + " values are not whole rows of " + std::to_string(width) + " for dataset " +
                object_name(id()));
  // The appended block: rows [old rows, old rows + count) and, for a 2-D dataset, every column.
  const std::array<hsize_t, 2> start{extent[0], 0};
  const std::array<hsize_t, 2> count{values.size() / width, width};
  extent[0] += count[0];
  check(H5Dset_extent(id(), extent.data()), "cannot extend dataset " + object_name(id()));
  const Handle file_space = dataspace_of(id());
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr), "cannot select the appended rows");
  const Handle memory_space = make_handle(H5Screate_simple(rank, count.data(), nullptr), H5Sclose, "cannot create a memory dataspace");
  check(H5Dwrite(id(), H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT, values.data()),
        "cannot append to dataset " + object_name(id()));
}

void Dataset::truncate_rows(std::int64_t rows) {
  const Handle space = dataspace_of(id());
  std::vector<hsize_t> extent = extent_of(space.get());
  if (extent.empty() || rows < 0 || hsize_t(rows) > extent[0])
    throw Error("truncate_rows: dataset " + object_name(id()) + " has fewer than " + std::to_string(rows) + " rows");
  extent[0] = hsize_t(rows);
  check(H5Dset_extent(id(), extent.data()), "cannot shrink dataset " + object_name(id()));
}

std::vector<double> Dataset::read_f64() const { return read_all<double>(id(), H5T_NATIVE_DOUBLE); }
std::vector<std::int64_t> Dataset::read_i64() const { return read_all<std::int64_t>(id(), H5T_NATIVE_INT64); }

std::vector<std::byte> Dataset::read_raw(hid_t native_type) const {
  const std::size_t size = H5Tget_size(native_type);
  if (size == 0) fail("read_raw: invalid memory type");
  std::vector<std::byte> bytes(element_count(id()) * size);
  if (!bytes.empty())
    check(H5Dread(id(), native_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), "cannot read dataset " + object_name(id()));
  return bytes;
}

// Group -----------------------------------------------------------------------

Group Group::create_group(const std::string& name) const {
  silence_error_printing();
  return Group(make_handle(H5Gcreate2(id(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                           "cannot create group '" + name + "' in " + object_name(id())));
}

Group Group::open_group(const std::string& path) const {
  silence_error_printing();
  return Group(make_handle(H5Gopen2(id(), path.c_str(), H5P_DEFAULT), H5Gclose, "cannot open group '" + path + "' in " + object_name(id())));
}

Group Group::require_group(const std::string& name) const { return has(name) ? open_group(name) : create_group(name); }

bool Group::has(const std::string& path) const {
  silence_error_printing();
  // H5Lexists fails (rather than answering false) when an intermediate
  // component is missing, so walk the path one component at a time.
  std::string prefix = path.starts_with('/') ? "/" : "";
  std::size_t begin = prefix.size();
  while (begin < path.size()) {
    std::size_t end = path.find('/', begin);
    if (end == std::string::npos) end = path.size();
    if (end > begin) {
      prefix += path.substr(begin, end - begin);
      const htri_t present = H5Lexists(id(), prefix.c_str(), H5P_DEFAULT);
      if (present < 0) fail("cannot look up '" + prefix + "' in " + object_name(id()));
      if (present == 0) return false;
      prefix += '/';
    }
    begin = end + 1;
  }
  return true;
}

std::vector<std::string> Group::members() const {
  silence_error_printing();
  std::vector<std::string> names;
  hsize_t index = 0;
  const herr_t status = H5Literate(
      id(), H5_INDEX_NAME, H5_ITER_INC, &index,
      [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
        try {
          static_cast<std::vector<std::string>*>(out)->emplace_back(name);
          return 0;
        } catch (...) {
          return -1;  // an exception must not cross the C library; stop the iteration instead
        }
      },
      &names);
  check(status, "cannot list the members of " + object_name(id()));
  return names;
}

Dataset Group::create_extendable_f64(const std::string& name, hsize_t chunk_rows, hsize_t width, int deflate_level) const {
  silence_error_printing();
  if (width == 0) throw Error("dataset '" + name + "' needs a width of at least 1");
  if (deflate_level < 0 || deflate_level > 9) throw Error("dataset '" + name + "': deflate level " + std::to_string(deflate_level) + " is not in 0..9");
  // A width-1 series stays 1-D: existing readers index it as a plain vector.
  const int rank = width == 1 ? 1 : 2;
  const hsize_t initial[] = {0, width};
  const hsize_t maximum[] = {H5S_UNLIMITED, width};
  const hsize_t chunk[] = {std::max<hsize_t>(chunk_rows, 1), width};
  const Handle space = make_handle(H5Screate_simple(rank, initial, maximum), H5Sclose, "cannot create an extendable dataspace");
  const Handle dcpl = make_handle(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "cannot create a dataset-creation property list");
  check(H5Pset_chunk(dcpl.get(), rank, chunk), "cannot set the chunk size of dataset '" + name + "'");
  if (deflate_level > 0)
    check(H5Pset_deflate(dcpl.get(), static_cast<unsigned>(deflate_level)), "cannot set the compression of dataset '" + name + "'");
  return Dataset(make_handle(H5Dcreate2(id(), name.c_str(), H5T_NATIVE_DOUBLE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                             H5Dclose, "cannot create dataset '" + name + "' in " + object_name(id())));
}

Dataset Group::write_dataset(const std::string& name, hid_t native_type, std::span<const std::int64_t> shape, std::span<const std::byte> bytes,
                             int deflate_level) const {
  silence_error_printing();
  std::vector<hsize_t> dims;
  std::size_t count = 1;
  for (const std::int64_t d : shape) {
    if (d < 0) throw Error("dataset '" + name + "' has a negative dimension");
    dims.push_back(static_cast<hsize_t>(d));
    count *= static_cast<std::size_t>(d);
  }
  const std::size_t type_size = H5Tget_size(native_type);
  if (type_size == 0) fail("dataset '" + name + "': invalid memory type");
  if (bytes.size() != count * type_size)
    throw Error("dataset '" + name + "' has " + std::to_string(bytes.size()) + " bytes of data but its shape and type need " +
                std::to_string(count * type_size));
  const Handle space = dims.empty() ? make_handle(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a scalar dataspace")
                                    : make_handle(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
                                                  "cannot create the dataspace of dataset '" + name + "'");
  if (deflate_level < 0 || deflate_level > 9) throw Error("dataset '" + name + "': deflate level " + std::to_string(deflate_level) + " is not in 0..9");
  const Handle dcpl = make_handle(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "cannot create a dataset-creation property list");
  if (deflate_level > 0 && !dims.empty() && count > 0) {
    // Chunks of whole rows, at most about 1 MiB: HDF5's default chunk cache
    // (1 MiB per dataset) holds one, and larger chunks deflate no better.
    constexpr std::size_t chunk_bytes = std::size_t{1} << 20;
    std::vector<hsize_t> chunk = dims;
    const std::size_t row_bytes = count / static_cast<std::size_t>(dims[0]) * type_size;
    chunk[0] = std::clamp<hsize_t>(chunk_bytes / row_bytes, 1, dims[0]);
    check(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), "cannot set the chunks of dataset '" + name + "'");
    check(H5Pset_deflate(dcpl.get(), static_cast<unsigned>(deflate_level)), "cannot set the compression of dataset '" + name + "'");
  }
  Dataset dataset(make_handle(H5Dcreate2(id(), name.c_str(), native_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), H5Dclose,
                              "cannot create dataset '" + name + "' in " + object_name(id())));
  if (count > 0)
    check(H5Dwrite(dataset.id(), native_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()),
          "cannot write dataset '" + name + "' in " + object_name(id()));
  return dataset;
}

Dataset Group::open_dataset(const std::string& path) const {
  silence_error_printing();
  return Dataset(make_handle(H5Dopen2(id(), path.c_str(), H5P_DEFAULT), H5Dclose, "cannot open dataset '" + path + "' in " + object_name(id())));
}

// File ------------------------------------------------------------------------

File File::create(const std::filesystem::path& path) {
  silence_error_printing();
  const std::filesystem::path parent = path.parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
    throw UserError("cannot create results file '" + path.string() + "': directory '" + parent.string() +
                    "' does not exist; create it or choose another output path.");
  const Handle fapl = unlocked_fapl();
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (id < 0) {
    const std::string detail = take_error_detail();
    throw UserError("cannot create HDF5 file '" + path.string() + "'" + (detail.empty() ? "" : " (" + detail + ")") +
                    "; check that the directory is writable and that no other program holds the file open.");
  }
  return File(Handle(id, H5Fclose), path);
}

void Group::remove(const std::string& name) const {
  silence_error_printing();
  check(H5Ldelete(id(), name.c_str(), H5P_DEFAULT), "cannot remove '" + name + "' from " + object_name(id()));
}

File File::open_read_write(const std::filesystem::path& path) {
  silence_error_printing();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw UserError("cannot open HDF5 file '" + path.string() + "' for writing: no such file; check the path.");
  const Handle fapl = unlocked_fapl();
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.get());
  if (id < 0) {
    const std::string detail = take_error_detail();
    throw UserError("cannot open HDF5 file '" + path.string() + "' for writing" + (detail.empty() ? "" : " (" + detail + ")") +
                    "; is it an HDF5 file, and is it not open in another program?");
  }
  return File(Handle(id, H5Fclose), path);
}

File File::open_read_only(const std::filesystem::path& path) {
  silence_error_printing();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw UserError("cannot open HDF5 file '" + path.string() + "': no such file; check the path.");
  const Handle fapl = unlocked_fapl();
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get());
  if (id < 0) {
    const std::string detail = take_error_detail();
    throw UserError("cannot open HDF5 file '" + path.string() + "'" + (detail.empty() ? "" : " (" + detail + ")") +
                    "; is it an HDF5 file, and was it flushed by its writer?");
  }
  return File(Handle(id, H5Fclose), path);
}

Group File::root() const {
  return Group(make_handle(H5Gopen2(id(), "/", H5P_DEFAULT), H5Gclose, "cannot open the root group of " + path_.string()));
}

void File::flush() { check(H5Fflush(id(), H5F_SCOPE_LOCAL), "cannot flush HDF5 file " + path_.string()); }

void File::close() {
  try {
    handle_.close();
  } catch (const Error& e) {
    throw Error("cannot close HDF5 file " + path_.string() + ": " + e.what());
  }
}

// Attributes ------------------------------------------------------------------

void write_attribute(hid_t object, const std::string& name, std::string_view value) {
  const Handle type = utf8_string_type();
  const Handle attribute = create_scalar_attribute(object, name, type.get());
  // A variable-length string is written from a char* to NUL-terminated text.
  const std::string text(value);
  const char* data = text.c_str();
  check(H5Awrite(attribute.get(), type.get(), &data), "cannot write attribute '" + name + "' of " + object_name(object));
}

void write_attribute(hid_t object, const std::string& name, const char* value) { write_attribute(object, name, std::string_view(value)); }

void write_attribute(hid_t object, const std::string& name, std::int64_t value) {
  write_numeric_attribute(object, name, H5T_NATIVE_INT64, value);
}

void write_attribute(hid_t object, const std::string& name, double value) {
  write_numeric_attribute(object, name, H5T_NATIVE_DOUBLE, value);
}

bool has_attribute(hid_t object, const std::string& name) {
  silence_error_printing();
  const htri_t present = H5Aexists(object, name.c_str());
  if (present < 0) fail("cannot query attribute '" + name + "' of " + object_name(object));
  return present > 0;
}

void remove_attribute(hid_t object, const std::string& name) {
  if (has_attribute(object, name)) check(H5Adelete(object, name.c_str()), "cannot delete attribute '" + name + "' of " + object_name(object));
}

std::string read_string_attribute(hid_t object, const std::string& name) {
  silence_error_printing();
  const Handle attribute = open_attribute(object, name);
  const Handle stored = make_handle(H5Aget_type(attribute.get()), H5Tclose, "cannot read the type of attribute '" + name + "'");
  if (H5Tget_class(stored.get()) != H5T_STRING)
    throw Error("attribute '" + name + "' of " + object_name(object) + " is not a string");
  const htri_t variable = H5Tis_variable_str(stored.get());
  if (variable < 0) fail("cannot inspect the type of attribute '" + name + "'");
  // Strings are read in their stored type: HDF5 will not convert between ASCII and UTF-8.
  if (variable > 0) {
    char* raw = nullptr;
    check(H5Aread(attribute.get(), stored.get(), &raw), "cannot read attribute '" + name + "' of " + object_name(object));
    // HDF5 allocated the text; hand it to a deleter at once so it is freed on every path.
    const std::unique_ptr<char, herr_t (*)(void*)> owned(raw, H5free_memory);
    return owned ? std::string(owned.get()) : std::string();
  }
  const std::size_t size = H5Tget_size(stored.get());
  std::string text(size, '\0');
  check(H5Aread(attribute.get(), stored.get(), text.data()), "cannot read attribute '" + name + "' of " + object_name(object));
  // Fixed-length strings may be NUL-padded or NUL-terminated.
  text.resize(std::strlen(text.c_str()));
  return text;
}

std::int64_t read_int64_attribute(hid_t object, const std::string& name) {
  return read_numeric_attribute<std::int64_t>(object, name, H5T_NATIVE_INT64);
}

double read_double_attribute(hid_t object, const std::string& name) { return read_numeric_attribute<double>(object, name, H5T_NATIVE_DOUBLE); }

// Read-back helpers -----------------------------------------------------------

std::vector<double> read_f64(const File& file, const std::string& dataset_path) { return file.root().open_dataset(dataset_path).read_f64(); }

std::vector<std::int64_t> read_i64(const File& file, const std::string& dataset_path) {
  return file.root().open_dataset(dataset_path).read_i64();
}

std::vector<std::int64_t> dataset_shape(const File& file, const std::string& dataset_path) {
  return file.root().open_dataset(dataset_path).shape();
}

std::string read_string_attribute(const File& file, const std::string& object_path, const std::string& name) {
  const Handle object = open_object(file, object_path);
  return read_string_attribute(object.get(), name);
}

std::vector<std::string> list_members(const File& file, const std::string& group_path) { return file.root().open_group(group_path).members(); }

bool exists(const File& file, const std::string& path) { return file.root().has(path); }

}  // namespace dfc::h5
