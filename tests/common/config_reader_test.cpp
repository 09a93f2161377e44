// ConfigReader: every scenario value goes through it, so its errors are what
// users see (CONTRIBUTING.md §6–7): the key path, what was expected, what was found.
#include <gtest/gtest.h>

#include <functional>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/version.hpp"

namespace dfc {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ConfigReader, ReadsValuesAndDefaults) {
  const nlohmann::json j = {{"a", 1.5}, {"n", 3}, {"flag", true}, {"name", "x"}, {"v", {1, 2, 3}}, {"sub", {{"k", 2}}}};
  ConfigReader r(j, "sec");
  EXPECT_EQ(r.number("a"), 1.5);
  EXPECT_EQ(r.number("missing", 7.0), 7.0);
  EXPECT_EQ(r.integer("n", 0), 3);
  EXPECT_TRUE(r.boolean("flag"));
  EXPECT_EQ(r.string("name"), "x");
  EXPECT_EQ(r.vec3("v")[2], 3.0);
  ConfigReader sub = r.child("sub");
  EXPECT_EQ(sub.integer("k", 0), 2);
  sub.finish();
  EXPECT_NO_THROW(r.finish());
}

TEST(ConfigReader, ErrorsNameTheKeyPathAndWhatWasExpected) {
  const nlohmann::json j = {{"size", -1.0}, {"count", 2.5}, {"law", "granite"}, {"sub", {{"x", "text"}}}};
  EXPECT_EQ(error_of([&] { (void)ConfigReader(j, "dem").positive("size"); }), "dem.size: expected a positive number, got -1");
  EXPECT_EQ(error_of([&] { (void)ConfigReader(j, "dem").integer("count", 0); }), "dem.count: expected an integer, got a number 2.5");
  EXPECT_EQ(error_of([&] { (void)ConfigReader(j, "dem").choice("law", {"linear", "soft_bond"}); }),
            "dem.law: unknown value \"granite\"; expected one of \"linear\", \"soft_bond\"");
  EXPECT_EQ(error_of([&] { (void)ConfigReader(j, "dem").child("sub").number("x"); }), "dem.sub.x: expected a finite number, got a string \"text\"");
  EXPECT_EQ(error_of([&] { (void)ConfigReader(j, "dem").number("absent"); }), "dem.absent: missing required key; expected a finite number");
  EXPECT_EQ(error_of([&] { (void)ConfigReader(j, "").number("size", Bounds{0.0, 1.0}); }), "size: expected a number in [0, 1], got -1");
}

TEST(ConfigReader, UnknownKeysAreErrorsWithASuggestion) {
  const nlohmann::json j = {{"radius", 1.0}, {"radus", 2.0}};
  ConfigReader r(j, "particles");
  (void)r.number("radius");
  EXPECT_EQ(error_of([&] { r.finish(); }), "particles.radus: unknown key; did you mean \"radius\"?");
  // Notes are allowed: "comment" and keys starting with '_'.
  const nlohmann::json notes = {{"comment", "why"}, {"_source", "paper"}};
  EXPECT_NO_THROW(ConfigReader(notes, "").finish());
}

TEST(ConfigReader, NonObjectSectionIsRejected) {
  const nlohmann::json j = nlohmann::json::array();
  EXPECT_EQ(error_of([&] { ConfigReader(j, "dem"); }), "dem: expected an object ({...}), got an array");
}

TEST(Fnv1a64, KnownVectors) {
  // Reference values of the FNV-1a 64-bit hash (SPEC.md §4.2).
  EXPECT_EQ(fnv1a64_hex(""), "cbf29ce484222325");
  EXPECT_EQ(fnv1a64_hex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(fnv1a64_hex("foobar"), "85944171f73967e8");
}

}  // namespace
}  // namespace dfc
