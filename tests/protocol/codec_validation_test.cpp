// decode() refuses malformed headers and array descriptors with the error
// code SPEC.md §7 assigns, and names the request's seq whenever it could read it.
#include <gtest/gtest.h>

#include "codec_test_support.hpp"

namespace dfc::protocol::testing {
namespace {

struct BadHeader {
  const char* label;
  std::string header;
  ErrorCode code;
};

std::string header_with(const std::string& fields) {
  return R"({"protocol":"dfc","version":"1.0","type":"ping","seq":7)" + (fields.empty() ? "" : "," + fields) + "}";
}

class CodecRefusesHeader : public ::testing::TestWithParam<BadHeader> {};

TEST_P(CodecRefusesHeader, WithTheSpecifiedCode) {
  EXPECT_EQ(decode_error_code({GetParam().header}), GetParam().code) << GetParam().header;
}

INSTANTIATE_TEST_SUITE_P(
    HeaderFields, CodecRefusesHeader,
    ::testing::Values(BadHeader{"not_json", "this is {not JSON", ErrorCode::bad_message},
                      BadHeader{"json_array", "[1,2,3]", ErrorCode::bad_message},
                      BadHeader{"empty_frame", "", ErrorCode::bad_message},
                      BadHeader{"missing_seq", R"({"protocol":"dfc","version":"1.0","type":"ping"})", ErrorCode::bad_message},
                      BadHeader{"negative_seq", R"({"protocol":"dfc","version":"1.0","type":"ping","seq":-1})", ErrorCode::bad_message},
                      BadHeader{"fractional_seq", R"({"protocol":"dfc","version":"1.0","type":"ping","seq":1.5})", ErrorCode::bad_message},
                      BadHeader{"string_seq", R"({"protocol":"dfc","version":"1.0","type":"ping","seq":"1"})", ErrorCode::bad_message},
                      BadHeader{"missing_protocol", R"({"version":"1.0","type":"ping","seq":1})", ErrorCode::bad_message},
                      BadHeader{"wrong_protocol", R"({"protocol":"zmtp","version":"1.0","type":"ping","seq":1})", ErrorCode::bad_message},
                      BadHeader{"missing_version", R"({"protocol":"dfc","type":"ping","seq":1})", ErrorCode::bad_message},
                      BadHeader{"version_without_minor", R"({"protocol":"dfc","version":"1","type":"ping","seq":1})", ErrorCode::bad_message},
                      BadHeader{"numeric_version", R"({"protocol":"dfc","version":1.0,"type":"ping","seq":1})", ErrorCode::bad_message},
                      BadHeader{"missing_type", R"({"protocol":"dfc","version":"1.0","seq":1})", ErrorCode::bad_message},
                      BadHeader{"empty_type", R"({"protocol":"dfc","version":"1.0","type":"","seq":1})", ErrorCode::bad_message},
                      BadHeader{"numeric_type", R"({"protocol":"dfc","version":"1.0","type":5,"seq":1})", ErrorCode::bad_message},
                      BadHeader{"body_not_object", header_with(R"("body":"x")"), ErrorCode::bad_message},
                      BadHeader{"arrays_not_array", header_with(R"("arrays":{})"), ErrorCode::bad_message},
                      BadHeader{"negative_reply_to", header_with(R"("reply_to":-3)"), ErrorCode::bad_message},
                      BadHeader{"string_step", header_with(R"("step":"3")"), ErrorCode::bad_message},
                      BadHeader{"step_beyond_int64", header_with(R"("step":18446744073709551615)"), ErrorCode::bad_message}),
    [](const auto& test) { return std::string(test.param.label); });

struct BadDescriptor {
  const char* label;
  std::string arrays;  ///< the header's "arrays" value
  std::vector<std::string> frames;
};

class CodecRefusesArrays : public ::testing::TestWithParam<BadDescriptor> {};

TEST_P(CodecRefusesArrays, AsBadArray) {
  std::vector<std::string> frames{header_with(R"("arrays":)" + GetParam().arrays)};
  frames.insert(frames.end(), GetParam().frames.begin(), GetParam().frames.end());
  EXPECT_EQ(decode_error_code(frames), ErrorCode::bad_array) << GetParam().arrays;
}

const std::string kEight(8, '\0');

INSTANTIATE_TEST_SUITE_P(
    Descriptors, CodecRefusesArrays,
    ::testing::Values(BadDescriptor{"more_descriptors_than_frames", R"([{"name":"a","dtype":"f64","shape":[1]},{"name":"b","dtype":"f64","shape":[1]}])", {kEight}},
                      BadDescriptor{"more_frames_than_descriptors", R"([{"name":"a","dtype":"f64","shape":[1]}])", {kEight, kEight}},
                      BadDescriptor{"frame_too_short", R"([{"name":"a","dtype":"f64","shape":[3]}])", {std::string(16, '\0')}},
                      BadDescriptor{"frame_too_long", R"([{"name":"a","dtype":"f32","shape":[1]}])", {kEight}},
                      BadDescriptor{"unknown_dtype", R"([{"name":"a","dtype":"c128","shape":[1]}])", {std::string(16, '\0')}},
                      BadDescriptor{"missing_dtype", R"([{"name":"a","shape":[1]}])", {kEight}},
                      BadDescriptor{"descriptor_not_object", R"(["a"])", {kEight}},
                      BadDescriptor{"missing_name", R"([{"dtype":"f64","shape":[1]}])", {kEight}},
                      BadDescriptor{"empty_name", R"([{"name":"","dtype":"f64","shape":[1]}])", {kEight}},
                      BadDescriptor{"shape_not_array", R"([{"name":"a","dtype":"f64","shape":1}])", {kEight}},
                      BadDescriptor{"nine_dimensions", R"([{"name":"a","dtype":"u8","shape":[1,1,1,1,1,1,1,1,1]}])", {std::string(1, '\0')}},
                      BadDescriptor{"negative_extent", R"([{"name":"a","dtype":"f64","shape":[-1]}])", {kEight}},
                      BadDescriptor{"fractional_extent", R"([{"name":"a","dtype":"f64","shape":[1.5]}])", {kEight}},
                      BadDescriptor{"duplicate_names", R"([{"name":"a","dtype":"f64","shape":[1]},{"name":"a","dtype":"f64","shape":[1]}])",
                                    {kEight, kEight}}),
    [](const auto& test) { return std::string(test.param.label); });

TEST(CodecErrors, NameTheSeqWhenTheHeaderHadOne) {
  try {
    (void)decode_texts({R"({"protocol":"dfc","version":"1.0","seq":42})"});
    FAIL() << "a header without type was accepted";
  } catch (const DecodeError& e) {
    EXPECT_EQ(e.code(), ErrorCode::bad_message);
    EXPECT_EQ(e.seq(), 42);
    EXPECT_NE(std::string(e.what()).find("type"), std::string::npos) << e.what();
  }
}

TEST(CodecErrors, HaveNoSeqWhenTheHeaderIsUnreadable) {
  try {
    (void)decode_texts({"{"});
    FAIL() << "an unreadable header was accepted";
  } catch (const DecodeError& e) {
    EXPECT_FALSE(e.seq().has_value());
  }
}

TEST(CodecErrors, ArrayErrorsNameTheArray) {
  try {
    (void)decode_texts({header_with(R"("arrays":[{"name":"force","dtype":"f64","shape":[2,3]}])"), std::string(40, '\0')});
    FAIL() << "a 40-byte frame for f64 [2,3] was accepted";
  } catch (const DecodeError& e) {
    EXPECT_EQ(e.code(), ErrorCode::bad_array);
    EXPECT_NE(std::string(e.what()).find("force"), std::string::npos) << e.what();
    EXPECT_EQ(e.seq(), 7);
  }
}

TEST(CodecErrors, NoFramesAtAllIsBadMessage) {
  EXPECT_EQ(decode_error_code({}), ErrorCode::bad_message);
}

}  // namespace
}  // namespace dfc::protocol::testing
