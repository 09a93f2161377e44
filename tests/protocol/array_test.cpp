// Array helpers (array.hpp): typed construction, typed reads, and the
// BAD_ARRAY errors that name the array and the expected dtype and shape.
#include <gtest/gtest.h>

#include "dfc/protocol/array.hpp"
#include "dfc/protocol/error_code.hpp"

namespace dfc::protocol {
namespace {

TEST(Array, ElementCountOfScalarEmptyAndMatrix) {
  EXPECT_EQ((Array{"s", DType::f64, {}, {}}).element_count(), 1);
  EXPECT_EQ((Array{"e", DType::f64, {0, 3}, {}}).element_count(), 0);
  EXPECT_EQ((Array{"m", DType::f64, {4, 3}, {}}).element_count(), 12);
}

TEST(Array, FromF64RoundTripsAndRefusesAShapeThatDoesNotMatch) {
  const std::vector<double> values{1, 2, 3, 4, 5, 6};
  const Array array = Array::from_f64("x", {2, 3}, values);
  EXPECT_EQ(array.bytes.size(), 48u);
  EXPECT_EQ(array.to_f64(), values);
  EXPECT_THROW((void)Array::from_f64("x", {4, 3}, values), ProtocolError);
}

TEST(Array, TypedReadOfTheWrongDtypeIsBadArray) {
  const std::vector<std::int64_t> ids{1, 2};
  const Array array = Array::from_i64("node_ids", {2}, ids);
  EXPECT_EQ(array.to_i64(), ids);
  try {
    (void)array.to_f64();
    FAIL() << "read i64 as f64";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), ErrorCode::bad_array);
    EXPECT_NE(std::string(e.what()).find("node_ids"), std::string::npos);
  }
}

TEST(RequireF64, MissingArrayNamesItAndTheExpectedShape) {
  try {
    (void)require_f64({}, "force", 4, 3);
    FAIL() << "missing array accepted";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), ErrorCode::bad_array);
    EXPECT_NE(std::string(e.what()).find("'force'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("f64 [4,3]"), std::string::npos) << e.what();
  }
}

TEST(RequireF64, WrongShapeOrDtypeIsBadArray) {
  const std::vector<Array> arrays{Array::from_f64("force", {5, 3}, std::vector<double>(15)),
                                  Array::from_i64("mass", {4}, std::vector<std::int64_t>(4))};
  EXPECT_THROW((void)require_f64(arrays, "force", 4, 3), ProtocolError);
  EXPECT_THROW((void)require_f64(arrays, "mass", 4, 0), ProtocolError);
  EXPECT_EQ(require_f64(arrays, "force", 5, 3).size(), 15u);
}

TEST(FindArray, FindsByNameOrReturnsNull) {
  const std::vector<Array> arrays{Array::from_f64("a", {1}, std::vector<double>{1.0})};
  EXPECT_EQ(find_array(arrays, "a"), &arrays[0]);
  EXPECT_EQ(find_array(arrays, "b"), nullptr);
}

}  // namespace
}  // namespace dfc::protocol
