// info.progress_monitors (SPEC.md §4.2, protocol 1.5): what is accepted, what
// is refused with the entry named, and how the coupler's line is written.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "dfc/protocol/progress_monitors.hpp"

namespace dfc::protocol {
namespace {

TEST(ProgressMonitors, AbsentListIsEmpty) {
  EXPECT_TRUE(parse_progress_monitors(nlohmann::json::object()).empty());
  EXPECT_TRUE(parse_progress_monitors(nlohmann::json()).empty());
}

TEST(ProgressMonitors, RoundTripKeepsOrderAndScale) {
  const std::vector<ProgressMonitor> entries = {{"pile_displacement_m", "pile", 1e3, "mm"}, {"pile_force_n", "force", 1.0, "N"}};
  const auto parsed = parse_progress_monitors({{progress_monitors_key, to_json(entries)}});
  ASSERT_EQ(parsed.size(), 2u);
  EXPECT_EQ(parsed[0].monitor, "pile_displacement_m");
  EXPECT_EQ(parsed[0].scale, 1e3);
  EXPECT_EQ(parsed[1].unit, "N");
}

TEST(ProgressMonitors, ScaleDefaultsToOne) {
  const auto parsed = parse_progress_monitors({{progress_monitors_key, {{{"monitor", "m"}, {"label", "x"}, {"unit", "m"}}}}});
  ASSERT_EQ(parsed.size(), 1u);
  EXPECT_EQ(parsed[0].scale, 1.0);
}

// Each malformed list is refused with the entry and key named.
TEST(ProgressMonitors, MalformedEntriesAreRefusedNamingTheKey) {
  const auto refusal = [](const nlohmann::json& list) {
    try {
      (void)parse_progress_monitors({{progress_monitors_key, list}});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refusal({{"not", "an array"}}).find("must be an array"), std::string::npos);
  EXPECT_NE(refusal({42}).find("progress_monitors[0].monitor"), std::string::npos);
  EXPECT_NE(refusal({{{"monitor", ""}, {"label", "x"}, {"unit", "m"}}}).find("[0].monitor must be a non-empty string"), std::string::npos);
  EXPECT_NE(refusal({{{"monitor", "a"}, {"label", 3}, {"unit", "m"}}}).find("[0].label"), std::string::npos);
  EXPECT_NE(refusal({{{"monitor", "a"}, {"label", "x"}, {"unit", "m"}, {"scale", 0}}}).find("[0].scale"), std::string::npos);
  EXPECT_NE(refusal({{{"monitor", "a"}, {"label", "x"}, {"unit", "m"}}, {{"monitor", "b"}, {"label", "y"}}}).find("[1].unit"),
            std::string::npos);
}

TEST(ProgressMonitors, FormatShowsScaledValuesAndSkipsMissingOrNull) {
  const std::vector<ProgressMonitor> entries = {
      {"pile_displacement_m", "pile", 1e3, "mm"}, {"absent", "gone", 1.0, "N"}, {"unknown", "null", 1.0, "N"}, {"pile_force_n", "force", 1.0, "N"}};
  const nlohmann::json monitors = {{"pile_displacement_m", 0.003}, {"unknown", nullptr}, {"pile_force_n", 93.61}};
  EXPECT_EQ(format_progress(entries, monitors), "pile 3 mm, force 93.6 N");
  EXPECT_EQ(format_progress(entries, nlohmann::json::object()), "");
}

}  // namespace
}  // namespace dfc::protocol
