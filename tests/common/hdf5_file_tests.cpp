// h5 wrappers: handles close what they own, paths that cannot be used are
// user errors naming the path, and values read back as written.
#include "dfc/common/hdf5_file.hpp"

#include <unistd.h>

#include <cstring>
#include <fstream>

#include <gtest/gtest.h>

#include "dfc/common/errors.hpp"

namespace dfc::h5 {
namespace {

class Hdf5File : public ::testing::Test {
 protected:
  Hdf5File() : dir_(std::filesystem::temp_directory_path() / ("dfc-hdf5-test-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~Hdf5File() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::filesystem::path dir_;
};

std::span<const std::byte> bytes_of(const std::vector<double>& values) { return std::as_bytes(std::span(values)); }

TEST_F(Hdf5File, HandleClosesOnDestructionAndMoveTransfersOwnership) {
  const hid_t space = H5Screate(H5S_SCALAR);
  ASSERT_GT(space, 0);
  {
    Handle owner(space, H5Sclose);
    Handle moved = std::move(owner);
    EXPECT_FALSE(owner.valid());  // NOLINT(bugprone-use-after-move): the moved-from state is what is tested
    EXPECT_EQ(moved.get(), space);
    EXPECT_GT(H5Iis_valid(space), 0);
  }
  EXPECT_LE(H5Iis_valid(space), 0);
}

TEST_F(Hdf5File, DatasetsAndAttributesRoundTrip) {
  const std::vector<double> values = {1.0, -0.0, 1e-310, 3.5, 4.25, 6.0};
  {
    File file = File::create(dir_ / "a.h5");
    const Group group = file.root().create_group("g");
    const std::vector<std::int64_t> shape = {2, 3};
    const Dataset dataset = group.write_dataset("d", H5T_NATIVE_DOUBLE, shape, bytes_of(values));
    write_attribute(dataset.id(), "unit", "m");
    write_attribute(dataset.id(), "unit", "mm");  // replaces
    write_attribute(group.id(), "count", std::int64_t{-5});
    write_attribute(group.id(), "scale", 0.1);
    Dataset series = group.create_extendable_f64("s", 4);
    series.append_f64(std::vector<double>{1, 2, 3});
    series.append_f64(std::vector<double>{4, 5, 6, 7, 8});  // crosses a chunk boundary
    file.flush();
    file.close();
    EXPECT_FALSE(file.is_open());
  }
  const File file = File::open_read_only(dir_ / "a.h5");
  const std::vector<double> back = read_f64(file, "/g/d");
  ASSERT_EQ(back.size(), values.size());
  EXPECT_EQ(std::memcmp(back.data(), values.data(), back.size() * sizeof(double)), 0);
  EXPECT_EQ(dataset_shape(file, "/g/d"), (std::vector<std::int64_t>{2, 3}));
  EXPECT_EQ(read_string_attribute(file, "/g/d", "unit"), "mm");
  const Group group = file.root().open_group("g");
  EXPECT_EQ(read_int64_attribute(group.id(), "count"), -5);
  EXPECT_EQ(read_double_attribute(group.id(), "scale"), 0.1);
  EXPECT_EQ(read_f64(file, "/g/s"), (std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(read_i64(file, "/g/s"), (std::vector<std::int64_t>{1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(list_members(file, "/g"), (std::vector<std::string>{"d", "s"}));
  EXPECT_EQ(group.open_dataset("d").element_type_name(), "f64");
}

TEST_F(Hdf5File, CompressedDatasetsReadBackAsWrittenAndTakeLessRoom) {
  // 3000 rows of three repetitive values: chunked and deflated, stored in far
  // fewer bytes than the 72 000 raw ones, and read back bit for bit; an empty
  // and a scalar dataset at the same level are stored as given.
  std::vector<double> values(9000);
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = double(k % 7) * 0.125;
  {
    File file = File::create(dir_ / "z.h5");
    const std::vector<std::int64_t> shape = {3000, 3}, empty = {0, 2}, scalar = {};
    (void)file.root().write_dataset("d", H5T_NATIVE_DOUBLE, shape, bytes_of(values), 1);
    (void)file.root().write_dataset("e", H5T_NATIVE_DOUBLE, empty, {}, 1);
    (void)file.root().write_dataset("s", H5T_NATIVE_DOUBLE, scalar, bytes_of({2.5}), 1);
    EXPECT_THROW((void)file.root().write_dataset("x", H5T_NATIVE_DOUBLE, shape, bytes_of(values), 10), Error);
    file.close();
  }
  const File file = File::open_read_only(dir_ / "z.h5");
  EXPECT_EQ(read_f64(file, "/d"), values);
  EXPECT_EQ(dataset_shape(file, "/e"), (std::vector<std::int64_t>{0, 2}));
  EXPECT_EQ(read_f64(file, "/s"), (std::vector<double>{2.5}));
  const Dataset d = file.root().open_dataset("d");
  EXPECT_LT(H5Dget_storage_size(d.id()), 72000U / 10);
  const Handle plist(H5Dget_create_plist(d.id()), H5Pclose);
  EXPECT_EQ(H5Pget_layout(plist.get()), H5D_CHUNKED);
  EXPECT_EQ(H5Pget_nfilters(plist.get()), 1);
}

TEST_F(Hdf5File, FixedLengthStringAttributesAreReadToo) {
  // Files written by other tools often use fixed-length, NUL-padded strings.
  {
    File file = File::create(dir_ / "fixed.h5");
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, 8);
    H5Tset_strpad(type, H5T_STR_NULLPAD);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attribute = H5Acreate2(file.id(), "label", type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char text[8] = {'a', 'b', 'c', '\0', '\0', '\0', '\0', '\0'};
    EXPECT_GE(H5Awrite(attribute, type, text), 0);
    H5Aclose(attribute);
    H5Sclose(space);
    H5Tclose(type);
  }
  const File file = File::open_read_only(dir_ / "fixed.h5");
  EXPECT_EQ(read_string_attribute(file, "/", "label"), "abc");
}

TEST_F(Hdf5File, ExistsIsFalseForMissingParents) {
  File file = File::create(dir_ / "b.h5");
  (void)file.root().create_group("a").create_group("b");
  EXPECT_TRUE(exists(file, "/a/b"));
  EXPECT_TRUE(exists(file, "/"));
  EXPECT_FALSE(exists(file, "/a/c"));
  EXPECT_FALSE(exists(file, "/x/y/z"));
  EXPECT_TRUE(file.root().open_group("a").has("b"));
}

TEST_F(Hdf5File, WrongByteCountIsAnError) {
  File file = File::create(dir_ / "c.h5");
  const std::vector<double> values = {1.0, 2.0};
  const std::vector<std::int64_t> shape = {3};
  EXPECT_THROW((void)file.root().write_dataset("d", H5T_NATIVE_DOUBLE, shape, bytes_of(values)), Error);
}

TEST_F(Hdf5File, FailuresCarryTheHdf5Reason) {
  const File file = File::create(dir_ / "d.h5");
  try {
    (void)file.root().open_dataset("/missing");
    FAIL() << "expected h5::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/missing"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("HDF5:"), std::string::npos) << e.what();
  }
}

TEST_F(Hdf5File, UnusablePathsAreUserErrorsNamingThePath) {
  const std::filesystem::path missing_dir = dir_ / "no" / "such" / "x.h5";
  try {
    (void)File::create(missing_dir);
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find(missing_dir.string()), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)File::open_read_only(dir_ / "absent.h5"), UserError);
  std::ofstream(dir_ / "text.h5") << "not an HDF5 file";
  try {
    (void)File::open_read_only(dir_ / "text.h5");
    FAIL() << "expected UserError";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("text.h5"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dfc::h5
