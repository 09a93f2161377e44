// ResultsWriter: what is written reads back exactly, the file is readable
// while the run goes on, and misuse fails loudly.
#include "dfc/coupler/results_writer.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <regex>

#include <gtest/gtest.h>

#include "dfc/common/errors.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "results_sample_data.hpp"

namespace dfc::coupler {
namespace {

using namespace dfc::coupler::testing;

const nlohmann::json scenario = {{"name", "pile"}, {"dem", {{"radius_m", 0.002}}}};
const nlohmann::json versions = {{"coupler", "0.1.0"}, {"servers", {{{"name", "dem"}, {"version", "0.1.0"}, {"protocol", 1}}}}};

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

TEST(ResultsWriterSeries, RoundTripIsBitIdentical) {
  ScratchDir dir("series");
  const std::vector<std::string> columns = {"time_s", "awkward"};
  std::vector<double> time, awkward;
  // More rows than one write block, and values a text or float round trip would alter.
  for (int i = 0; i < 1000; ++i) {
    time.push_back(std::nextafter(1e-3 * i, 1.0));
    awkward.push_back(i % 4 == 0 ? -0.0 : i % 4 == 1 ? std::numeric_limits<double>::denorm_min() * i : i % 4 == 2 ? 1.0 / 3.0 * i : -1e300);
  }
  {
    ResultsWriter out(dir / "run.h5", scenario, versions);
    out.declare_series(columns, {{"time_s", "s"}});
    for (std::size_t i = 0; i < time.size(); ++i) out.append({time[i], awkward[i]});
    EXPECT_EQ(out.row_count(), 1000);
    out.close();
  }
  const h5::File in = h5::File::open_read_only(dir / "run.h5");
  EXPECT_TRUE(same_bits(h5::read_f64(in, "/timeseries/time_s"), time));
  EXPECT_TRUE(same_bits(h5::read_f64(in, "/timeseries/awkward"), awkward));
  EXPECT_EQ(h5::read_string_attribute(in, "/timeseries/time_s", "unit"), "s");
  EXPECT_FALSE(h5::has_attribute(in.root().open_dataset("/timeseries/awkward").id(), "unit"));
  EXPECT_EQ(nlohmann::json::parse(h5::read_string_attribute(in, "/timeseries", "columns")), nlohmann::json(columns));
}

TEST(ResultsWriterSeries, SeriesAreStoredCompressed) {
  // 5000 rows of a slowly changing value and a constant (a monitor that
  // settles): deflated, they take far fewer bytes than the 80 000 raw ones,
  // and read back bit for bit.
  ScratchDir dir("series_compressed");
  std::vector<double> settling, constant(5000, 9.81);
  for (int i = 0; i < 5000; ++i) settling.push_back(std::floor(i / 100.0) * 0.5);
  {
    ResultsWriter out(dir / "run.h5", scenario, versions);
    out.declare_series({"settling", "constant"}, {});
    for (std::size_t i = 0; i < settling.size(); ++i) out.append({settling[i], constant[i]});
    out.close();
  }
  const h5::File in = h5::File::open_read_only(dir / "run.h5");
  EXPECT_TRUE(same_bits(h5::read_f64(in, "/timeseries/settling"), settling));
  EXPECT_TRUE(same_bits(h5::read_f64(in, "/timeseries/constant"), constant));
  for (const char* name : {"settling", "constant"}) {
    const h5::Dataset d = in.root().open_dataset(std::string("/timeseries/") + name);
    EXPECT_LT(H5Dget_storage_size(d.id()), 40000U / 10) << name;
  }
}

TEST(ResultsWriterSeries, AppendWithWrongRowLengthThrows) {
  ScratchDir dir("rowlength");
  ResultsWriter out(dir / "run.h5", scenario, versions);
  EXPECT_THROW(out.append({1.0}), std::logic_error);  // before declare_series
  out.declare_series({"a", "b", "c"}, {});
  EXPECT_THROW(out.append({1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(out.append({1.0, 2.0, 3.0, 4.0}), std::invalid_argument);
  out.append({1.0, 2.0, 3.0});
  EXPECT_EQ(out.row_count(), 1);
  EXPECT_THROW(out.declare_series({"d"}, {}), std::logic_error);
}

TEST(ResultsWriterSeries, VectorColumnsAreRowsOfThreeWithTheirUnits) {
  ScratchDir dir("vectors");
  const std::size_t rows = 300;  // more than one write block
  {
    ResultsWriter out(dir / "run.h5", scenario, versions);
    out.declare_series({{"time_s", "s"}, {"dem_wall_floor_force_n", "N", 3}, {"dem_axial_stress_pa", "Pa"}, {"dem_odd", "1", 1, true}});
    for (std::size_t i = 0; i < rows; ++i) {
      const double x = double(i);
      out.append({x, x, -x, 2 * x, 1e3 * x, 0.5});
    }
    EXPECT_THROW(out.append({0.0, 1.0, 2.0, 3.0}), std::invalid_argument);  // a row must hold all three components
    out.close();
  }
  const h5::File in = h5::File::open_read_only(dir / "run.h5");
  const h5::Dataset force = in.root().open_dataset("/timeseries/dem_wall_floor_force_n");
  EXPECT_EQ(force.shape(), (std::vector<std::int64_t>{std::int64_t(rows), 3}));
  const std::vector<double> components = force.read_f64();
  ASSERT_EQ(components.size(), 3 * rows);
  EXPECT_EQ((std::vector<double>(components.begin() + 3 * 7, components.begin() + 3 * 8)), (std::vector<double>{7.0, -7.0, 14.0}));
  EXPECT_EQ(in.root().open_dataset("/timeseries/time_s").shape(), (std::vector<std::int64_t>{std::int64_t(rows)}));
  EXPECT_EQ(h5::read_f64(in, "/timeseries/dem_axial_stress_pa")[9], 9e3);
  EXPECT_EQ(h5::read_string_attribute(in, "/timeseries/dem_wall_floor_force_n", "unit"), "N");
  EXPECT_EQ(h5::read_string_attribute(in, "/timeseries/dem_axial_stress_pa", "unit"), "Pa");
  // Only a guessed unit says where it came from.
  EXPECT_FALSE(h5::has_attribute(force.id(), "unit_source"));
  EXPECT_EQ(h5::read_string_attribute(in, "/timeseries/dem_odd", "unit_source"), "guessed from the name");
}

TEST(ResultsWriterSeries, RejectsBadColumnDeclarations) {
  ScratchDir dir("columns");
  ResultsWriter out(dir / "run.h5", scenario, versions);
  EXPECT_THROW(out.declare_series({"a", "a"}, {}), std::invalid_argument);
  EXPECT_THROW(out.declare_series({"a/b"}, {}), std::invalid_argument);
  EXPECT_THROW(out.declare_series({"a"}, {{"typo", "m"}}), std::invalid_argument);
  out.declare_series({"a"}, {{"a", "m"}});  // the rejected calls left nothing behind
}

TEST(ResultsWriterSnapshot, ArraysKeepDtypeShapeAndValues) {
  ScratchDir dir("snapshot");
  std::vector<protocol::Array> arrays = particle_arrays(5, 1);
  arrays.push_back(make_array<float>("f32_values", protocol::DType::f32, {2, 2}, {1.5F, -2.5F, 3.25F, 0.0F}));
  arrays.push_back(make_array<std::int32_t>("i32_values", protocol::DType::i32, {3}, {-7, 0, 2147483647}));
  arrays.push_back(make_array<std::uint8_t>("u8_values", protocol::DType::u8, {4}, {0, 1, 254, 255}));
  arrays.push_back(f64_array("empty", {0, 3}, {}));
  {
    ResultsWriter out(dir / "run.h5", scenario, versions);
    out.write_snapshot("dem", 10, 0.5, "particles", particle_arrays(5, 0));
    out.write_snapshot("dem", 20, 1.0, "particles", arrays);
    out.write_snapshot("fdm", 20, 1.0, "grid", grid_arrays(2, 1, 1, 0));
  }
  const h5::File in = h5::File::open_read_only(dir / "run.h5");
  EXPECT_EQ(h5::list_members(in, "/snapshots"), (std::vector<std::string>{"dem", "fdm"}));
  EXPECT_EQ(h5::list_members(in, "/snapshots/dem"), (std::vector<std::string>{"000000", "000001"}));
  const h5::Group group = in.root().open_group("/snapshots/dem/000001");
  EXPECT_EQ(h5::read_int64_attribute(group.id(), "step"), 20);
  EXPECT_EQ(h5::read_double_attribute(group.id(), "time"), 1.0);
  EXPECT_EQ(h5::read_string_attribute(group.id(), "kind"), "particles");
  EXPECT_EQ(h5::read_string_attribute(in, "/snapshots/fdm/000000", "kind"), "grid");

  const std::map<protocol::DType, std::pair<const char*, hid_t>> types = {{protocol::DType::f64, {"f64", H5T_NATIVE_DOUBLE}},
                                                                          {protocol::DType::f32, {"f32", H5T_NATIVE_FLOAT}},
                                                                          {protocol::DType::i64, {"i64", H5T_NATIVE_INT64}},
                                                                          {protocol::DType::i32, {"i32", H5T_NATIVE_INT32}},
                                                                          {protocol::DType::u8, {"u8", H5T_NATIVE_UINT8}}};
  EXPECT_EQ(h5::list_members(in, "/snapshots/dem/000001").size(), arrays.size());
  for (const protocol::Array& array : arrays) {
    SCOPED_TRACE(array.name);
    const h5::Dataset dataset = group.open_dataset(array.name);
    const auto& [type_name, native] = types.at(array.dtype);
    EXPECT_EQ(dataset.element_type_name(), type_name);
    EXPECT_EQ(dataset.shape(), array.shape);
    EXPECT_EQ(dataset.read_raw(native), array.bytes);
  }
  // Integers above 2^53 prove the ids were not stored as doubles.
  EXPECT_EQ(h5::read_i64(in, "/snapshots/dem/000001/particle_id").front(), (std::int64_t{1} << 53) + 1);
  EXPECT_EQ(h5::dataset_shape(in, "/snapshots/fdm/000000/zone_nodes"), (std::vector<std::int64_t>{2, 8}));
}

TEST(ResultsWriterSnapshot, BadArrayThrowsAndLeavesNoGroup) {
  ScratchDir dir("badarray");
  ResultsWriter out(dir / "run.h5", scenario, versions);
  std::vector<protocol::Array> arrays = particle_arrays(3, 0);
  arrays[1].shape = {4};  // 3 values for a shape of 4
  EXPECT_THROW(out.write_snapshot("dem", 0, 0.0, "particles", arrays), std::invalid_argument);
  std::vector<protocol::Array> twice = particle_arrays(3, 0);
  twice.push_back(twice.front());
  EXPECT_THROW(out.write_snapshot("dem", 0, 0.0, "particles", twice), std::invalid_argument);
  EXPECT_THROW(out.write_snapshot("de/m", 0, 0.0, "particles", particle_arrays(3, 0)), std::invalid_argument);
  out.write_snapshot("dem", 0, 0.0, "particles", particle_arrays(3, 0));
  out.close();
  const h5::File in = h5::File::open_read_only(dir / "run.h5");
  EXPECT_EQ(h5::list_members(in, "/snapshots/dem"), (std::vector<std::string>{"000000"}));
}

TEST(ResultsWriterAttributes, RootAttributesRoundTrip) {
  ScratchDir dir("attributes");
  {
    ResultsWriter out(dir / "run.h5", scenario, versions);
    out.set_attribute("summary", R"({"steps": 1})");
    out.set_attribute("summary", R"({"steps": 2, "note": "ünïcode"})");  // replaces the first
  }
  const h5::File in = h5::File::open_read_only(dir / "run.h5");
  EXPECT_EQ(nlohmann::json::parse(h5::read_string_attribute(in, "/", "scenario")), scenario);
  EXPECT_EQ(nlohmann::json::parse(h5::read_string_attribute(in, "/", "versions")), versions);
  EXPECT_EQ(h5::read_string_attribute(in, "/", "format"), "dfc-results-1");
  EXPECT_EQ(h5::read_string_attribute(in, "/", "summary"), R"({"steps": 2, "note": "ünïcode"})");
  EXPECT_TRUE(std::regex_match(h5::read_string_attribute(in, "/", "created_utc"), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")));
}

TEST(ResultsWriterFlush, FileIsReadableAfterFlushWhileWriterIsOpen) {
  ScratchDir dir("flush");
  ResultsWriter out(dir / "run.h5", scenario, versions);
  out.declare_series({"x"}, {});
  for (int i = 0; i < 10; ++i) out.append({1.0 * i});  // fewer than a block: only flush() writes them
  out.write_snapshot("dem", 3, 0.25, "particles", particle_arrays(4, 0));
  out.flush();
  {
    const h5::File in = h5::File::open_read_only(dir / "run.h5");
    EXPECT_EQ(h5::read_f64(in, "/timeseries/x").size(), 10U);
    EXPECT_EQ(h5::dataset_shape(in, "/snapshots/dem/000000/particle_position"), (std::vector<std::int64_t>{4, 3}));
  }
  EXPECT_TRUE(std::filesystem::exists(out.xdmf_path()));  // the sidecar is kept current for runs that die later
  out.append({10.0});
  out.flush();
  const h5::File in = h5::File::open_read_only(dir / "run.h5");
  EXPECT_EQ(h5::read_f64(in, "/timeseries/x").back(), 10.0);
}

// The same check from a separate process, which does not share the writer's
// HDF5 library state: it sees only what flush() put on disk, and must not be
// stopped by a file lock.
TEST(ResultsWriterFlush, AnotherProcessReadsFlushedFile) {
  ScratchDir dir("otherprocess");
  const std::filesystem::path path = dir / "run.h5";
  int go[2];
  ASSERT_EQ(::pipe(go), 0);
  // Fork before the file exists so the child's copy of the library has nothing open.
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(go[1]);
    char byte = 0;
    if (::read(go[0], &byte, 1) != 1) ::_exit(2);
    int status = 1;
    try {
      const h5::File in = h5::File::open_read_only(path);
      const std::vector<double> x = h5::read_f64(in, "/timeseries/x");
      const bool ok = x.size() == 7 && x.back() == 6.0 && h5::read_string_attribute(in, "/", "format") == "dfc-results-1";
      status = ok ? 0 : 3;
    } catch (...) {
      status = 4;
    }
    ::_exit(status);  // skip gtest's and the parent's atexit work in the child
  }
  ::close(go[0]);
  ResultsWriter out(path, scenario, versions);
  out.declare_series({"x"}, {});
  for (int i = 0; i < 7; ++i) out.append({1.0 * i});
  out.flush();
  ASSERT_EQ(::write(go[1], "g", 1), 1);
  ::close(go[1]);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "child exit codes: 2 no go signal, 3 wrong contents, 4 could not open or read";
  EXPECT_TRUE(out.is_open());
}

TEST(ResultsWriterClose, DestructorClosesCleanly) {
  ScratchDir dir("destructor");
  const std::filesystem::path path = dir / "run.h5";
  {
    ResultsWriter out(path, scenario, versions);
    out.declare_series({"x"}, {});
    out.append({42.0});
    out.write_snapshot("dem", 0, 0.0, "particles", particle_arrays(2, 0));
  }  // no close(): the destructor must write the buffered row and the sidecar, and release the file
  EXPECT_TRUE(std::filesystem::exists(dir / "run.xdmf"));
  {
    const h5::File in = h5::File::open_read_only(path);
    EXPECT_EQ(h5::read_f64(in, "/timeseries/x"), (std::vector<double>{42.0}));
  }
  // HDF5 refuses to truncate a file this process still holds open, so this proves it was released.
  EXPECT_NO_THROW(ResultsWriter(path, scenario, versions).close());
}

TEST(ResultsWriterClose, CloseIsIdempotentAndLaterWritesThrow) {
  ScratchDir dir("close");
  ResultsWriter out(dir / "run.h5", scenario, versions);
  out.declare_series({"x"}, {});
  out.close();
  EXPECT_FALSE(out.is_open());
  EXPECT_NO_THROW(out.close());
  EXPECT_THROW(out.append({1.0}), std::logic_error);
  EXPECT_THROW(out.flush(), std::logic_error);
  EXPECT_THROW(out.set_attribute("summary", "{}"), std::logic_error);
}

TEST(ResultsWriterClose, MovedWriterKeepsWriting) {
  ScratchDir dir("move");
  ResultsWriter first(dir / "run.h5", scenario, versions);
  first.declare_series({"x"}, {});
  ResultsWriter second = std::move(first);
  second.append({1.0});
  second.close();
  EXPECT_NO_THROW(first.close());  // moved-from: nothing to do
  const h5::File in = h5::File::open_read_only(dir / "run.h5");
  EXPECT_EQ(h5::read_f64(in, "/timeseries/x").size(), 1U);
}

TEST(ResultsWriterErrors, UnwritablePathIsUserErrorNamingThePath) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "dfc-no-such-dir" / "sub" / "run.h5";
  try {
    ResultsWriter out(path, scenario, versions);
    FAIL() << "expected a UserError";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  ScratchDir dir("xdmfname");
  EXPECT_THROW(ResultsWriter(dir / "run.xdmf", scenario, versions), UserError);
}

TEST(ResultsWriterPaths, SidecarReplacesTheExtension) {
  ScratchDir dir("sidecar");
  ResultsWriter out(dir / "run.h5", scenario, versions);
  EXPECT_EQ(out.xdmf_path(), dir / "run.xdmf");
  EXPECT_EQ(out.path(), dir / "run.h5");
}

}  // namespace
}  // namespace dfc::coupler
