// Echoed input stays readable (issue 42, part 5): a value from outside quoted
// in an error is cut to a readable length and its length is stated, wherever
// the error is raised (ConfigReader, the JSON reader).
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/echo.hpp"
#include "dfc/common/json_text.hpp"

namespace dfc {
namespace {

const std::string kHuge(200'000, 'k');  // the 200 kB key of the issue

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Echoed, ShortValuesAreUnchanged) {
  EXPECT_EQ(echoed("radius_m"), "radius_m");
  EXPECT_EQ(echoed(std::string(kMaxEchoBytes, 'x')), std::string(kMaxEchoBytes, 'x'));
  EXPECT_EQ(echoed(""), "");
}

TEST(Echoed, LongValuesAreCutAndTheirLengthStated) {
  const std::string cut = echoed(kHuge);
  EXPECT_LE(cut.size(), kMaxEchoBytes);
  EXPECT_EQ(cut.rfind("kkkk", 0), 0u) << cut;  // it begins as the value does
  EXPECT_NE(cut.find("(200000 bytes)"), std::string::npos) << cut;
  const std::string one_over = echoed(std::string(kMaxEchoBytes + 1, 'x'));
  EXPECT_LE(one_over.size(), kMaxEchoBytes);
  EXPECT_NE(one_over.find("(81 bytes)"), std::string::npos) << one_over;
  // Echoing an echo (a server's error passed on by the coupler) keeps the first length.
  EXPECT_EQ(echoed(cut), cut);
  EXPECT_LE(echoed(kHuge, kMaxEchoedPathBytes).size(), kMaxEchoedPathBytes);
}

TEST(Echoed, ACutNeverSplitsAUtf8Character) {
  // "é" is two bytes: wherever the cut falls, no lone lead or continuation byte remains before "…".
  for (std::size_t prefix = 0; prefix < 4; ++prefix) {
    std::string value(prefix, 'a');
    for (int i = 0; i < 100; ++i) value += "\xC3\xA9";
    const std::string cut = echoed(value);
    const std::string kept = cut.substr(0, cut.find("\xE2\x80\xA6"));
    ASSERT_GE(kept.size(), prefix);
    EXPECT_EQ((kept.size() - prefix) % 2, 0u) << "cut inside a character at prefix " << prefix;
  }
}

TEST(Echoed, AnUnknownKey200kBLongIsNamedInAReadableError) {
  const nlohmann::json section = {{"radius", 1.0}, {kHuge, 2.0}};
  const std::string message = error_of([&] {
    ConfigReader r(section, "particles");
    (void)r.number("radius");
    r.finish();
  });
  EXPECT_LT(message.size(), 400u) << message.substr(0, 400);
  EXPECT_EQ(message.rfind("particles.kkkk", 0), 0u) << message.substr(0, 400);
  EXPECT_NE(message.find("(200000 bytes)"), std::string::npos) << message.substr(0, 400);
  EXPECT_NE(message.find("unknown key"), std::string::npos) << message.substr(0, 400);
}

TEST(Echoed, ValuesAndTheirKeysAreCutInEveryKindOfError) {
  const nlohmann::json section = {{"law", kHuge}, {"size", kHuge}, {kHuge, {{"x", "text"}}}};
  for (const auto& read : std::vector<std::function<void()>>{
           [&] { (void)ConfigReader(section, "dem").choice("law", {"linear", "soft_bond"}); },
           [&] { (void)ConfigReader(section, "dem").number("size"); },
           [&] { (void)ConfigReader(section, "dem").child(kHuge).number("x"); },
       }) {
    const std::string message = error_of(read);
    EXPECT_LT(message.size(), 400u) << message.substr(0, 400);
    EXPECT_NE(message.find("bytes)"), std::string::npos) << message.substr(0, 400);
  }
  // The JSON reader names a duplicate key by its path.
  const std::string text = "{\"" + kHuge + "\": 1, \"" + kHuge + "\": 2}";
  const std::string duplicate = error_of([&] { (void)parse_json_text(text, JsonTextLimits{.reject_duplicate_keys = true}); });
  EXPECT_LT(duplicate.size(), 400u) << duplicate.substr(0, 400);
  EXPECT_NE(duplicate.find("(200000 bytes)"), std::string::npos) << duplicate.substr(0, 400);
}

}  // namespace
}  // namespace dfc
