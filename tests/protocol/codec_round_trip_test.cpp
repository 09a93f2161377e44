// Encoding then decoding a message gives it back unchanged (SPEC.md §3):
// every dtype, empty and scalar shapes, and every header field.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

#include "codec_test_support.hpp"

namespace dfc::protocol::testing {
namespace {

void expect_same_array(const Array& expected, const Array& actual) {
  EXPECT_EQ(expected.name, actual.name);
  EXPECT_EQ(expected.dtype, actual.dtype) << expected.name;
  EXPECT_EQ(expected.shape, actual.shape) << expected.name;
  EXPECT_EQ(expected.bytes, actual.bytes) << expected.name;
}

TEST(CodecRoundTrip, EveryDtypeKeepsItsBytesShapeAndName) {
  Message message;
  message.type = "advance";
  message.arrays = {
      typed_array<double>("f64", DType::f64, {2, 2}, {1.5, -2.25, std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min()}),
      typed_array<float>("f32", DType::f32, {3}, {0.1f, -7.0f, std::numeric_limits<float>::lowest()}),
      typed_array<std::int64_t>("i64", DType::i64, {3}, {std::numeric_limits<std::int64_t>::min(), 0, std::numeric_limits<std::int64_t>::max()}),
      typed_array<std::int32_t>("i32", DType::i32, {1, 2}, {-1, std::numeric_limits<std::int32_t>::max()}),
      typed_array<std::uint8_t>("u8", DType::u8, {4}, {0, 1, 127, 255}),
  };
  const Message decoded = round_trip(message);
  ASSERT_EQ(decoded.arrays.size(), message.arrays.size());
  for (std::size_t i = 0; i < message.arrays.size(); ++i) expect_same_array(message.arrays[i], decoded.arrays[i]);
}

TEST(CodecRoundTrip, EmptyScalarAndEightDimensionalShapes) {
  Message message;
  message.type = "ping";
  message.arrays = {
      typed_array<double>("empty", DType::f64, {0}, {}),
      typed_array<std::int64_t>("no_rows", DType::i64, {0, 3}, {}),
      typed_array<double>("scalar", DType::f64, {}, {42.0}),
      typed_array<std::uint8_t>("eight_dims", DType::u8, {1, 1, 1, 1, 1, 1, 1, 2}, {7, 9}),
  };
  const Message decoded = round_trip(message);
  ASSERT_EQ(decoded.arrays.size(), 4u);
  for (std::size_t i = 0; i < message.arrays.size(); ++i) expect_same_array(message.arrays[i], decoded.arrays[i]);
  EXPECT_EQ(decoded.arrays[2].element_count(), 1);
  EXPECT_EQ(decoded.arrays[1].element_count(), 0);
}

TEST(CodecRoundTrip, HeaderFieldsSurviveExactly) {
  Message message;
  message.type = "advanced";
  message.version = "1.7";
  message.seq = 123;
  message.reply_to = 122;
  message.step = (std::int64_t(1) << 53) + 1;  // not representable as a double: must travel as an integer
  message.body = {{"dt", 0.1}, {"monitors", {{"e", {1.0, 2.0, 3.0}}}}, {"text", "ü ✓"}};
  const Message decoded = round_trip(message);
  EXPECT_EQ(decoded.type, "advanced");
  EXPECT_EQ(decoded.version, "1.7");
  EXPECT_EQ(decoded.seq, 123);
  EXPECT_EQ(decoded.reply_to, 122);
  EXPECT_EQ(decoded.step, (std::int64_t(1) << 53) + 1);
  EXPECT_EQ(decoded.body, message.body);
  EXPECT_EQ(decoded.body["dt"].get<double>(), 0.1);
}

TEST(CodecRoundTrip, AbsentOptionalFieldsStayAbsent) {
  const Message decoded = decode_texts({R"({"protocol":"dfc","version":"1.0","type":"ping","seq":0})"});
  EXPECT_FALSE(decoded.reply_to.has_value());
  EXPECT_FALSE(decoded.step.has_value());
  EXPECT_TRUE(decoded.body.is_object());
  EXPECT_TRUE(decoded.body.empty());
  EXPECT_TRUE(decoded.arrays.empty());
}

TEST(CodecRoundTrip, UnknownHeaderFieldsAreIgnoredForMinorCompatibility) {
  const Message decoded = decode_texts({R"({"protocol":"dfc","version":"1.9","type":"ping","seq":4,"priority":"high"})"});
  EXPECT_EQ(decoded.type, "ping");
  EXPECT_EQ(decoded.seq, 4);
}

TEST(CodecRoundTrip, EncodedHeaderCarriesDescriptorsInArrayOrder) {
  Message message;
  message.type = "interface";
  message.arrays = {typed_array<std::int64_t>("b", DType::i64, {1}, {5}), typed_array<double>("a", DType::f64, {1, 3}, {1, 2, 3})};
  const auto header = nlohmann::json::parse(encode_header(message));
  ASSERT_EQ(header["arrays"].size(), 2u);
  EXPECT_EQ(header["arrays"][0], (nlohmann::json{{"name", "b"}, {"dtype", "i64"}, {"shape", {1}}}));
  EXPECT_EQ(header["arrays"][1], (nlohmann::json{{"name", "a"}, {"dtype", "f64"}, {"shape", {1, 3}}}));
  EXPECT_EQ(header["protocol"], "dfc");
}

}  // namespace
}  // namespace dfc::protocol::testing
