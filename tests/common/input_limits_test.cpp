// Limits on input from outside (issue 20, "defects found by probing from
// outside"): JSON nesting, duplicate keys and out-of-range numbers are refused
// with the key path; durations cannot overflow; command-line values and
// thread counts are checked and named.
#include <gtest/gtest.h>

#include <string>

#include "dfc/common/command_line.hpp"
#include "dfc/common/config_reader.hpp"
#include "dfc/common/durations.hpp"
#include "dfc/common/json_text.hpp"

namespace dfc {
namespace {

JsonTextError parse_error_of(const std::string& text, JsonTextLimits limits = {}) {
  try {
    (void)parse_json_text(text, limits);
  } catch (const JsonTextError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted: " << text.substr(0, 200);
  return JsonTextError(JsonTextError::Kind::syntax, "", "");
}

TEST(JsonText, NestingFarBeyondTheLimitIsRefusedWithItsPathNotACrash) {
  // 400 000 levels in a note killed the coupler with a stack overflow.
  const std::string deep = R"({"_note": [)" + std::string(400'000, '[') + std::string(400'000, ']') + "]}";
  const JsonTextError error = parse_error_of(deep);
  EXPECT_EQ(error.kind(), JsonTextError::Kind::too_deep);
  EXPECT_EQ(error.key_path().rfind("_note[0][0]", 0), 0u) << error.key_path();
  EXPECT_NE(error.reason().find(std::to_string(kMaxJsonNesting)), std::string::npos) << error.reason();
}

TEST(JsonText, NestingAtTheLimitIsAccepted) {
  const std::string at_limit = std::string(kMaxJsonNesting, '[') + std::string(kMaxJsonNesting, ']');
  EXPECT_NO_THROW((void)parse_json_text(at_limit));
  EXPECT_EQ(parse_error_of("[" + at_limit + "]").kind(), JsonTextError::Kind::too_deep);
}

TEST(JsonText, DepthIsCountedOutsideStringsOnly) {
  // parse_json_text measures the depth before parsing (its fast path): brackets
  // inside strings do not nest, and an escaped quote or backslash must not make
  // the count lose track of where a string ends.
  const std::string brackets_in_a_string = R"({"note": ")" + std::string(1000, '[') + R"("})";
  EXPECT_NO_THROW((void)parse_json_text(brackets_in_a_string));
  const std::string too_deep = std::string(kMaxJsonNesting, '[') + std::string(kMaxJsonNesting, ']');
  for (const std::string& string_before : {std::string(R"("\\")"), std::string(R"("\"[")"), std::string(R"("a\\\"]]]")")}) {
    const std::string text = "[" + string_before + ", " + too_deep + "]";
    EXPECT_EQ(parse_error_of(text).kind(), JsonTextError::Kind::too_deep) << text.substr(0, 40);
  }
  // Unbalanced closing brackets, or a string never closed, are syntax errors named as such.
  EXPECT_EQ(parse_error_of("]]]" + too_deep).kind(), JsonTextError::Kind::syntax);
  EXPECT_EQ(parse_error_of(R"(["unclosed)").kind(), JsonTextError::Kind::syntax);
}

TEST(JsonText, DuplicateKeysAreRefusedWithTheKeyPathWhenAsked) {
  const std::string text = R"({"run": {"exchanges": 1}, "list": [{}, {"a": 1, "b": {"c": 1, "c": 2}}]})";
  const JsonTextError error = parse_error_of(text, JsonTextLimits{.reject_duplicate_keys = true});
  EXPECT_EQ(error.kind(), JsonTextError::Kind::duplicate_key);
  EXPECT_EQ(error.key_path(), "list[1].b.c");
  // Same key in different objects is fine; without the option the last one wins, as before.
  EXPECT_NO_THROW((void)parse_json_text(R"({"a": {"x": 1}, "b": {"x": 2}})", JsonTextLimits{.reject_duplicate_keys = true}));
  EXPECT_EQ(parse_json_text(R"({"a": 1, "a": 2})").at("a"), 2);
}

TEST(JsonText, NumberBeyondADoubleIsRefusedWithItsKey) {
  const JsonTextError error = parse_error_of(R"({"gravity": {"g_m_s2": 9.81, "g_level": 1e999}})");
  EXPECT_EQ(error.kind(), JsonTextError::Kind::number_out_of_range);
  EXPECT_EQ(error.key_path(), "gravity.g_level");
  EXPECT_NE(error.reason().find("1e999"), std::string::npos) << error.reason();
}

TEST(JsonText, SyntaxErrorsAreSyntax) { EXPECT_EQ(parse_error_of("{not json").kind(), JsonTextError::Kind::syntax); }

TEST(JsonText, ReadableDumpStaysWithinAFixedMultipleOfTheCompactForm) {
  // A 42 kB scenario nested deep grew to 800 MB indented; at the nesting
  // limit a large array of numbers is the worst case left.
  nlohmann::json value = nlohmann::json::array();
  for (int i = 0; i < 100'000; ++i) value.push_back(i);
  for (std::size_t level = 1; level < kMaxJsonNesting; ++level) {
    nlohmann::json outer = nlohmann::json::array();
    outer.push_back(std::move(value));
    value = std::move(outer);
  }
  const std::size_t compact = value.dump().size();
  EXPECT_LE(readable_json(value).size(), 2 * compact);  // 130x indented
  // Small documents stay indented for people.
  EXPECT_EQ(readable_json(nlohmann::json{{"a", 1}}), "{\n  \"a\": 1\n}");
}

TEST(Durations, HugeAndInvalidSecondsSaturateInsteadOfOverflowing) {
  using std::chrono::milliseconds;
  EXPECT_EQ(milliseconds_from_seconds(1.5), milliseconds(1500));
  EXPECT_EQ(milliseconds_from_seconds(1e10), milliseconds(static_cast<long long>(kLongestWaitSeconds * 1000)));
  EXPECT_EQ(milliseconds_from_seconds(1e300), milliseconds(static_cast<long long>(kLongestWaitSeconds * 1000)));
  EXPECT_EQ(milliseconds_from_seconds(-1.0), milliseconds(0));
  EXPECT_EQ(milliseconds_from_seconds(std::nan("")), milliseconds(0));
  // The longest wait still fits steady_clock arithmetic with centuries to spare.
  const auto until = std::chrono::steady_clock::now() + milliseconds_from_seconds(1e300);
  EXPECT_GT(until, std::chrono::steady_clock::now());
}

TEST(CommandLine, BadNumbersNameTheOptionAndWhatItTakes) {
  try {
    (void)parse_number_option("--idle-timeout", "abc", Bounds{0.0, 100.0});
    FAIL() << "accepted 'abc'";
  } catch (const UserError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("--idle-timeout"), std::string::npos) << message;
    EXPECT_NE(message.find("'abc'"), std::string::npos) << message;
    EXPECT_NE(message.find("[0, 100]"), std::string::npos) << message;
    EXPECT_EQ(message.find("stod"), std::string::npos) << message;
  }
  EXPECT_THROW((void)parse_number_option("--idle-timeout", "5s", Bounds{0.0, 100.0}), UserError);
  EXPECT_THROW((void)parse_number_option("--idle-timeout", "1e999", Bounds{0.0, 100.0}), UserError);
  EXPECT_THROW((void)parse_number_option("--idle-timeout", "", Bounds{0.0, 100.0}), UserError);
  EXPECT_DOUBLE_EQ(parse_number_option("--idle-timeout", "2.5", Bounds{0.0, 100.0}), 2.5);
  EXPECT_THROW((void)parse_count_option("--max-array-bytes", "-5", 1, 1000), UserError);
  EXPECT_THROW((void)parse_count_option("--max-array-bytes", "12x", 1, 1000), UserError);
  EXPECT_EQ(parse_count_option("--max-array-bytes", "512", 1, 1000), 512u);
}

std::string thread_error(const nlohmann::json& section) {
  try {
    ConfigReader reader(section, "dem");
    (void)read_thread_count(reader);
  } catch (const ConfigError& e) {
    return e.key_path();
  }
  return "(no error)";
}

TEST(ThreadCount, BoundedAndNeverWrapped) {
  EXPECT_EQ(thread_error({{"threads", 100000}}), "dem.threads");      // crashed libgomp
  EXPECT_EQ(thread_error({{"threads", 4294967297LL}}), "dem.threads");  // silently became 1
  EXPECT_EQ(thread_error({{"threads", -1}}), "dem.threads");
  EXPECT_EQ(thread_error({{"threads", 18446744073709551615ULL}}), "dem.threads");
  EXPECT_EQ(thread_error({{"threads", kMaxThreads}}), "(no error)");
  EXPECT_EQ(thread_error(nlohmann::json::object()), "(no error)");
}

}  // namespace
}  // namespace dfc
