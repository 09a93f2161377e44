// Regression tests for what the protocol fuzzer (fuzz/protocol_codec_fuzzer.cpp)
// found; the inputs that found them are in fuzz/corpus/protocol/.
//
// 1. A reply whose error text quotes bytes that are not UTF-8 could not be
//    encoded: nlohmann's dump() threw, and the server ended instead of
//    answering. It happened for a configure whose bad value is cut to 40
//    bytes inside a character (ConfigReader's message), and for a header
//    that is not UTF-8 (the parser's "last read: ..."). encode_header now
//    sends such bytes as U+FFFD.
// 2. Array::element_count() of a decoded empty array with huge extents
//    before its zero ([2^32, 2^31, 0] as u8: 0 bytes, so decode accepts it)
//    overflowed int64 (undefined behaviour, reported by UBSan).
#include <gtest/gtest.h>

#include <string>

#include "codec_test_support.hpp"
#include "dfc/common/config_reader.hpp"
#include "dfc/protocol/server_session.hpp"
#include "scripted_backend.hpp"

namespace dfc::protocol::testing {
namespace {

const std::string kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

/// The reply as the client receives it: encoded by the server, decoded.
Message as_received(const Message& reply) {
  Message received;
  EXPECT_NO_THROW(received = round_trip(reply)) << "a reply must always be encodable";
  return received;
}

TEST(CodecEncodeHeader, SendsBytesThatAreNotUtf8AsReplacementCharacters) {
  Message message = make_error(3, ErrorCode::bad_config, "got \"x\xC3\xA9\xC3...", "side");
  message.body["raw"] = std::string("\xFF\xFE", 2);
  const Message received = as_received(message);
  EXPECT_EQ(received.body.at("message").get<std::string>(), "got \"x\xC3\xA9" + kReplacement + "...");
  EXPECT_EQ(received.body.at("raw").get<std::string>(), kReplacement + kReplacement);
  EXPECT_EQ(received.body.at("key"), "side");
}

TEST(ServerSessionReplies, ToAConfigureWhoseBadValueIsCutInsideACharacterCanBeSent) {
  ScriptedBackend backend;
  backend.on_configure = [](const nlohmann::json& section) {
    ConfigReader config(section, "");
    (void)config.integer("side", 2, 2);
  };
  ServerSession session(backend, Limits{});
  Message hello;
  hello.type = std::string(type::hello);
  ASSERT_EQ(session.handle(hello).type, type::hello_ok);
  // ConfigReader quotes at most 40 bytes of a bad value: "x" then 2-byte
  // characters puts the cut inside one.
  std::string value = "x";
  for (int k = 0; k < 30; ++k) value += "\xC3\xA9";  // é
  Message configure;
  configure.type = std::string(type::configure);
  configure.seq = 1;
  configure.body = {{"section_json", nlohmann::json{{"side", value}}.dump()}};
  const Message reply = session.handle(configure);
  ASSERT_EQ(reply.type, type::error);
  EXPECT_EQ(reply.body.value("code", ""), "BAD_CONFIG");
  const Message received = as_received(reply);
  EXPECT_NE(received.body.at("message").get<std::string>().find("side"), std::string::npos);
}

TEST(ServerSessionReplies, ToAHeaderThatIsNotUtf8CanBeSent) {
  ScriptedBackend backend;
  ServerSession session(backend, Limits{});
  Message reply;
  try {
    (void)decode_texts({"{\"seq\": 1, \"note\": \"\xFF\xFE\"}"});
    FAIL() << "a header that is not UTF-8 must not decode";
  } catch (const DecodeError& e) {
    reply = session.refuse_undecodable(e);
  }
  EXPECT_EQ(reply.body.value("code", ""), "BAD_MESSAGE");
  const Message received = as_received(reply);
  EXPECT_EQ(received.type, type::error);
  EXPECT_EQ(received.reply_to, std::nullopt);
}

TEST(ArrayElementCount, OfAnEmptyDecodedArrayWithHugeExtentsIsZero) {
  // Decodes: the byte size is 0. The running product 2^32 * 2^31 = 2^63 is
  // beyond int64; under -fsanitize=undefined the old count reported it.
  const Message decoded = decode_texts(
      {R"({"protocol":"dfc","version":"1.5","type":"ping","seq":0,"arrays":[{"name":"z","dtype":"u8","shape":[4294967296,2147483648,0]}]})",
       ""});
  ASSERT_EQ(decoded.arrays.size(), 1u);
  EXPECT_EQ(decoded.arrays[0].element_count(), 0);
  EXPECT_EQ((Array{"e", DType::f64, {std::int64_t(1) << 62, 4, 0}, {}}).element_count(), 0);
}

}  // namespace
}  // namespace dfc::protocol::testing
