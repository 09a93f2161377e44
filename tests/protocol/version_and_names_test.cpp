// Version strings (SPEC.md §1) and the names of error codes, dtypes and
// session states, which are part of the wire format.
#include <gtest/gtest.h>

#include "dfc/protocol/message.hpp"
#include "dfc/protocol/server_session.hpp"

namespace dfc::protocol {
namespace {

TEST(ParseVersion, ReadsMajorAndMinor) {
  EXPECT_EQ(parse_version("1.0"), std::make_pair(1, 0));
  EXPECT_EQ(parse_version("12.34"), std::make_pair(12, 34));
  EXPECT_EQ(parse_version("0.0"), std::make_pair(0, 0));
  EXPECT_EQ(parse_version("99.0"), std::make_pair(99, 0));
}

TEST(ParseVersion, RefusesEverythingElse) {
  for (const char* text : {"", "1", "1.", ".1", "a.b", "1.0.0", "-1.0", "1.-0", "-0.0", " 1.0", "1.0 ", "+1.0", "1,0", "99999999999.0"})
    EXPECT_FALSE(parse_version(text).has_value()) << "'" << text << "'";
}

TEST(VersionString, IsMajorDotMinorOfTheConstants) {
  EXPECT_EQ(version_string(), std::to_string(kVersionMajor) + "." + std::to_string(kVersionMinor));
  EXPECT_EQ(parse_version(version_string()), std::make_pair(kVersionMajor, kVersionMinor));
}

TEST(ErrorCodeNames, RoundTripAndMatchTheSpec) {
  const std::vector<std::pair<ErrorCode, std::string_view>> spec{
      {ErrorCode::bad_message, "BAD_MESSAGE"},   {ErrorCode::unknown_type, "UNKNOWN_TYPE"},
      {ErrorCode::version_mismatch, "VERSION_MISMATCH"}, {ErrorCode::out_of_order, "OUT_OF_ORDER"},
      {ErrorCode::bad_array, "BAD_ARRAY"},       {ErrorCode::too_large, "TOO_LARGE"},
      {ErrorCode::step_mismatch, "STEP_MISMATCH"}, {ErrorCode::bad_config, "BAD_CONFIG"},
      {ErrorCode::unsupported, "UNSUPPORTED"},   {ErrorCode::solver_failure, "SOLVER_FAILURE"},
      {ErrorCode::internal, "INTERNAL"}};
  for (const auto& [code, name] : spec) {
    EXPECT_EQ(error_code_name(code), name);
    EXPECT_EQ(error_code_from_name(name), code);
  }
  EXPECT_FALSE(error_code_from_name("bad_message").has_value());
}

TEST(DtypeNames, RoundTripWithSizes) {
  const std::vector<std::tuple<DType, std::string_view, std::size_t>> spec{
      {DType::f64, "f64", 8}, {DType::f32, "f32", 4}, {DType::i64, "i64", 8}, {DType::i32, "i32", 4}, {DType::u8, "u8", 1}};
  for (const auto& [dtype, name, size] : spec) {
    EXPECT_EQ(dtype_name(dtype), name);
    EXPECT_EQ(dtype_from_name(name), dtype);
    EXPECT_EQ(dtype_size(dtype), size);
  }
  EXPECT_FALSE(dtype_from_name("float64").has_value());
}

TEST(MakeError, CarriesCodeMessageKeyAndReplyTo) {
  const Message error = make_error(5, ErrorCode::bad_config, "contact.law: unknown", "contact.law");
  EXPECT_EQ(error.type, type::error);
  EXPECT_EQ(error.reply_to, 5);
  EXPECT_EQ(error.body["code"], "BAD_CONFIG");
  EXPECT_EQ(error.body["message"], "contact.law: unknown");
  EXPECT_EQ(error.body["key"], "contact.law");
  EXPECT_FALSE(make_error(std::nullopt, ErrorCode::bad_message, "x").body.contains("key"));
}

}  // namespace
}  // namespace dfc::protocol
