// `coupler check` on broken scenarios (issue check 6): every case must give one
// clear error that names the offending key path, and exit with status 2.
// Each file in tests/e2e/broken/ carries the expected key path in "_expect"
// (keys starting with '_' are free-form notes the scenario reader allows).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "e2e_paths.hpp"

namespace dfc::testing {
namespace {

std::vector<std::filesystem::path> broken_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(e2e_dir() / "broken"))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

int count_lines_starting_with(const std::string& text, const std::string& prefix) {
  int count = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0) ++count;
  return count;
}

TEST(BrokenScenarios, AtLeastTenCasesExist) { EXPECT_GE(broken_files().size(), 10u); }

TEST(BrokenScenarios, EachGivesOneErrorNamingTheKeyAndExitsTwo) {
  for (const auto& file : broken_files()) {
    SCOPED_TRACE(file.filename().string());
    std::string expected = "not valid JSON";
    const auto document = nlohmann::json::parse(read_text(file), nullptr, false);
    if (!document.is_discarded()) expected = "scenario error at " + document.at("_expect").get<std::string>() + ":";
    const CommandResult result = run_command({coupler(), "check", file.string()}, std::chrono::seconds(30));
    EXPECT_EQ(result.exit_status, 2) << result.output;
    EXPECT_NE(result.output.find(expected), std::string::npos) << "expected '" << expected << "' in:\n" << result.output;
    EXPECT_EQ(count_lines_starting_with(result.output, "coupler:"), 1) << result.output;
  }
}

}  // namespace
}  // namespace dfc::testing
