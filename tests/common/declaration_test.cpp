// Declared sections (dfc/common/declaration.hpp): the reader takes defaults,
// bounds and choices from the declaration, refuses a parser that reads an
// undeclared key or repeats a default, and the generated --help and JSON
// Schema carry the same facts.
#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/declaration.hpp"
#include "dfc/common/json_schema.hpp"

namespace dfc {
namespace {

using P = ParameterDeclaration;
using nlohmann::json;

const SectionDeclaration& box_keys() {
  static const SectionDeclaration s{.name = "test.box", .doc = "a box", .parameters = {P::vector3("size_m", "m", "edges").positive()}};
  return s;
}

const SectionDeclaration& section() {
  static const SectionDeclaration s{
      .name = "test",
      .doc = "a test section",
      .parameters = {P::number("radius_m", "m", "radius").positive(),
                     P::number("friction", "-", "coefficient").within(Bounds{0.0, 10.0}).fallback(0.5),
                     P::integer("count", "how many").integer_within(1, 9).fallback(3),
                     P::number("top_m", "m", "top").optional("the mesh's top"),
                     P::string("type", "shape").one_of({"box", "ball"}).fallback("ball"),
                     P::strings("shows", "what to draw").one_of({"edges", "faces"}).fallback(json::array({"edges"})),
                     thread_count_declaration()},
      .selector = "type",
      .variants = {{"box", "a box", &box_keys()}, {"ball", "a ball", nullptr}},
  };
  return s;
}

std::string error_path(const json& object, const std::function<void(ConfigReader&)>& parse) {
  try {
    ConfigReader cfg(object, "s", section());
    parse(cfg);
    cfg.finish();
  } catch (const ConfigError& e) {
    return e.key_path();
  }
  return "";
}

TEST(DeclaredReader, DefaultsAndBoundsComeFromTheDeclaration) {
  const json object{{"radius_m", 2.0}};
  ConfigReader cfg(object, "s", section());
  EXPECT_EQ(cfg.number("radius_m"), 2.0);
  EXPECT_EQ(cfg.number("friction"), 0.5);
  EXPECT_EQ(cfg.integer("count"), 3);
  EXPECT_EQ(cfg.string("type"), "ball");
  EXPECT_EQ(read_thread_count(cfg), 0);
  EXPECT_FALSE(cfg.has("top_m"));
  EXPECT_NO_THROW(cfg.finish());
}

TEST(DeclaredReader, BadValuesAreKeyedErrorsWithTheDeclaredBounds) {
  const auto read_all = [](ConfigReader& c) {
    (void)c.number("radius_m");
    (void)c.number("friction");
    (void)c.integer("count");
    (void)c.string("type");
  };
  EXPECT_EQ(error_path(json{{"radius_m", 0.0}}, read_all), "s.radius_m");       // > 0
  EXPECT_EQ(error_path(json{{"radius_m", 1.0}, {"friction", 11.0}}, read_all), "s.friction");
  EXPECT_EQ(error_path(json{{"radius_m", 1.0}, {"count", 10}}, read_all), "s.count");
  EXPECT_EQ(error_path(json{{"radius_m", 1.0}, {"type", "cube"}}, read_all), "s.type");
  EXPECT_EQ(error_path(json::object(), read_all), "s.radius_m");                // required
  EXPECT_EQ(error_path(json{{"radius_m", 1.0}, {"radus_m", 1.0}}, read_all), "s.radus_m");  // unknown
  // An optional key the parser needs is missing like a required one.
  EXPECT_EQ(error_path(json{{"radius_m", 1.0}}, [](ConfigReader& c) { (void)c.number("top_m"); }), "s.top_m");
}

TEST(DeclaredReader, EveryEntryOfAStringListIsOneOfItsChoices) {
  const json given{{"radius_m", 1.0}, {"shows", {"faces", "edges"}}};
  ConfigReader cfg(given, "s", section());
  EXPECT_EQ(cfg.strings("shows"), (std::vector<std::string>{"faces", "edges"}));
  const json absent{{"radius_m", 1.0}};
  ConfigReader defaults(absent, "s", section());
  EXPECT_EQ(defaults.strings("shows"), (std::vector<std::string>{"edges"}));
  // A wrong entry is named by its place, with the choices.
  const json wrong{{"radius_m", 1.0}, {"shows", {"edges", "face"}}};
  ConfigReader bad(wrong, "s", section());
  try {
    (void)bad.strings("shows");
    ADD_FAILURE() << "an unknown entry was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key_path(), "s.shows[1]");
    EXPECT_NE(std::string(e.what()).find("unknown value \"face\"; expected one of \"edges\", \"faces\""), std::string::npos) << e.what();
  }
  EXPECT_NE(describe_section(section()).find("shows  [\"edges\"|\"faces\", ...], default [\"edges\"]"), std::string::npos) << describe_section(section());
  const json schema = schema_document(section(), "test", "test")["else"]["properties"]["shows"];
  EXPECT_EQ(schema["items"]["enum"], json({"edges", "faces"}));
}

TEST(DeclaredReader, TheSelectorAddsItsVariantsKeys) {
  const json box{{"radius_m", 1.0}, {"type", "box"}, {"size_m", {1.0, 2.0, 3.0}}};
  ConfigReader cfg(box, "s", section());
  (void)cfg.number("radius_m");
  EXPECT_EQ(cfg.string("type"), "box");
  EXPECT_EQ(cfg.vec3("size_m")[2], 3.0);
  EXPECT_NO_THROW(cfg.finish());
  // A ball has no size_m: the parser asking for it is a bug.
  const json ball{{"radius_m", 1.0}};
  ConfigReader ball_cfg(ball, "s", section());
  (void)ball_cfg.string("type");
  EXPECT_THROW((void)ball_cfg.vec3("size_m"), std::logic_error);
}

TEST(DeclaredReader, AParserThatReadsAnUndeclaredKeyOrRepeatsADefaultIsABug) {
  const json object{{"radius_m", 1.0}};
  ConfigReader cfg(object, "s", section());
  EXPECT_THROW((void)cfg.number("height_m"), std::logic_error);
  EXPECT_THROW((void)cfg.has("height_m"), std::logic_error);
  EXPECT_THROW((void)cfg.number("friction", 0.5, Bounds{0.0, 10.0}), std::logic_error);
  EXPECT_THROW((void)cfg.number("radius_m", kPositive), std::logic_error);
  EXPECT_THROW((void)cfg.integer("count", 3, 1), std::logic_error);
  EXPECT_THROW((void)cfg.string("type", "ball"), std::logic_error);
  EXPECT_THROW((void)cfg.boolean("radius_m"), std::logic_error);  // declared as a number
}

TEST(DeclaredReader, HelpListsEveryKeyWithUnitBoundsAndDefault) {
  const std::string help = describe_section(section());
  for (const char* expected : {"radius_m [m]  number, > 0, required: radius", "friction [-]  number, in [0, 10], default 0.5",
                               "count  integer, in [1, 9], default 3", "top_m [m]  number, optional (absent: the mesh's top)",
                               "type \"box\": a box", "size_m [m]  [x,y,z], > 0, required"})
    EXPECT_NE(help.find(expected), std::string::npos) << expected << "\n" << help;
}

TEST(DeclaredSchema, CarriesTypesBoundsDefaultsAndTheVariantsKeys) {
  const json document = schema_document(section(), "test", "test");
  EXPECT_EQ(document["$schema"], "https://json-schema.org/draft/2020-12/schema");
  // A document that includes a file is a patch of it (no key required, at any
  // depth); any other is the complete section.
  EXPECT_EQ(document["if"]["required"], json({"include"}));
  EXPECT_EQ(document["then"]["$ref"], "#/$defs/test.patch");
  EXPECT_FALSE(document["$defs"]["test.patch"].contains("required"));
  const json& schema = document["else"];
  const json& radius = schema["properties"]["radius_m"];
  EXPECT_EQ(radius["type"], "number");
  EXPECT_EQ(radius["exclusiveMinimum"], 0.0);
  EXPECT_EQ(radius["x-unit"], "m");
  EXPECT_EQ(schema["properties"]["friction"]["default"], 0.5);
  EXPECT_EQ(schema["properties"]["friction"]["maximum"], 10.0);
  EXPECT_EQ(schema["properties"]["count"]["type"], json({"integer", "null"}));
  // A key that may be absent may be null (a JSON Merge Patch removes it that
  // way, e.g. "variants": null); a required key may not.
  EXPECT_EQ(schema["properties"]["type"]["enum"], json({"box", "ball", nullptr}));
  EXPECT_EQ(schema["properties"]["friction"]["type"], json({"number", "null"}));
  EXPECT_EQ(schema["required"], json({"radius_m"}));
  EXPECT_EQ(schema["unevaluatedProperties"], false);
  // The box variant adds size_m, required, when type is "box".
  bool box_found = false;
  for (const json& condition : schema["allOf"])
    if (condition.contains("if") && condition["if"].contains("properties") && condition["if"]["properties"]["type"]["const"] == "box") {
      box_found = true;
      EXPECT_EQ(condition["then"]["properties"]["size_m"]["minItems"], 3);
      EXPECT_EQ(condition["then"]["required"], json({"size_m"}));
    }
  EXPECT_TRUE(box_found);
}

}  // namespace
}  // namespace dfc
