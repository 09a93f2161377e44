// Scenario variants (coupler/include/dfc/coupler/scenario_variants.hpp): one
// file, several runs, each the base with an RFC 7386 merge patch.
#include <gtest/gtest.h>

#include "dfc/common/errors.hpp"
#include "dfc/coupler/scenario.hpp"
#include "dfc/coupler/scenario_variants.hpp"

namespace dfc::coupler {
namespace {

nlohmann::json base() {
  return {{"schema_version", 1},
          {"name", "ucs"},
          {"participants", {{"dem", {{"program", "/bin/true"}, {"config", {{"upscaling", {{"scale_factor", 1}}}, {"threads", 1}}}}}}},
          {"run", {{"exchanges", 100}}},
          {"output", {{"directory", "out/ucs"}}}};
}

std::string error_key(const nlohmann::json& document) {
  try {
    for (const auto& v : expand_variants(document)) (void)parse_scenario(v.document, "s.json", "");
  } catch (const ConfigError& e) {
    return e.key_path();
  }
  return "(no error)";
}

TEST(ScenarioVariants, WithoutVariantsTheScenarioIsOneRunUnchanged) {
  const auto runs = expand_variants(base());
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_TRUE(runs[0].label.empty());
  EXPECT_EQ(runs[0].document, base());
}

TEST(ScenarioVariants, EachPatchMergesIntoTheBaseAndNamesItsRun) {
  auto d = base();
  d["variants"] = {{{"label", "S1"}},
                   {{"label", "S2"}, {"patch", {{"participants", {{"dem", {{"config", {{"upscaling", {{"scale_factor", 2}}}}}}}}}, {"run", {{"exchanges", 50}}}}}}};
  const auto runs = expand_variants(d);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].label, "S1");
  EXPECT_EQ(runs[0].document.at("name"), "ucs_S1");
  EXPECT_FALSE(runs[0].document.contains("variants"));
  EXPECT_EQ(runs[0].document.at("/participants/dem/config/upscaling/scale_factor"_json_pointer), 1);
  EXPECT_EQ(runs[1].document.at("/participants/dem/config/upscaling/scale_factor"_json_pointer), 2);
  EXPECT_EQ(runs[1].document.at("/participants/dem/config/threads"_json_pointer), 1);  // merged, not replaced
  EXPECT_EQ(runs[1].document.at("/run/exchanges"_json_pointer), 50);
  const Scenario s = parse_scenario(runs[1].document, "s.json", "");
  EXPECT_EQ(s.name, "ucs_S2");
  EXPECT_EQ(s.output_directory, std::filesystem::path("out/ucs/S2"));
  EXPECT_EQ(s.run.exchanges, 50);
}

TEST(ScenarioVariants, WithoutOutputDirectoryResultsGoUnderTheBaseName) {
  auto d = base();
  d.erase("output");
  d["variants"] = {{{"label", "a"}}};
  const Scenario s = parse_scenario(expand_variants(d)[0].document, "s.json", "");
  EXPECT_EQ(s.output_directory, std::filesystem::path("results/ucs/a"));
}

TEST(ScenarioVariants, MalformedListsNameTheKey) {
  auto d = base();
  d["variants"] = nlohmann::json::array();
  EXPECT_EQ(error_key(d), "variants");
  d["variants"] = {{{"label", "a b"}}};
  EXPECT_EQ(error_key(d), "variants[0].label");
  // ".." would put the variant's results in the folder above output.directory.
  d["variants"] = {{{"label", ".."}}};
  EXPECT_EQ(error_key(d), "variants[0].label");
  d["variants"] = {{{"label", "a"}}, {{"label", "a"}}};
  EXPECT_EQ(error_key(d), "variants[1].label");
  d["variants"] = {{{"label", "a"}, {"patch", 3}}};
  EXPECT_EQ(error_key(d), "variants[0].patch");
  d["variants"] = {{{"label", "a"}, {"pach", nlohmann::json::object()}}};
  EXPECT_EQ(error_key(d), "variants[0].pach");
  // A patch that breaks the scenario is reported at the scenario's key.
  d["variants"] = {{{"label", "a"}, {"patch", {{"run", {{"exchanges", -1}}}}}}};
  EXPECT_EQ(error_key(d), "run.exchanges");
}

}  // namespace
}  // namespace dfc::coupler
